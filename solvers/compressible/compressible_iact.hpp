#pragma once
// Pair physics of compressible SPH with variable smoothing lengths (one i-j interaction each; the
// loops are the variable-h ones of src/sph/pair_loop.hpp, run by compressible_solver.cpp). Every particle carries its
// own h_i, fixed by
//   rho_i h_i^D = m_i eta^D   together with   rho_i = sum_j m_j W(r_ij, h_i),
// and the grad-h factor  Omega_i = 1 - (dh_i/drho_i) sum_j m_j dW(r_ij, h_i)/dh_i  (Springel & Hernquist
// 2002, MNRAS 333:649; Monaghan 2002; Price 2012, JCP 231:759, sec. 3). With P_i/(Omega_i rho_i^2) = q_i
//   dv_i/dt = -sum_j m_j [q_i grad_i W_ij(h_i) + q_j grad_i W_ij(h_j)]                   (Price 2012 eq. 33)
//   du_i/dt =  q_i sum_j m_j v_ij . grad_i W_ij(h_i)                                     (Price 2012 eq. 35)
// conserve momentum exactly (antisymmetric pair forces) and total energy in continuous time.
// Dissipation (artificial viscosity, conductivity) uses the mean gradient of the two kernels, so it is
// pairwise antisymmetric too, and its heating makes the total energy conserved as well.
// Kernels are the shared ones (src/kernels): a particle's kernel is Kernel<D>(type, h_i).
#include <algorithm>
#include <cmath>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"
#include "src/sph/artificial_viscosity.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph::compressible {

// ---------------------------------------------------------------------------------------------------
// Density and smoothing length.

// dW/dh at fixed r for a kernel W = sigma h^-D f(r/h):  -(D W + r dW/dr) / h.
inline double dW_dh(int D, double W, double r, double dWdr, double h) { return -(D * W + r * dWdr) / h; }

// Density from the smoothing length: rho(h) = m (eta / h)^D.
inline double density_from_h(int D, double m, double eta, double h) { return m * std::pow(eta / h, D); }

// Sums of the gather loop of particle i at its current h_i.
struct DensitySums {
  double rho = 0.0;      // sum_j m_j W(r_ij, h_i), self term included
  double drho_dh = 0.0;  // sum_j m_j dW(r_ij, h_i)/dh_i
};

// One step of the safeguarded Newton-Raphson iteration on f(h) = rho_sum(h) - m (eta/h)^D (Price 2012
// sec. 3.3). f grows with h, so each evaluation narrows a bracket [lo, hi] around the root; a Newton step
// that leaves it (or a non-positive slope) is replaced by bisection, or by a fixed-point step
// h = eta (m / rho_sum)^(1/D) limited to a factor 2 while one side is still open. Kernels with a jump
// at the support edge (the truncated Gaussian) make f discontinuous: after a number of steps the caller
// asks for plain bisection (bisect_only), which closes the bracket in ~50 halvings at most.
struct HBracket {
  double lo = 0.0, hi = 0.0;  // hi = 0: no upper bound yet
};
inline double newton_h_update(int D, double m, double eta, double h, const DensitySums& s, HBracket& b,
                              bool bisect_only = false) {
  const double rho_h = density_from_h(D, m, eta, h);
  const double f = s.rho - rho_h;
  if (f > 0.0) b.hi = h;
  else b.lo = h;
  const double df = s.drho_dh + D * rho_h / h;  // d rho_sum/dh - d rho(h)/dh
  double h_new = df > 0.0 ? h - f / df : -1.0;
  const double lo = b.lo > 0.0 ? b.lo : 0.5 * h, hi = b.hi > 0.0 ? b.hi : 2.0 * h;
  const bool bracketed = b.lo > 0.0 && b.hi > 0.0;
  if (!(h_new >= lo && h_new <= hi) || (bisect_only && bracketed)) {
    if (bracketed) {
      h_new = 0.5 * (b.lo + b.hi);
    } else {
      h_new = s.rho > 0.0 ? eta * std::pow(m / s.rho, 1.0 / D) : 2.0 * h;
      h_new = std::clamp(h_new, std::max(lo, 0.5 * h), std::min(hi, 2.0 * h));
    }
  }
  return h_new;
}

// Omega_i = 1 - (dh/drho) sum_j m_j dW/dh with dh/drho = -h / (D rho).
inline double grad_h_factor(int D, double h, const DensitySums& s) { return 1.0 + h / (D * s.rho) * s.drho_dh; }

// ---------------------------------------------------------------------------------------------------
// Forces and heating of one pair (i from j).

// Pressure acceleration on i from j; q = P / (Omega rho^2).
template <int D> inline Vector<D> pressure_acceleration(double mj, double qi, double qj, const VariableHPair<D>& g) {
  return (-mj / g.r * (qi * g.dWi + qj * g.dWj)) * g.rij;
}

// Compressional (pdV) heating of i by j.
template <int D> inline double pdv_heating(double mj, double qi, const Vector<D>& vij, const VariableHPair<D>& g) {
  return qi * mj * vij.dot(g.gradWi());
}

