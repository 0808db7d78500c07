#pragma once
// Pair physics of weakly-compressible SPH (one i-j interaction each; the loops live in the solver).
#include <cmath>

#include "src/sph/artificial_viscosity.hpp"
#include "src/sph/pair_terms.hpp"

namespace sph::wcsph {

// Tait equation of state (Batchelor 1967; Monaghan 1994): p = B ((rho/rho0)^gamma - 1), B = c0^2 rho0 / gamma.
struct TaitEos {
  double rho0 = 1.0, c0 = 10.0, gamma = 7.0;
  double B() const { return c0 * c0 * rho0 / gamma; }
  double pressure(double rho) const { return B() * (std::pow(rho / rho0, gamma) - 1.0); }
  double density(double p) const { return rho0 * std::pow(1.0 + p / B(), 1.0 / gamma); }
  double sound_speed(double rho) const { return c0 * std::pow(rho / rho0, 0.5 * (gamma - 1.0)); }
};

// Continuity: d rho_i/dt += rho_i V_j u_ij . grad_i W_ij.
template <int D>
inline double continuity_pair(double rho_i, double Vj, const Vector<D>& uij, const PairGeometry<D>& g) {
  return rho_i * Vj * uij.dot(g.gradW);
}

// Molteni & Colagrossi (2009) density diffusion: delta h c0 sum_j psi_ij . grad_i W_ij V_j with
// psi_ij = 2 (rho_j - rho_i) (x_j - x_i) / |x_j - x_i|^2, i.e. delta h c0 times a Morris Laplacian of rho.
// Antuono et al. (2010) subtract the part a linear density field would give: (G_i + G_j) . grad_i W_ij V_j
// with G the corrected density gradient, so hydrostatic stratification is not diffused.
template <int D>
inline double density_diffusion_pair(double delta_h_c0, double rho_i, double rho_j, double Vj, double F,
                                     const Vector<D>& Gi, const Vector<D>& Gj, const PairGeometry<D>& g) {
  return delta_h_c0 * Vj * (-2.0 * (rho_j - rho_i) * F - (Gi + Gj).dot(g.gradW));
}

// Monaghan (1992) artificial viscosity Pi_ij (only for approaching pairs) with WCSPH's sound speeds.
struct MonaghanAV {
  double alpha = 0.0, beta = 0.0, epsilon = 0.01;
  bool active() const { return alpha > 0.0 || beta > 0.0; }
  // The sound speeds come from the equation of state, and only for approaching pairs: std::pow.
  template <int D>
  double Pi(double h, const TaitEos& eos, double rho_i, double rho_j, const Vector<D>& uij,
            const PairGeometry<D>& g) const {
    const double ur = uij.dot(g.rij);
    if (ur >= 0.0) return 0.0;
    const double c_mean = 0.5 * (eos.sound_speed(rho_i) + eos.sound_speed(rho_j));
    return monaghan_viscosity(alpha, beta, epsilon, h, c_mean, 0.5 * (rho_i + rho_j), ur, g.r);
  }
};

// Momentum-conserving pressure (+ artificial viscosity) acceleration on i from j.
template <int D>
inline Vector<D> pressure_acceleration_pair(double mj, double pi, double pj, double rho_i, double rho_j,
                                            double Pi_ij, const PairGeometry<D>& g) {
  return (-mj * (pi / (rho_i * rho_i) + pj / (rho_j * rho_j) + Pi_ij)) * g.gradW;
}

}  // namespace sph::wcsph
