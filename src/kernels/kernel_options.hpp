#pragma once
// The run's kernel and smoothing length from the options database (-kernel, -h_over_dx): the one place
// that knows the default h for every kernel.
#include "src/kernels/kernel.hpp"

namespace sph {

struct KernelChoice {
  KernelType type = KernelType::WendlandC2;
  double h_over_dx = -1;  // -1: the support radius is 3 dx, whatever the kernel

  // h over the particle spacing this choice gives.
  template <int D> double resolved_h_over_dx() const {
    return h_over_dx > 0 ? h_over_dx : 3.0 / Kernel<D>::support_factor(type);
  }
  template <int D> Kernel<D> make(double dx) const { return Kernel<D>(type, resolved_h_over_dx<D>() * dx); }
};

// Reads -kernel and -h_over_dx (a PETSc options block: -help lists them) and checks them. A scheme's
// own default pair (Solver::default_kernel) holds only when neither option is given: a kernel and its
// h go together, so either option alone takes the general default for the other.
KernelChoice read_kernel_options(const KernelChoice& scheme_default = KernelChoice{});

}  // namespace sph
