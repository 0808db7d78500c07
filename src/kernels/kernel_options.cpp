#include "src/kernels/kernel_options.hpp"

#include <petscsys.h>

#include "src/core/error.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* kernel, PetscReal* h_over_dx, PetscBool* kernel_set, PetscBool* h_set) {
  PetscFunctionBeginUser;
  std::vector<const char*> kernels;
  for (const auto& k : kernel_names()) kernels.push_back(k.c_str());
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Smoothing kernel", "sph");
  PetscCall(option_choice(PetscOptionsObject, "-kernel",
                          "Smoothing kernel (WCSPH with a free surface, when neither this nor -h_over_dx is "
                          "given: quintic_spline at -h_over_dx 0.93, where its square lattice is stable)",
                          kernels.data(), static_cast<PetscInt>(kernels.size()), kernels[*kernel], kernel, kernel_set));
  PetscCall(option_real(PetscOptionsObject, "-h_over_dx",
                        "Smoothing length over particle spacing (-1: support radius 3 dx)", *h_over_dx, h_over_dx,
                        h_set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

KernelChoice read_kernel_options(const KernelChoice& scheme_default) {
  KernelChoice choice;
  PetscInt kernel = static_cast<PetscInt>(choice.type);
  PetscReal h_over_dx = choice.h_over_dx;
  PetscBool kernel_set = PETSC_FALSE, h_set = PETSC_FALSE;
  SPH_PETSC(read_options(&kernel, &h_over_dx, &kernel_set, &h_set));
  require(h_over_dx == -1 || h_over_dx > 0, "-h_over_dx", "positive", h_over_dx);
  if (!kernel_set && !h_set) return scheme_default;
  choice.type = static_cast<KernelType>(kernel);
  choice.h_over_dx = h_over_dx;
  return choice;
}

}  // namespace sph
