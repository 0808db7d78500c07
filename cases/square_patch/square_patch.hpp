#pragma once
// Rotating square patch (Colagrossi 2005; Le Touzé et al. 2010): a square of fluid of side L in
// vacuum, started in rigid rotation u = omega (y - yc), v = -omega (x - xc), without gravity. The free
// surface deforms into a rotating four-armed shape and the pressure in the corners goes negative:
// a stability test for free-surface treatment and tensile instability. There is no closed-form
// solution at later times; the run reports what an inviscid flow must conserve: angular momentum
// about the centre (angular_momentum_drift_rel) and kinetic energy (kinetic_energy_change_rel).
#include "src/run/case.hpp"

namespace sph {

class SquarePatch : public Case<2> {
 public:
  std::string name() const override { return "square_patch"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return L_ / nx_; }
  double minimum_particles() const override { return double(nx_) * nx_; }
  int resolution() const override { return nx_; }
  Physics<2> physics() const override;
  double default_t_end() const override { return 1.0 / omega_; }
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  nlohmann::json parameters() const override;

 private:
  // Angular momentum about the centre and kinetic energy of the fluid, reduced over ranks.
  std::pair<double, double> invariants(const Particles<2>& P) const;

  PetscInt nx_ = 40;
  PetscReal L_ = 1.0, omega_ = 1.0, nu_ = 0.0, rho0_ = 1.0;
  mutable double L0_ = 0.0, E0_ = 0.0;  // initial values, taken at the first call of errors()
};

}  // namespace sph