// Signal velocity of the pair for the time step (Monaghan 1997, JCP 136:298): c_i + c_j - 3 w_ij for
// approaching pairs (w_ij = v_ij . r_hat_ij < 0), c_i + c_j otherwise.
inline double signal_velocity(double ci, double cj, double w, double beta = 3.0) {
  return ci + cj - beta * std::min(w, 0.0);
}

enum class ViscosityModel { None, SignalVelocity, Monaghan1992 };

// Artificial viscosity Pi_ij (>= 0, non-zero for approaching pairs only). alpha_ij is the pair's alpha
// (constant, or the mean of Morris-Monaghan alphas), times the mean Balsara factor where that is on.
//  SignalVelocity (Monaghan 1997; Springel 2010, ARA&A 48:391, eq. 15):
//      Pi = -(alpha/2) v_sig w / rho_bar,  v_sig = c_i + c_j - beta w
//  Monaghan1992 (ARA&A 30:543):  Pi = (-alpha c_bar mu + beta mu^2) / rho_bar,  mu = h_bar v.r / (r^2 + eps h_bar^2)
struct ArtificialViscosity {
  ViscosityModel model = ViscosityModel::SignalVelocity;
  double alpha = 1.0, beta = 3.0, epsilon = 0.01;

  bool active() const { return model != ViscosityModel::None; }
  template <int D> double Pi(double alpha_ij, double ci, double cj, double rho_i, double rho_j, double hi, double hj,
                             const Vector<D>& vij, const VariableHPair<D>& g) const {
    const double vr = vij.dot(g.rij);
    if (vr >= 0.0) return 0.0;
    const double rho_bar = 0.5 * (rho_i + rho_j);
    if (model == ViscosityModel::SignalVelocity) {
      const double w = vr / g.r;
      return -0.5 * alpha_ij * signal_velocity(ci, cj, w, beta) * w / rho_bar;
    }
    return monaghan_viscosity(alpha_ij, beta, epsilon, 0.5 * (hi + hj), 0.5 * (ci + cj), rho_bar, vr, g.r);
  }
};

// Viscous acceleration on i from j and its heating of i: -m_j Pi grad_bar W and (1/2) m_j Pi v_ij . grad_bar W,
// which together conserve the total energy exactly.
template <int D> inline Vector<D> viscous_acceleration(double mj, double Pi, const VariableHPair<D>& g) {
  return (-mj * Pi) * g.gradW_mean();
}
template <int D> inline double viscous_heating(double mj, double Pi, const Vector<D>& vij, const VariableHPair<D>& g) {
  return 0.5 * mj * Pi * vij.dot(g.gradW_mean());
}

// Artificial thermal conductivity (Price 2008, JCP 227:10040, eq. 28): heat flows down the thermal
// energy difference with the pressure-jump signal speed v_sig^u = sqrt(|P_i - P_j| / rho_bar), so it
// acts at contact discontinuities and vanishes in pressure equilibrium's smooth parts. dW_mean < 0.
inline double conductivity_heating(double mj, double alpha_u, double pi, double pj, double rho_i, double rho_j,
                                   double ui, double uj, double dW_mean) {
  const double rho_bar = 0.5 * (rho_i + rho_j);
  const double v_sig = std::sqrt(std::abs(pi - pj) / rho_bar);
  return mj * alpha_u * v_sig * (ui - uj) * dW_mean / rho_bar;
}

// Velocity divergence and curl contributions of j to i (multiplied by 1/(Omega_i rho_i) afterwards):
//   (div v)_i = -1/(Omega_i rho_i) sum_j m_j v_ij . grad_i W_ij(h_i),
//   (curl v)_i = -1/(Omega_i rho_i) sum_j m_j v_ij x grad_i W_ij(h_i)   (Price 2012 eqs. 103-104).
template <int D> inline double divergence_term(double mj, const Vector<D>& vij, const Vector<D>& gradWi) {
  return -mj * vij.dot(gradWi);
}
template <int D> inline Eigen::Vector3d curl_term(double mj, const Vector<D>& vij, const Vector<D>& gradWi) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  for (int k = 0; k < D; ++k) a[k] = vij[k], b[k] = gradWi[k];
  return -mj * a.cross(b);
}

// Balsara (1995, JCP 121:357) switch: ~1 in compression, ~0 in shear flows.
inline double balsara_factor(double divv, double curl, double c, double h) {
  const double d = std::abs(divv);
  return d / (d + curl + 1e-4 * c / std::max(h, 1e-300));
}

// Morris & Monaghan (1997, JCP 136:41) time-dependent alpha, with the source bounded by alpha_max
// (Rosswog et al. 2000): d alpha/dt = -(alpha - alpha_min) sigma c / h + max(-div v, 0)(alpha_max - alpha).
inline double morris_monaghan_rate(double alpha, double alpha_min, double alpha_max, double sigma, double divv,
                                   double c, double h) {
  return -(alpha - alpha_min) * sigma * c / h + std::max(-divv, 0.0) * (alpha_max - alpha);
}

}  // namespace sph::compressible
