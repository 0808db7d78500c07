#pragma once
// Particle shifting (Lind, Xu, Stansby & Rogers 2012; Skillen et al. 2013): particles drift down the
// gradient of particle concentration, dr_i = -D grad C_i, which keeps the distribution near-uniform
// (avoiding the clustering and voids that ruin Lagrangian SPH), and fields are Taylor-corrected to the
// shifted positions.
//
// D = A h^2 per step (the Fickian form). Lind et al. write D = A_L h U_max dt; at the advective step
// dt = CFL h / U_max the two agree with A = A_L CFL. We measured on the Taylor-Green vortex (Re 100)
// that what matters is the shift per step, not per unit time, in both schemes:
//  - ISPH, nx 64: with A_L = 2, halving dt from CFL 0.2 to 0.1 tripled the velocity error
//    (0.17% -> 0.59%); doubling A_L at CFL 0.1 restored it (0.22%); A_L = 4 at CFL 0.2 (A = 0.8) blew up.
//  - WCSPH, nx 32 (dt ten times smaller than ISPH's): A_L = 2 gave 12% error, A_L = 20 (A ~ 0.45) 0.66%.
// The disorder shifting removes is made per step, so the per-step form also keeps working when dt is
// set by the viscous or acoustic limit. Stable up to A ~ 0.5.
//   grad C_i = sum_j V_j [1 + R (W_ij / W(dx))^n] grad_i W_ij  (R = 0.2, n = 4: the tensile-instability
//   term of Monaghan 2000 that Lind et al. add to stop pairing).
#include <vector>

#include <nlohmann/json.hpp>

#include "src/neighbours/neighbourhood.hpp"
#include "src/run/log_events.hpp"
#include "src/sph/operators.hpp"

namespace sph {

// x^n for a small exponent n >= 0 by repeated squaring: std::pow cost 5% of an ISPH step here.
inline double integer_power(double x, int n) {
  double result = 1.0;
  for (; n > 0; n >>= 1, x *= x)
    if (n & 1) result *= x;
  return result;
}

struct LindShifting {
  double A = 0.4;   // D = A h^2 per step
  double R = 0.2;   // tensile-correction strength
  int n = 4;        // tensile-correction exponent

  nlohmann::json describe() const { return {{"model", "LindShifting"}, {"A", A}, {"R", R}, {"n", n}}; }
};

// Shifts the owned particles by -D grad C (on free-surface particles only along the surface: the
// normal part, n = -grad C / |grad C|, is removed, Lind et al. 2012) and Taylor-corrects the velocity,
// u + (dr . grad) u with the corrected gradient, and the listed scalar fields likewise. Positions must
// be current in `nh`.
//
// One pair loop gathers all of it: grad C, the moment matrix of the kernel-gradient correction and the
// uncorrected gradients of u and of the scalars. As separate operators (correction_matrices,
// vector_gradient_corrected, gradient_corrected) these were one loop each, and traversing the pairs,
// not the arithmetic, is the cost: the fused loop gives each sum bitwise the same terms in the same
// order (tests/test_operators.cpp), at 0.4x the time.
template <int D>
void shift_particles(Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K, const LindShifting& model,
                     double dx, const std::vector<std::vector<double>*>& scalars = {},
                     const std::vector<char>* surface = nullptr) {
  const LogEventScope log_shifting(LogEvent::Shifting);
  const NeighbourList<D>& nl = nh.list();
  const std::size_t n = P.n_owned;
  std::vector<Vector<D>> dr(n, Vector<D>::Zero());
  std::vector<Tensor<D>> L(n, Tensor<D>::Zero()), grad_u(n, Tensor<D>::Zero());
  std::vector<std::vector<Vector<D>>> grad_f(scalars.size(), std::vector<Vector<D>>(n, Vector<D>::Zero()));
  const double W_dx = K.W(dx);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) {
    const double Vj = P.m[j] / P.rho[j];
    dr[i] += (Vj * (1.0 + model.R * integer_power(g.W / W_dx, model.n))) * g.gradW;
    L[i] += correction_moment_term(Vj, g);
    grad_u[i] += difference_vector_gradient_term(Vj, P.v[i], P.v[j], g);
    for (std::size_t k = 0; k < scalars.size(); ++k) {
      const std::vector<double>& f = *scalars[k];
      grad_f[k][i] += difference_gradient_term(Vj, f[i], f[j], g);
    }
  });
  const double Dcoef = model.A * K.h() * K.h();
  for (std::size_t i = 0; i < n; ++i) {
    dr[i] *= -Dcoef;
    L[i] = correction_from_moments(L[i]);
  }
  if (surface)
    for (std::size_t i = 0; i < n; ++i) {
      if (!(*surface)[i] || dr[i].squaredNorm() == 0.0) continue;
      const Vector<D> normal = dr[i].normalized();  // dr is along -grad C, the outward normal
      dr[i] -= normal.dot(dr[i]) * normal;
    }
  // Only fluid particles move; walls keep their place.
  for (std::size_t k = 0; k < scalars.size(); ++k)
    for (std::size_t i = 0; i < n; ++i)
      if (P.kind[i] == kFluid) (*scalars[k])[i] += Vector<D>(L[i] * grad_f[k][i]).dot(dr[i]);
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] != kFluid) continue;
    P.x[i] += dr[i];
    P.v[i] += Tensor<D>(L[i] * grad_u[i]).transpose() * dr[i];
  }
}

}  // namespace sph
