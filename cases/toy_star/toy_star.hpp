#pragma once
// One-dimensional toy star (Monaghan & Price 2004, MNRAS 350:1449): a polytropic gas P = K rho^gamma
// held by the external force -Omega^2 x. Flows with v = A(t) x keep the exact non-linear form
//   v = A(t) x,   rho^(gamma-1) = H(t) - C(t) x^2,
//   dA/dt = 2 K gamma C / (gamma - 1) - Omega^2 - A^2,  dH/dt = -(gamma - 1) A H,  dC/dt = -(gamma + 1) A C,
// integrated here with RK4 as the reference. Start: the static star of radius R = 1
// (C = (gamma-1) Omega^2 / (2 K gamma), H = C R^2) with the velocity v = A0 x, which makes it
// breathe with the linear frequency Omega sqrt(gamma + 1). The scene is isentropic (no energy equation).
#include <array>

#include "src/run/case.hpp"

namespace sph {

class ToyStar : public Case<1> {
 public:
  std::string name() const override { return "toy_star"; }
  void set_from_options() override;
  void create(Particles<1>& P, Domain<1>& domain) const override;
  double spacing() const override;  // m / rho at the centre
  double minimum_particles() const override { return double(n_); }
  int resolution() const override { return static_cast<int>(n_); }
  Physics<1> physics() const override;
  double default_t_end() const override { return 2.0 * period(); }
  // Particle means (equal masses) of |rho - rho_exact| and |v - v_exact|, absolute (rho_c(0) = 1 and
  // R = 1 with the default parameters, so they read as fractions of the central density and of Omega R).
  std::map<std::string, double> errors(const Particles<1>& P, double t) const override;
  nlohmann::json parameters() const override;

  // The reference (public for tests): (A, H, C) at time t, and the fields.
  std::array<double, 3> coefficients(double t) const;
  double density(double x, double t) const;
  double velocity(double x, double t) const;
  double period() const;  // linear breathing period 2 pi / (Omega sqrt(gamma + 1))
  double mass() const;

 private:
  std::array<double, 3> rates(const std::array<double, 3>& y) const;
  std::array<double, 3> rk4_step(const std::array<double, 3>& y, double h) const;

  PetscInt n_ = 200;
  PetscReal gamma_ = 2.0, K_ = 0.25, omega_ = 1.0, A0_ = 0.1;
  // RK4 cache: errors() is called every step with increasing t.
  mutable long k_cache_ = 0;
  mutable std::array<double, 3> y_cache_{};
};

}  // namespace sph
