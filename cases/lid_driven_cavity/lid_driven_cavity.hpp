#pragma once
// Lid-driven cavity: unit square (unit cube in 3D) of fluid inside layers of fixed wall particles
// (Adami et al. 2012 walls); the top layers (y = 1) slide at the lid speed U in x. Re = U L / nu.
// Runs to steady state. References, compiled in from cases/lid_driven_cavity/data/ (sources in its
// README): 2D, Ghia, Ghia & Shin (1982, JCP 48:387) centreline tables for Re = 100, 400, 1000; 3D,
// Albensoeder & Kuhlmann (2005, JCP 206:536) for Re = 1000, and for Re = 100 and 400 a grid-converged
// finite-difference solution (scripts/cavity3d_reference.py), for want of a published table.
// Centreline profiles: u(1/2, y[, 1/2]) and v(x, 1/2[, 1/2]).
#include <string>
#include <utility>
#include <vector>

#include "src/run/case.hpp"
#include "src/sph/interpolation.hpp"

namespace sph {

template <int D> class LidDrivenCavity : public Case<D> {
 public:
  std::string name() const override { return "lid_driven_cavity"; }
  void set_from_options() override;
  void create(Particles<D>& P, Domain<D>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }
  double minimum_particles() const override { return D == 3 ? double(nx_) * nx_ * nx_ : double(nx_) * nx_; }
  int resolution() const override { return nx_; }
  Physics<D> physics() const override;
  double default_t_end() const override { return 40.0; }
  double wall_thickness() const override { return wall_layers_ * spacing(); }
  double steady_tolerance() const override { return 1e-3; }
  std::map<std::string, double> errors(const Particles<D>& P, double t) const override;
  std::string unmeasured_reason(const std::string& name) const override;
  void accumulate(const Particles<D>& P, double t, double dt) override;
  nlohmann::json accumulated_state() const override;
  void restore_accumulated_state(const nlohmann::json& state) override;
  void write_outputs(const Particles<D>& P, double t, const std::string& dir) const override;
  nlohmann::json parameters() const override;

 private:
  // The reference for this dimension and Re: its two files and the column holding this Re.
  struct Reference {
    std::string u_file, v_file, u_column, v_column;
    std::string file_tag, source;  // centreline_<file_tag>.csv, its column <source>
  };
  bool has_reference() const;
  Reference reference() const;
  struct Profiles {
    std::vector<double> y_u, u_ref, u_sph;  // u along the vertical centreline, at the reference's points
    std::vector<double> x_v, v_ref, v_sph;  // v along the horizontal centreline
  };
  Profiles reference_profiles() const;  // the reference's points and values, no SPH values yet
  Profiles centreline_profiles(const Particles<D>& P) const;
  const Profiles& profiles_at(const Particles<D>& P, double t, Profiles& scratch) const;
  std::pair<double, double> rms_errors(const Profiles& pr) const;  // RMS of u and v against the reference
  bool averaging() const { return average_from_ >= 0.0; }
  Profiles averaged_profiles() const;  // the reference's points with the time-averaged u and v

  // -profile_average_from T: the profiles at the reference's points averaged over the steps that start
  // at t >= T, each weighted by its dt. A steady cavity's particles keep circulating, so its instantaneous
  // profile carries particle-scale noise (docs/verification/lid_driven_cavity.md, "Design measurements");
  // the average does not.
  struct ProfileAverage {
    double weight = 0.0;       // the time averaged over
    std::vector<double> u, v;  // sums of dt times the profile
  };
  ProfileAverage average_;
  // The profiles of the last accumulate() call, so that errors() at the same time reuses them.
  Profiles last_;
  double last_t_ = -1.0;
  Vector<D> centreline_point(double along, int axis) const;  // axis 1: (1/2, along, 1/2); axis 0: (along, 1/2, 1/2)

  PetscInt nx_ = 50, wall_layers_ = 4;
  ProbeInterpolation interpolation_ = ProbeInterpolation::Linear;
  bool symmetric_corners_ = false;  // -lid_corners: both corner blocks at U/2, not upstream at U, downstream 0
  PetscReal re_ = 100.0, U_ = 1.0, rho0_ = 1.0, average_from_ = -1.0;
};

}  // namespace sph
