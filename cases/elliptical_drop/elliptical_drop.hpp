#pragma once
// Evolving elliptical drop (Monaghan 1994; Colagrossi 2005): a circular drop of radius R of inviscid
// fluid, no gravity, started with the velocity u = A0 (x, -y) and the pressure that goes with it,
// p = rho0 A0^2 (R^2 - x^2 - y^2) / 2. The velocity stays linear, u = A(t) (x, -y), and the drop an
// ellipse with semi-axes a(t), b(t), a b = R^2, following
//   da/dt = A a,   db/dt = -A b,   dA/dt = A^2 (b^2 - a^2) / (a^2 + b^2)
// (the free-surface condition p = 0 on the ellipse in Euler's equations). That ODE, integrated by RK4
// to round-off, is the reference. The particles move as the flow does, x(t) = (a / R) x(0), so the
// drop's semi-axis is read off its particles' second moments: a = R sqrt(<x^2>(t) / <x^2>(0)), exact
// for that linear map on any lattice. Errors: semi_axis_rel = |a - a_ODE| / a_ODE; semi_axis_b_rel the
// same for b; also reported: semi_axis_a, semi_axis_b.
#include "src/run/case.hpp"

namespace sph {

class EllipticalDrop : public Case<2> {
 public:
  std::string name() const override { return "elliptical_drop"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return R_ / nx_; }
  double minimum_particles() const override { return 2.0 * nx_ * nx_; }  // the square inscribed in the drop
  int resolution() const override { return nx_; }
  Physics<2> physics() const override;
  double default_t_end() const override { return 0.8 / A0_; }  // Monaghan's 0.008 s at A0 = 100 / s
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  nlohmann::json parameters() const override;

  // The reference semi-axes (a, b) at time t.
  std::pair<double, double> semi_axes(double t) const;

 private:
  PetscInt nx_ = 20;  // particles across the radius
  PetscReal R_ = 1.0, A0_ = 1.0, rho0_ = 1.0;
  mutable double x2_0_ = -1.0, y2_0_ = -1.0;  // <x^2>, <y^2> at the start, from the first errors() call
};

}  // namespace sph
