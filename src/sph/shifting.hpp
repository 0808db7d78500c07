#pragma once
// Particle shifting (Lind, Xu, Stansby & Rogers 2012; Skillen et al. 2013): particles drift down the
// gradient of particle concentration, dr_i = -D grad C_i with D = A h U_max dt, which keeps the
// distribution near-uniform (avoiding the clustering and voids that ruin Lagrangian ISPH). Fields are
// then Taylor-corrected to the new position by the solver.
//   grad C_i = sum_j V_j [1 + R (W_ij / W(dx))^n] grad_i W_ij  (R = 0.2, n = 4: the tensile-instability
//   term of Monaghan 2000 that Lind et al. add to stop pairing).
#include <vector>

#include <nlohmann/json.hpp>

#include "src/sph/pair_loop.hpp"

namespace sph {

struct LindShifting {
  double A = 2.0;   // diffusion coefficient factor (Lind et al. 2012 use 1 to 6)
  double R = 0.2;   // tensile-correction strength
  int n = 4;        // tensile-correction exponent

  template <int D>
  std::vector<Vector<D>> displacement(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                   double dx, double u_max, double dt) const {
    std::vector<Vector<D>> gradC(P.n_owned, Vector<D>::Zero());
    const double W_dx = K.W(dx);
    for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) {
      const double ratio = g.W / W_dx;
      gradC[i] += (P.m[j] / P.rho[j] * (1.0 + R * std::pow(ratio, n))) * g.gradW;
    });
    const double Dcoef = A * K.h() * u_max * dt;
    for (auto& d : gradC) d *= -Dcoef;
    return gradC;
  }

  nlohmann::json describe() const { return {{"model", "LindShifting"}, {"A", A}, {"R", R}, {"n", n}}; }
};

}  // namespace sph
