#pragma once
// Standing wave: the first sloshing mode of a tank of width L and depth h, released from rest with its
// surface at h + a cos(k x), k = pi / L, a << h (walls on the floor and both sides, gravity g). Linear
// theory (Lamb 1932, sec. 227): it oscillates with omega^2 = g k tanh(k h). The fluid's horizontal
// momentum moves with the mode and has no mean (the centre of mass's swing may have one: the particles'
// equilibrium is not exactly the lattice's), so its zero crossings, read at every step, give the period
// over whole periods (a mean offset lengthens every other half period): period_rel = |T - 2 pi / omega|
// / (2 pi / omega) (NaN before the first full period). Also reported: T, and the decay rate of the
// momentum's swings (damping_rate, the least-squares slope of the log of their extremes), beside the bulk
// viscous rate 2 nu k^2 and the theory's whole rate with the walls' Stokes layers in the case's
// parameters. -side_walls 0: one wavelength 2L, periodic, a floor only; -free_slip_side_walls: side
// walls without shear, so that only the floor has a Stokes layer. The particles start on a
// lattice stretched column by column to the surface, each with the mass of its volume and the
// hydrostatic pressure below that surface.
#include <vector>

#include "src/run/case.hpp"

namespace sph {

class StandingWave : public Case<2> {
 public:
  std::string name() const override { return "standing_wave"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }
  double minimum_particles() const override { return width_ * depth_ * nx_ * nx_; }  // the water
  int resolution() const override { return nx_; }
  Physics<2> physics() const override;
  double default_t_end() const override { return 3.0 * linear_period(); }
  double wall_thickness() const override { return wall_layers_ * spacing(); }
  void accumulate(const Particles<2>& P, double t, double dt) override;
  nlohmann::json accumulated_state() const override;
  void restore_accumulated_state(const nlohmann::json& state) override;
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  std::string unmeasured_reason(const std::string& name) const override;
  nlohmann::json parameters() const override;
  std::vector<char> free_slip_of_particles() const override;

  double linear_period() const;
  double damping_rate_theory() const;

 private:
  double horizontal_momentum(const Particles<2>& P) const;  // of the fluid, all ranks
  enum class Site { Floor, SideWall, Fluid };
  template <class F> void for_each_site(F&& f) const;

  PetscInt nx_ = 40, wall_layers_ = 4;
  PetscReal width_ = 1.0, depth_ = 0.5, amplitude_ = 0.01, g_ = 1.0, re_ = 1000.0, rho0_ = 1.0;
  bool side_walls_ = true, free_slip_side_walls_ = false;
  std::vector<double> crossings_;  // times where the momentum changes sign
  std::vector<double> extremes_;   // its largest magnitude in each whole swing
  std::vector<double> extreme_times_;
  double last_t_ = 0.0, last_ = 0.0;            // the last sample
  double swing_max_ = 0.0, swing_max_t_ = 0.0;  // the swing under way
  int samples_ = 0;
};

}  // namespace sph
