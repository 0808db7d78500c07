// Sedov-Taylor blast wave: the self-similar reference on its own (published constants, conservation of
// energy and mass by the profile, the strong-shock jump conditions, Sedov's energy first integral), then
// end-to-end 2D runs of the sph program against it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "cases/sedov/sedov_solution.hpp"
#include "run_sph.hpp"
#include "src/core/error.hpp"

namespace {

using sph::SedovSolution;
using sph::testing::run_sph;

// Composite Simpson's rule of f on [a, b], n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(a + k * h);
  return s * h / 3.0;
}

// ------------------------------------------------------------------------------------------------
// The reference.

// Published constants, gamma = 1.4. Kamm's standard problems (LA-UR-00-6055; ExactPack's Sedov
// documentation): rho0 = 1, E = 0.851072 puts the spherical shock at R = 1 and E = 0.311357 the
// cylindrical one at R = 0.75 at t = 1, i.e. alpha = E t^2 / (rho0 R^(nu+2)) = 0.851072 and 0.984041.
// Sedov's cylindrical xi0 = alpha^(-1/4) = 1.0040. The spherical value agrees to 3e-8 in R; the
// cylindrical one to 8e-6 in R (3.3e-5 in alpha: 0.984074 here). Kamm & Timmes (2007, Table 4) list the
// spherical alpha as 0.851060, 1.4e-5 below the energy that puts their own shock at R = 1, so their
// tabulated alphas carry errors of that order; this integration's own error is ~1e-10 (it changes by
// 3e-11 from 1000 to 16000 steps). The tolerances are 2e-7 (spherical: E published to 6 digits) and 1e-5.
// For gamma = 5/3 the spherical constant is quoted as xi0 = 1.15167 (e.g. Ostriker & McKee 1988).
TEST(SedovSolution, ShockRadiusMatchesPublishedConstants) {
  const SedovSolution spherical(1.4, 3, 0.851072, 1.0), cylindrical(1.4, 2, 0.311357, 1.0);
  EXPECT_NEAR(spherical.shock_radius(1.0), 1.0, 2e-7);
  EXPECT_NEAR(cylindrical.shock_radius(1.0), 0.75, 0.75 * 1e-5);
  const SedovSolution cyl(1.4, 2, 1.0, 1.0);
  EXPECT_NEAR(cyl.xi0(), 1.0040, 5e-5);
  EXPECT_NEAR(std::pow(cyl.xi0(), -4.0), 0.984041, 5e-5);
  EXPECT_NEAR(SedovSolution(5.0 / 3.0, 3, 1.0, 1.0).xi0(), 1.15167, 5e-6);
  // The integration has converged: a 4x coarser one gives the same xi0 to 1e-8.
  EXPECT_NEAR(SedovSolution(1.4, 2, 1.0, 1.0, 1000).xi0(), cyl.xi0(), 1e-8);
  // R = xi0 (E t^2 / rho0)^(1/(nu+2)): scaling with E, rho0 and t.
  const SedovSolution other(1.4, 2, 2.5, 0.7);
  EXPECT_NEAR(other.shock_radius(0.3), cyl.xi0() * std::pow(2.5 * 0.09 / 0.7, 0.25), 1e-14);
  EXPECT_NEAR(other.shock_speed(0.3), (other.shock_radius(0.3 + 1e-6) - other.shock_radius(0.3 - 1e-6)) / 2e-6, 1e-7);
}

// Energy and mass behind the shock, by quadrature of the dimensional profile at(r, t) (the interpolated
// profile, not the integral that fixed xi0): E, and all the swept-up mass rho0 sigma R^nu / nu.
// Measured: within 3.4e-10 (energy) and 4e-13 (mass).
TEST(SedovSolution, ProfileHoldsTheEnergyAndTheSweptMass) {
  for (int nu = 1; nu <= 3; ++nu) {
    for (double gamma : {1.4, 5.0 / 3.0}) {
      const double E = 2.5, rho0 = 0.7, t = 0.3;
      const SedovSolution s(gamma, nu, E, rho0);
      const double R = s.shock_radius(t), sigma = SedovSolution::geometry_factor(nu);
      auto energy = [&](double r) {
        const auto q = s.at(r, t);
        return sigma * std::pow(r, nu - 1) * (0.5 * q.rho * q.v * q.v + q.p / (gamma - 1.0));
      };
      auto mass = [&](double r) { return sigma * std::pow(r, nu - 1) * s.at(r, t).rho; };
      EXPECT_NEAR(simpson(energy, 0.0, R, 20000), E, 1e-8 * E) << "nu " << nu << " gamma " << gamma;
      const double swept = rho0 * sigma * std::pow(R, nu) / nu;
      EXPECT_NEAR(simpson(mass, 0.0, R, 20000), swept, 1e-8 * swept) << "nu " << nu << " gamma " << gamma;
    }
  }
}

