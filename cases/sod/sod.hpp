#pragma once
// Sod (1978) shock tube: an ideal gas (gamma = 1.4) at rest with rho = 1, P = 1 for x < 0 and
// rho = 0.125, P = 0.1 for x > 0; at t = 0.2 a rarefaction, a contact and a shock have formed.
// Layout: equal-mass particles (the spacing on the right is rho_L/rho_R = 8 times the left one in 1D)
// on the periodic domain x in [-1, 1): the mirrored interface at x = +-1 avoids open ends, and its
// waves reach |x| < 0.5 only after t = 0.28 (its shock runs at 1.75 from x = 1). Errors are measured
// on the tube |x| <= 0.5 against the exact Riemann solution (Toro 2009, ch. 4).
// -dim 2 / 3: a thin periodic box in y (and z) of -ny particle layers of the left state; the right
// state's lattice is as close to isotropic as the layer count allows, masses nearly equal.
#include "cases/sod/exact_riemann.hpp"
#include "src/run/case.hpp"

namespace sph {

template <int D> class SodShockTube : public Case<D> {
 public:
  std::string name() const override { return "sod"; }
  void set_from_options() override;
  void create(Particles<D>& P, Domain<D>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }  // the left (dense) state's spacing
  double minimum_particles() const override;
  int resolution() const override { return static_cast<int>(nx_); }
  Physics<D> physics() const override;
  double default_t_end() const override { return 0.2; }
  // Over the tube |x| <= 0.5, with V = m/rho (integral means):
  //   l1_density, l1_velocity, l1_pressure: sum V |f - f_exact| / sum V;
  //   plateau_density_rel, plateau_pressure_rel: relative error of the mean density / pressure between the
  //     contact and the shock (exact positions), excluding -plateau_margin particle spacings next to each;
  //   shock_position: |x_s,measured - x_s,exact|, x_s where the density falls through the midpoint of the
  //     exact post-shock and right-state densities (the rightmost crossing, linearly interpolated).
  std::map<std::string, double> errors(const Particles<D>& P, double t) const override;
  nlohmann::json parameters() const override;

  const ExactRiemann& reference() const { return *exact_; }

 private:
  struct Lattice {
    long nx, ny;    // cells along x and across (ny = 1 in 1D)
    double dx, dy;  // spacings along x and across
    double x0;      // left edge
  };
  Lattice left_lattice() const;
  Lattice right_lattice() const;

  PetscInt nx_ = 400, ny_ = D == 2 ? 32 : 16;
  PetscReal gamma_ = 1.4, rho_l_ = 1.0, p_l_ = 1.0, rho_r_ = 0.125, p_r_ = 0.1;
  PetscReal plateau_margin_ = 4.0;
  std::shared_ptr<ExactRiemann> exact_;
};

}  // namespace sph
