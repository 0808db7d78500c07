#include "cases/sedov/sedov_solution.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "src/core/error.hpp"

namespace sph {

namespace {
// Inwards the similarity ODE has a growing mode (phi ~ xi^(1-nu), the singular branch): the RK4
// truncation error made near the shock, where the profile is steep, grows as xi^-nu. With 20000 steps
// it stays below 1e-6 down to xi_min = e^-5 = 0.0067 (phi/xi within 6e-7 of 1/gamma for nu = 3, where
// 4000 steps leave 1.4e-4); below xi_min the central power laws phi = xi/gamma,
// psi ~ xi^(nu/(gamma-1)), pi = const carry the profile to the centre.
constexpr double ln_xi_min = -5.0;
}  // namespace

double SedovSolution::geometry_factor(int nu) {
  switch (nu) {
    case 1: return 2.0;
    case 2: return 2.0 * M_PI;
    case 3: return 4.0 * M_PI;
  }
  throw Error("Sedov solution: nu must be 1, 2 or 3 (got " + std::to_string(nu) + ")");
}

SedovSolution::Y SedovSolution::rates(double s, const Y& y) const {
  const double xi = std::exp(s), g = gamma_, nu = nu_;
  const double phi = y[0], psi = std::exp(y[1]), pi = std::exp(y[2]);
  const double a = phi - xi;
  // q = 1 / c^2 with c^2 = gamma pi / psi the squared sound speed in units of Rdot: the momentum and
  // entropy equations divided by c^2 stay finite at the hot centre, where psi -> 0.
  const double q = psi / (g * pi);
  const double denominator = q * a * a - 1.0;  // (a^2 - c^2) / c^2 < 0: the flow behind the shock is subsonic
  if (!(denominator < 0.0))
    throw Error("Sedov solution: the similarity ODE met a sonic point at xi = " + std::to_string(xi) +
                " (gamma = " + std::to_string(g) + ")");
  const double xi_dphi = xi * (q * a * nu * phi / 2.0 - nu / g + (nu - 1.0) * phi / xi) / denominator;
  const double compression = xi_dphi + (nu - 1.0) * phi;  // xi (phi' + (nu - 1) phi / xi)
  return {xi_dphi, -compression / a, (nu * xi - g * compression) / a,
          -(psi * phi * phi / 2.0 + pi / (g - 1.0)) * std::pow(xi, nu)};
}

SedovSolution::SedovSolution(double gamma, int nu, double energy, double rho0, int steps)
    : gamma_(gamma), E_(energy), rho0_(rho0), nu_(nu) {
  if (!(gamma > 1.0)) throw Error("Sedov solution: gamma must be greater than 1 (got " + std::to_string(gamma) + ")");
  if (!(energy > 0.0) || !(rho0 > 0.0)) throw Error("Sedov solution: energy and density must be positive");
  if (steps < 100) throw Error("Sedov solution: at least 100 integration steps");
  const double sigma = geometry_factor(nu);
  s_min_ = ln_xi_min;
  ds_ = -s_min_ / steps;
  // Strong-shock jump conditions on the inner side of the shock (xi = 1).
  Y y = {2.0 / (gamma + 1.0), std::log((gamma + 1.0) / (gamma - 1.0)), std::log(2.0 / (gamma + 1.0)), 0.0};
  y_.reserve(steps + 1), dy_.reserve(steps + 1);
  for (int k = 0;; ++k) {
    const double s = -k * ds_;
    const Y dy = rates(s, y);
    y_.push_back(y), dy_.push_back(dy);
    if (k == steps) break;
    // Classical RK4 with the step -ds (inwards).
    const double h = -ds_;
    auto shifted = [&](const Y& k_, double f) {
      Y out = y;
      for (std::size_t c = 0; c < out.size(); ++c) out[c] += f * h * k_[c];
      return out;
    };
    const Y k2 = rates(s + 0.5 * h, shifted(dy, 0.5));
    const Y k3 = rates(s + 0.5 * h, shifted(k2, 0.5));
    const Y k4 = rates(s + h, shifted(k3, 1.0));
    for (std::size_t c = 0; c < y.size(); ++c) y[c] += h / 6.0 * (dy[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
  }
  // Below xi_min, the central power laws: phi = phi_m xi/xi_m, psi = psi_m (xi/xi_m)^k, pi = pi_m.
  const double xi_m = std::exp(s_min_), k = dy_.back()[1];
  const double phi_m = y_.back()[0], psi_m = std::exp(y_.back()[1]), pi_m = std::exp(y_.back()[2]);
  I_ = y_.back()[3] + (psi_m * phi_m * phi_m / 2.0 / (k + 2.0 + nu) + pi_m / (gamma - 1.0) / nu) * std::pow(xi_m, nu);
  const double delta = 2.0 / (nu + 2.0);
  xi0_ = std::pow(sigma * delta * delta * I_, -1.0 / (nu + 2.0));
}

SedovSolution::Profile SedovSolution::profile(double xi) const {
  if (!(xi > 0.0)) return {0.0, 0.0, std::exp(y_.back()[2])};  // the centre: at rest, empty, hot
  xi = std::min(xi, 1.0);
  const double s = std::log(xi);
  const std::size_t last = y_.size() - 1;
  double phi, ln_psi, ln_pi;
  if (s <= s_min_) {
    // Central power laws: phi ~ xi, psi and pi with their logarithmic slopes at xi_min.
    const Y& y = y_[last];
    const Y& d = dy_[last];
    const double ds = s - s_min_;
    phi = y[0] * std::exp(ds), ln_psi = y[1] + d[1] * ds, ln_pi = y[2] + d[2] * ds;
  } else {
    // Cubic Hermite between nodes k (s_k = -k ds) and k + 1, parameter t from 0 to 1 inwards.
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(-s / ds_), last - 1);
    const double t = (-static_cast<double>(k) * ds_ - s) / ds_;
    const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
    const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
    auto hermite = [&](int c) {
      return h00 * y_[k][c] + h01 * y_[k + 1][c] - ds_ * (h10 * dy_[k][c] + h11 * dy_[k + 1][c]);
    };
    phi = hermite(0), ln_psi = hermite(1), ln_pi = hermite(2);
  }
  return {phi, std::exp(ln_psi), std::exp(ln_pi)};
}

double SedovSolution::shock_radius(double t) const { return xi0_ * std::pow(E_ * t * t / rho0_, 1.0 / (nu_ + 2.0)); }

double SedovSolution::shock_speed(double t) const { return 2.0 / (nu_ + 2.0) * shock_radius(t) / t; }

SedovSolution::State SedovSolution::at(double r, double t) const {
  const double R = shock_radius(t);
  if (!(t > 0.0) || r > R) return {rho0_, 0.0, 0.0};
  const double U = shock_speed(t);
  const Profile f = profile(r / R);
  return {rho0_ * f.psi, U * f.phi, rho0_ * U * U * f.pi};
}

}  // namespace sph
