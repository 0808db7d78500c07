#pragma once
// What the operator tests share: the kernel choices, the periodic lattice and the disordered open
// patch they run on, and the analytic fields they sample.
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "src/core/domain.hpp"
#include "src/kernels/kernel.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/particles/particles.hpp"

namespace sph::test {

using V2 = Vector<2>;
using T2 = Tensor<2>;

inline constexpr double kRho0 = 1000.0;
inline constexpr double k2pi = 2.0 * M_PI;

// Kernel choices with support 3 dx; the truncated Gaussian gets 3.3 dx, so that no lattice neighbour
// sits exactly on its cut-off, where it jumps (e^-9 W(0)) and round-off would pick sides at random.
struct KernelCase {
  KernelType type;
  double h_over_dx;
};
inline const KernelCase kCases[] = {{KernelType::WendlandC2, 1.5},
                                    {KernelType::CubicSpline, 1.5},
                                    {KernelType::QuinticSpline, 1.0},
                                    {KernelType::WendlandC4, 1.5},
                                    {KernelType::Gaussian, 1.1}};

// nx^2 particles at cell centres of the periodic unit square, m = rho0 dx^2, rho = rho0, with ghosts
// and neighbour lists built by a Neighbourhood.
struct Lattice {
  double dx;
  Domain<2> domain;
  Kernel<2> K;
  Particles<2> P;
  std::unique_ptr<Neighbourhood<2>> nh;

  Lattice(int nx, const KernelCase& kc) : dx(1.0 / nx), K(kc.type, kc.h_over_dx / nx) {
    domain.periodic = {true, true};
    for (int k = 0; k < nx * nx; ++k) {
      P.add(V2((k % nx + 0.5) * dx, (k / nx + 0.5) * dx), V2::Zero(), kRho0 * dx * dx, kRho0);
      P.gid.back() = k;
    }
    P.n_global = nx * nx;
    nh = std::make_unique<Neighbourhood<2>>(domain, K.support_radius(), 0.0);
    nh->update(P, true);
  }
  const NeighbourList<2>& nl() const { return nh->list(); }

  // Samples g at the owned particles; the ghost slots are filled by the halo.
  template <class T> std::vector<T> sample(const std::function<T(const V2&)>& g) const {
    std::vector<T> v(P.n_owned);
    for (std::size_t i = 0; i < P.n_owned; ++i) v[i] = g(P.x[i]);
    nh->halo().update(v);
    return v;
  }
};

inline double f_s(const V2& x) { return std::sin(k2pi * x[0]) * std::sin(k2pi * x[1]); }
inline V2 grad_f_s(const V2& x) {
  return k2pi * V2(std::cos(k2pi * x[0]) * std::sin(k2pi * x[1]), std::sin(k2pi * x[0]) * std::cos(k2pi * x[1]));
}
inline double lap_f_s(const V2& x) { return -2.0 * k2pi * k2pi * f_s(x); }
// Solenoidal (Taylor-Green) field and its Laplacian.
inline V2 u_tg(const V2& x) {
  return V2(std::sin(k2pi * x[0]) * std::cos(k2pi * x[1]), -std::cos(k2pi * x[0]) * std::sin(k2pi * x[1]));
}
inline V2 lap_u_tg(const V2& x) { return -2.0 * k2pi * k2pi * u_tg(x); }
// Non-solenoidal field and its divergence.
inline V2 w_ns(const V2& x) { return V2(std::sin(k2pi * x[0]), std::sin(k2pi * x[1])); }
inline double div_w_ns(const V2& x) { return k2pi * (std::cos(k2pi * x[0]) + std::cos(k2pi * x[1])); }

inline std::string label(const KernelCase& kc) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s (h = %.1f dx)", kernel_names()[static_cast<int>(kc.type)].c_str(), kc.h_over_dx);
  return buf;
}

// ---------------------------------------------------------------------------------------------
// Disordered open patch: exactness that holds on any particle distribution.

struct Patch {
  Domain<2> domain;  // [0, 1]^2, not periodic: no ghosts
  Kernel<2> K;
  Particles<2> P;
  std::unique_ptr<Neighbourhood<2>> nh;

  Patch(int nx, const KernelCase& kc) : K(kc.type, kc.h_over_dx / nx) {
    const double dx = 1.0 / nx;
    std::mt19937 gen(2024);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2), vary(0.8, 1.2);
    for (int k = 0; k < nx * nx; ++k) {
      const V2 x((k % nx + 0.5 + jitter(gen)) * dx, (k / nx + 0.5 + jitter(gen)) * dx);
      // Masses and densities vary too, so that the volumes V_j = m_j / rho_j differ.
      P.add(x, V2::Zero(), kRho0 * dx * dx * vary(gen), kRho0 * vary(gen));
      P.gid.back() = k;
    }
    P.n_global = nx * nx;
    nh = std::make_unique<Neighbourhood<2>>(domain, K.support_radius(), 0.0);
    nh->update(P, true);
  }
  const NeighbourList<2>& nl() const { return nh->list(); }
};

}  // namespace sph::test
