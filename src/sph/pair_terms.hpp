#pragma once
// Physics of one i-j pair, shared by the operators and the solvers (SWIFT's hydro_iact idea).
#include "src/sph/pair_loop.hpp"

namespace sph {

// F_ij = r_ij . grad_i W_ij / (|r_ij|^2 + eta^2): the radial factor of the Morris et al. (1997) /
// Cummins & Rudman (1999) Laplacians (negative inside the support). eta only guards r -> 0.
// Morris' eta = 0.1 h biases every pair by eta^2/r^2, an error of the Laplacian that does not shrink
// with resolution and stalls the PPE solution's convergence, so eta = 0.01 h is used (bias ~1e-4;
// docs/pressure-solve.md, "Design measurements").
constexpr double morris_eta_over_h = 0.01;
template <int D> inline double morris_factor(const PairGeometry<D>& g, double h) {
  constexpr double eta2 = morris_eta_over_h * morris_eta_over_h;
  return g.r * g.dWdr / (g.r * g.r + eta2 * h * h);
}

// Morris et al. (1997) laminar viscous acceleration on i from j:
//   sum_j m_j (mu_i + mu_j) / (rho_i rho_j) F_ij u_ij, with mu = rho nu.
template <int D> inline Vector<D> morris_viscous_acceleration(double mj, double rho_i, double rho_j, double nu_i,
                                                              double nu_j, double F, const Vector<D>& uij) {
  return (mj * (rho_i * nu_i + rho_j * nu_j) / (rho_i * rho_j) * F) * uij;
}

}  // namespace sph