// Strong-shock Rankine-Hugoniot conditions (cold gas at rest ahead): the state just inside R(t), fluxes
// of mass, momentum and enthalpy balanced in the shock frame; the gas at rest just outside.
TEST(SedovSolution, JumpConditionsAtTheShock) {
  for (double gamma : {1.4, 5.0 / 3.0}) {
    const double rho0 = 1.3, t = 0.05;
    const SedovSolution s(gamma, 2, 1.0, rho0);
    const double R = s.shock_radius(t), U = s.shock_speed(t);
    const auto in = s.at(R * (1 - 1e-12), t), out = s.at(R * (1 + 1e-12), t);
    EXPECT_NEAR(in.rho, rho0 * (gamma + 1) / (gamma - 1), 1e-9);  // 6 rho0 for gamma = 1.4, 4 rho0 for 5/3
    EXPECT_NEAR(s.post_shock_density(), in.rho, 1e-9);
    EXPECT_NEAR(in.v, 2 * U / (gamma + 1), 1e-9);
    EXPECT_NEAR(in.p, 2 * rho0 * U * U / (gamma + 1), 1e-9);
    const double w = U - in.v;  // downstream speed relative to the shock
    EXPECT_NEAR(rho0 * U, in.rho * w, 1e-9);
    EXPECT_NEAR(rho0 * U * U, in.p + in.rho * w * w, 1e-9);
    EXPECT_NEAR(0.5 * U * U, gamma * in.p / ((gamma - 1) * in.rho) + 0.5 * w * w, 1e-9);
    EXPECT_EQ(out.rho, rho0);
    EXPECT_EQ(out.v, 0.0);
    EXPECT_EQ(out.p, 0.0);
  }
}

// Sedov's energy integral: the energy inside the similar sphere xi R(t) is constant in time, so the
// energy swept by the moving sphere equals the flux through it at every xi,
//   xi (psi phi^2/2 + pi/(gamma-1)) = phi (psi phi^2/2 + gamma pi/(gamma-1)).
// The ODEs do not impose it: it checks their integration (and derivation) along the whole profile.
// Measured worst residuals: <= 7.7e-7 (nu = 3: the inward growing mode amplifies the RK4 error as
// xi^-3 down to xi_min = 0.0067), <= 2.4e-6 for gamma = 3, whose central power laws set in slowly
// (psi ~ xi^(nu/2)) so the extrapolation below xi_min is less exact.
// Towards the centre: phi = xi/gamma, psi ~ xi^(nu/(gamma-1)), pi -> a constant.
TEST(SedovSolution, EnergyFirstIntegralHoldsAlongTheProfile) {
  for (int nu = 1; nu <= 3; ++nu) {
    for (double gamma : {1.2, 1.4, 5.0 / 3.0, 3.0}) {
      const SedovSolution s(gamma, nu, 1.0, 1.0);
      double worst = 0.0;
      for (double xi = 1.0; xi > 1e-4; xi *= 0.97) {
        const auto f = s.profile(xi);
        const double kinetic = 0.5 * f.psi * f.phi * f.phi;
        const double swept = xi * (kinetic + f.pi / (gamma - 1)), flux = f.phi * (kinetic + gamma * f.pi / (gamma - 1));
        worst = std::max(worst, std::abs(swept - flux) / flux);
      }
      EXPECT_LT(worst, gamma < 2 ? 1.5e-6 : 5e-6) << "nu " << nu << " gamma " << gamma;
      if (gamma > 2) continue;
      const auto c = s.profile(1e-3);
      EXPECT_NEAR(c.phi / 1e-3, 1.0 / gamma, 1e-6);
      EXPECT_NEAR(std::log10(s.profile(1e-2).psi / c.psi), nu / (gamma - 1), 1e-4);
      EXPECT_NEAR(c.pi, s.profile(1e-2).pi, 1e-6 * c.pi);
    }
  }
}

TEST(SedovSolution, RefusesBadInput) {
  EXPECT_THROW(SedovSolution(1.0, 2, 1.0, 1.0), sph::Error);
  EXPECT_THROW(SedovSolution(1.4, 4, 1.0, 1.0), sph::Error);
  EXPECT_THROW(SedovSolution(1.4, 2, -1.0, 1.0), sph::Error);
}

// ------------------------------------------------------------------------------------------------
// End-to-end runs.

