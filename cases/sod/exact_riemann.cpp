#include "cases/sod/exact_riemann.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "src/core/error.hpp"

namespace sph {

ExactRiemann::ExactRiemann(const GasState& left, const GasState& right, double gamma)
    : L_(left), R_(right), gamma_(gamma) {
  if (!(gamma > 1.0)) throw Error("exact Riemann solver: gamma must exceed 1 (got " + std::to_string(gamma) + ")");
  if (!(L_.rho > 0 && R_.rho > 0 && L_.p > 0 && R_.p > 0))
    throw Error("exact Riemann solver: densities and pressures must be positive");
  cL_ = std::sqrt(gamma_ * L_.p / L_.rho);
  cR_ = std::sqrt(gamma_ * R_.p / R_.rho);
  const double du = R_.u - L_.u;
  // Pressure positivity condition (Toro eq. 4.40): otherwise the solution contains vacuum.
  if (2.0 * (cL_ + cR_) / (gamma_ - 1.0) <= du)
    throw Error("exact Riemann solver: the initial data generate vacuum (not supported)");

  // Initial guess: the primitive-variable (PVRS) estimate, Toro eq. 4.47, kept positive.
  const double tol = 1e-14;
  const double p_pv = 0.5 * (L_.p + R_.p) - 0.125 * du * (L_.rho + R_.rho) * (cL_ + cR_);
  double p = std::max(tol, p_pv);
  for (iterations_ = 1; iterations_ <= 100; ++iterations_) {
    double fL, dfL, fR, dfR;
    pressure_function(p, L_, cL_, fL, dfL);
    pressure_function(p, R_, cR_, fR, dfR);
    double p_new = p - (fL + fR + du) / (dfL + dfR);
    if (p_new < tol) p_new = tol;
    const double change = 2.0 * std::abs(p_new - p) / (p_new + p);  // Toro eq. 4.45
    p = p_new;
    if (change < tol) break;
  }
  if (iterations_ > 100) throw Error("exact Riemann solver: Newton iteration for p* did not converge");
  double fL, dfL, fR, dfR;
  pressure_function(p, L_, cL_, fL, dfL);
  pressure_function(p, R_, cR_, fR, dfR);
  p_star_ = p;
  u_star_ = 0.5 * (L_.u + R_.u) + 0.5 * (fR - fL);  // Toro eq. 4.9

  const double g6 = (gamma_ - 1.0) / (gamma_ + 1.0);
  auto star_density = [&](const GasState& K) {
    const double ratio = p_star_ / K.p;
    return ratio > 1.0 ? K.rho * (ratio + g6) / (g6 * ratio + 1.0)  // shock, Toro eq. 4.50
                       : K.rho * std::pow(ratio, 1.0 / gamma_);     // rarefaction, eq. 4.53
  };
  rho_star_L_ = star_density(L_);
  rho_star_R_ = star_density(R_);
}

void ExactRiemann::pressure_function(double p, const GasState& K, double cK, double& f, double& df) const {
  const double g = gamma_;
  if (p > K.p) {  // shock
    const double A = 2.0 / ((g + 1.0) * K.rho), B = (g - 1.0) / (g + 1.0) * K.p;
    const double s = std::sqrt(A / (p + B));
    f = (p - K.p) * s;
    df = s * (1.0 - 0.5 * (p - K.p) / (B + p));
  } else {  // rarefaction
    const double ratio = p / K.p;
    f = 2.0 * cK / (g - 1.0) * (std::pow(ratio, (g - 1.0) / (2.0 * g)) - 1.0);
    df = 1.0 / (K.rho * cK) * std::pow(ratio, -(g + 1.0) / (2.0 * g));
  }
}

double ExactRiemann::left_head_speed() const {
  const double g = gamma_;
  if (left_is_shock()) return L_.u - cL_ * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / L_.p + (g - 1.0) / (2.0 * g));
  return L_.u - cL_;
}
double ExactRiemann::left_tail_speed() const {
  if (left_is_shock()) return left_head_speed();
  return u_star_ - cL_ * std::pow(p_star_ / L_.p, (gamma_ - 1.0) / (2.0 * gamma_));
}
double ExactRiemann::right_head_speed() const {
  const double g = gamma_;
  if (right_is_shock()) return R_.u + cR_ * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / R_.p + (g - 1.0) / (2.0 * g));
  return R_.u + cR_;
}
double ExactRiemann::right_tail_speed() const {
  if (right_is_shock()) return right_head_speed();
  return u_star_ + cR_ * std::pow(p_star_ / R_.p, (gamma_ - 1.0) / (2.0 * gamma_));
}

GasState ExactRiemann::sample(double s) const {
  const double g = gamma_;
  if (s <= u_star_) {  // left of the contact
    if (s <= left_head_speed()) return L_;
    if (left_is_shock() || s >= left_tail_speed()) return {rho_star_L_, u_star_, p_star_};
    // Inside the left rarefaction fan (Toro eq. 4.56).
    const double base = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * cL_) * (L_.u - s);
    return {L_.rho * std::pow(base, 2.0 / (g - 1.0)), 2.0 / (g + 1.0) * (cL_ + 0.5 * (g - 1.0) * L_.u + s),
            L_.p * std::pow(base, 2.0 * g / (g - 1.0))};
  }
  if (s >= right_head_speed()) return R_;
  if (right_is_shock() || s <= right_tail_speed()) return {rho_star_R_, u_star_, p_star_};
  // Inside the right rarefaction fan (Toro eq. 4.63).
  const double base = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * cR_) * (R_.u - s);
  return {R_.rho * std::pow(base, 2.0 / (g - 1.0)), 2.0 / (g + 1.0) * (-cR_ + 0.5 * (g - 1.0) * R_.u + s),
          R_.p * std::pow(base, 2.0 * g / (g - 1.0))};
}

GasState ExactRiemann::at(double x, double t, double x0) const {
  if (t <= 0.0) return x < x0 ? L_ : R_;
  return sample((x - x0) / t);
}

}  // namespace sph
