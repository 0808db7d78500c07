#pragma once
// Decaying Arnold-Beltrami-Childress (ABC) flow on the periodic cube [0, 2 pi)^3, a 3D viscous flow with
// an exact Navier-Stokes solution:
//   u = (A sin z + C cos y, B sin x + A cos z, C sin y + B cos x) e^{-nu t},  p = -rho |u|^2 / 2 (+ const).
// The flow is Beltrami (curl u = u), so u . grad u = grad |u|^2 / 2 is a pure gradient that the pressure
// balances, and each component is a Laplacian eigenfunction (lap u = -u): the viscous term only decays it.
// Re = U L / nu with U = max |u(x, 0)| and L = 2 pi (Ethier & Steinman 1994 give the family in general).
#include "src/run/case.hpp"

namespace sph {

class Beltrami : public Case<3> {
 public:
  std::string name() const override { return "beltrami"; }
  void set_from_options() override;
  void create(Particles<3>& P, Domain<3>& domain) const override;
  double spacing() const override;
  double minimum_particles() const override { return double(nx_) * nx_ * nx_; }
  int resolution() const override { return nx_; }
  Physics<3> physics() const override;
  double default_t_end() const override { return 1.0; }
  std::map<std::string, double> errors(const Particles<3>& P, double t) const override;
  nlohmann::json parameters() const override;

  // The exact solution (public for tests).
  Vector<3> velocity(const Vector<3>& x, double t) const;
  double pressure(const Vector<3>& x, double t) const;
  double speed_scale() const { return U_; }  // max |u(x, 0)|
  double viscosity() const;

 private:
  PetscInt nx_ = 32;
  PetscReal re_ = 100.0, A_ = 1.0, B_ = 1.0, C_ = 1.0, rho0_ = 1.0;
  double U_ = 0.0;  // set from A, B, C
};

// max over the cube of |u(x, 0)| for the coefficients (A, B, C): a grid search refined around its best point.
double beltrami_max_speed(double A, double B, double C);

}  // namespace sph
