#pragma once
// Sedov-Taylor point explosion in 2D (cylindrical symmetry, nu = 2): an ideal gas (gamma = 1.4) of
// density rho0 = 1 at rest on a square lattice filling the periodic box [-1/2, 1/2)^2, cold
// (P = -p_ambient, 1e-5), with the energy -energy (E = 1) deposited as thermal energy in the central particles with
// M4 cubic-spline weights W(|x_i|, h_dep), h_dep = -deposit_h dx (support 2 h_dep: 16 particles at the
// default 1.2). The shock runs at R(t) = xi0 (E t^2 / rho0)^(1/4), xi0 = 1.0040 (gamma = 1.4); at the
// default t_end = 0.1 it is at R = 0.317, 0.18 short of the box edge, so the periodic images never meet
// it. Reference: the self-similar solution (cases/sedov/sedov_solution.hpp).
//
// Errors (errors(), into summary.json and timeseries.csv), from the particle density, with the shock
// measured on a radial profile: the mean particle density in rings of width dx/2 around the centre.
//   shock_radius_rel:   |R_measured - R| / R, R_measured where the profile, going outwards from its
//                       maximum, falls through the mid-level between that maximum and rho0 (linear
//                       interpolation between ring centres);
//   peak_density_rel:   |max ring density - rho2| / rho2, rho2 = rho0 (gamma+1)/(gamma-1) (6 rho0): the
//                       exact jump, which SPH smears over a few h, so this stays large at coarse resolution;
//   l1_density:         sum V |rho - rho_exact(r)| / (rho0 sum V) over r < 1.2 R, V = m / rho;
//   l1_velocity:        the same for |v - v_exact(r) r_hat| / Rdot;
//   l1_pressure:        the same for |P - P_exact(r)| / P2, P2 = 2 rho0 Rdot^2 / (gamma + 1);
//   shock_anisotropy:   |R_axes - R_diagonals| / R, the shock radius measured as above in cones of
//                       half-angle pi/16 around the lattice axes and around the diagonals (a square
//                       lattice and its 4-fold symmetry are the only source of non-radial structure).
// write_outputs: radial_profile.csv (rings: r, particles, mean rho, v_r, P and the exact values at r)
// and shock.csv (R exact, measured overall, along the axes and the diagonals, ring peak, rho2).
#include <memory>
#include <vector>

#include "cases/sedov/sedov_solution.hpp"
#include "src/run/case.hpp"

namespace sph {

class SedovBlast : public Case<2> {
 public:
  std::string name() const override { return "sedov"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }
  double minimum_particles() const override { return double(nx_) * nx_; }
  int resolution() const override { return static_cast<int>(nx_); }
  Physics<2> physics() const override;
  double default_t_end() const override { return 0.1; }
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  void write_outputs(const Particles<2>& P, double t, const std::string& dir) const override;
  nlohmann::json parameters() const override;

  const SedovSolution& reference() const { return *exact_; }

  // Ring-averaged profile (all ranks' particles) out to r_max, rings of width dr; `cone` selects
  // particles by direction: 0 all, 1 within pi/16 of a lattice axis, 2 within pi/16 of a diagonal.
  struct RadialProfile {
    double dr = 0.0;
    std::vector<double> count, rho, vr, p;  // per ring: particles and mean values (0 where empty)
    double r(std::size_t k) const { return (k + 0.5) * dr; }
  };
  struct Shock {
    double radius, peak;  // NaN when no front is found
  };
  RadialProfile radial_profile(const Particles<2>& P, double r_max, int cone) const;
  Shock measure_shock(const RadialProfile& prof) const;

 private:
  PetscInt nx_ = 64;
  PetscReal gamma_ = 1.4, rho0_ = 1.0, energy_ = 1.0, p_ambient_ = 1e-5, deposit_h_ = 1.2;
  std::shared_ptr<SedovSolution> exact_;
};

}  // namespace sph