std::string opts() { return std::string("-options_file ") + SPH_SOURCE_DIR + "/cases/sedov.opts"; }
double num(const nlohmann::json& j) { return j.get<double>(); }

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// cases/sedov.opts at t = 0.1 (R = 0.3175). The shock runs ahead of the exact one, the upstream half of a front
// smeared over a few h, and its peak stays far below the exact 6. The bounds leave ~50% headroom over the nx = 64
// measurements; from 32 to 64 every norm but the anisotropy (not monotonic in nx: a lattice effect) falls by a
// factor 0.47-0.77 (docs/verification/compressible.md, "Sedov-Taylor blast (2D)" and "Design measurements").
TEST(SedovBlast, ShockRadiusConvergesToTheSelfSimilarSolution) {
  const auto coarse = run_sph("sedov_32", opts() + " -nx 32 -output_interval 0");
  const auto r = run_sph("sedov_64", opts() + " -nx 64 -output_interval 0");
  ASSERT_EQ(coarse.exit_code, 0);
  ASSERT_EQ(r.exit_code, 0);
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "completed");
  EXPECT_EQ(s["n_particles"], 64 * 64);
  EXPECT_NEAR(num(s["parameters"]["exact"]["xi0"]), 1.0040, 5e-5);
  const auto& e = s["errors"];
  const auto& c = coarse.summary["errors"];
  EXPECT_LT(num(e["shock_radius_rel"]), 0.06);
  EXPECT_LT(num(e["peak_density_rel"]), 0.65);
  EXPECT_LT(num(e["l1_density"]), 0.45);
  EXPECT_LT(num(e["l1_velocity"]), 0.15);
  EXPECT_LT(num(e["l1_pressure"]), 0.13);
  EXPECT_LT(num(e["shock_anisotropy"]), 0.12);
  EXPECT_LT(num(c["shock_radius_rel"]), 0.12);
  // Refinement (measured ratios: shock radius 0.47, l1 0.57-0.62, peak 0.77).
  EXPECT_LT(num(e["shock_radius_rel"]), 0.7 * num(c["shock_radius_rel"]));
  for (const char* norm : {"l1_density", "l1_velocity", "l1_pressure"})
    EXPECT_LT(num(e[norm]), 0.8 * num(c[norm])) << norm;
  EXPECT_LT(num(e["peak_density_rel"]), 0.9 * num(c["peak_density_rel"]));
  // E = 1 deposited (plus the cold gas's 2.5e-5; the solver's thermal energy comes from the summation
  // density, 2.4e-4 below rho0 on the lattice); momentum to round-off, energy to the integrator's
  // accuracy at the blast's first steps (measured 5.3e-4 at cfl 0.3, 1.8e-4 at 0.15: O(dt^1.5)).
  EXPECT_NEAR(num(s["conservation"]["energy_initial"]), 1.0, 1e-3);
  EXPECT_LT(num(s["conservation"]["momentum_drift"]), 1e-12);
  EXPECT_LT(num(s["conservation"]["energy_drift_rel"]), 2e-3);
  // The radial profile: the undisturbed gas beyond the shock, the exact values alongside.
  const std::string profile = slurp(r.output_dir + "/radial_profile.csv");
  EXPECT_EQ(profile.rfind("r,particles,rho,v_r,p,rho_exact,v_r_exact,p_exact\n", 0), 0u);
  std::istringstream lines(profile);
  std::string line;
  std::getline(lines, line);
  int rings = 0, beyond = 0;
  while (std::getline(lines, line)) {
    double v[8];
    char comma;
    std::istringstream row(line);
    row >> v[0];
    for (int c = 1; c < 8; ++c) row >> comma >> v[c];
    ++rings;
    if (v[0] > 1.25 * 0.3175) {  // the front's precursor reaches ~1.22 R at nx = 64
      ++beyond;
      EXPECT_NEAR(v[2], 1.0, 2e-3) << line;
      EXPECT_EQ(v[5], 1.0);
    }
  }
  EXPECT_GT(rings, 40);  // 61 rings of dx/2 out to 1.5 R, the innermost empty
  EXPECT_GT(beyond, 5);
  EXPECT_NE(slurp(r.output_dir + "/shock.csv").find("radius_exact"), std::string::npos);
}

TEST(SedovBlast, RefusedByIncompressibleSolversAndBadValues) {
  for (const char* solver : {"isph", "wcsph"}) {
    const auto r = run_sph(std::string("sedov_") + solver, std::string("-case sedov -nx 16 -solver ") + solver);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(slurp(r.output_dir + ".log").find("use -solver compressible"), std::string::npos) << solver;
  }
  const auto bad = run_sph("sedov_bad_energy", "-case sedov -solver compressible -nx 16 -energy -1");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(slurp(bad.output_dir + ".log").find("-energy must be positive"), std::string::npos);
}

}  // namespace
