#pragma once
// Lid-driven cavity: unit square of fluid inside layers of fixed wall particles (Adami et al. 2012
// walls); the top layers slide at the lid speed U. Re = U L / nu. Runs to steady state. Reference:
// Ghia, Ghia & Shin (1982, JCP 48:387) centreline tables for Re = 100, 400, 1000 (compiled in from
// cases/lid_driven_cavity/data/).
#include "src/run/case.hpp"

namespace sph {

class LidDrivenCavity : public Case<2> {
 public:
  std::string name() const override { return "lid_driven_cavity"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }
  int resolution() const override { return nx_; }
  Physics<2> physics() const override;
  double default_t_end() const override { return 40.0; }
  double wall_thickness() const override { return wall_layers_ * spacing(); }
  double steady_tolerance() const override { return 1e-3; }
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  void write_outputs(const Particles<2>& P, double t, const std::string& dir) const override;
  nlohmann::json parameters() const override;

 private:
  struct Profiles {
    std::vector<double> y_u, u_ref, u_sph;  // u(0.5, y) at Ghia's points
    std::vector<double> x_v, v_ref, v_sph;  // v(x, 0.5)
  };
  Profiles centreline_profiles(const Particles<2>& P) const;
  bool has_reference() const;

  PetscInt nx_ = 50, wall_layers_ = 4;
  PetscReal re_ = 100.0, U_ = 1.0, rho0_ = 1.0;
};

}  // namespace sph
