#pragma once
// Decaying Taylor-Green vortex on the periodic unit square (Taylor & Green 1937), a viscous flow with
// an exact Navier-Stokes solution:
//   u = -U e^{bt} cos(2 pi x) sin(2 pi y),  v = U e^{bt} sin(2 pi x) cos(2 pi y),
//   p = -(rho U^2 / 4) e^{2bt} (cos 4 pi x + cos 4 pi y),  b = -8 pi^2 / Re,  Re = U L / nu, L = 1.
#include "src/run/case.hpp"

namespace sph {

class TaylorGreen : public Case<2> {
 public:
  std::string name() const override { return "taylor_green"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }
  double minimum_particles() const override { return double(nx_) * nx_; }
  int resolution() const override { return nx_; }
  Physics<2> physics() const override;
  double default_t_end() const override { return 1.0; }
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  nlohmann::json parameters() const override;

  // The exact solution (public for tests).
  Vector<2> velocity(const Vector<2>& x, double t) const;
  double pressure(const Vector<2>& x, double t) const;
  double decay_rate() const;  // b

 private:
  PetscInt nx_ = 64;
  PetscReal re_ = 100.0, U_ = 1.0, rho0_ = 1.0;
  PetscReal perturbation_ = 0.0;  // random start: each particle moved up to this fraction of dx
};

}  // namespace sph
