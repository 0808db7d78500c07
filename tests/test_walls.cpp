// End-to-end: Adami et al. (2012) walls in ISPH and WCSPH, against the Poiseuille series solution
// (Morris et al. 1997) and the lid-driven cavity tables of Ghia, Ghia & Shin (1982).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

double error(const sph::testing::RunResult& r, const char* name) { return r.summary["errors"][name].get<double>(); }

// Start-up Poiseuille flow at Re = 10 to t = 1 (about the viscous time L^2/nu / 10). A wall that let
// the fluid slip would give a plug profile, an error of tens of percent; 2% at 20 particles across
// is a fifth of the smallest such failure and the error must shrink with resolution (second order
// expected from the kernel smoothing error: measured 0.53% -> 0.14%, nx 20 -> 40).
TEST(Walls, IsphPoiseuilleMatchesSeriesSolutionAndConverges) {
  const auto coarse = run_sph("pois_isph_20", "-case poiseuille -solver isph -nx 20 -t_end 1");
  const auto fine = run_sph("pois_isph_40", "-case poiseuille -solver isph -nx 40 -t_end 1");
  ASSERT_EQ(coarse.exit_code, 0);
  ASSERT_EQ(fine.exit_code, 0);
  EXPECT_LT(error(coarse, "l1_velocity"), 0.02);
  EXPECT_LT(error(fine, "l1_velocity"), 0.5 * error(coarse, "l1_velocity"));
  EXPECT_EQ(coarse.summary["ksp"]["type"], "gmres");  // wall rows are not symmetric
  EXPECT_EQ(coarse.summary["models"]["walls"]["model"], "AdamiWall");
}

TEST(Walls, WcsphPoiseuilleMatchesSeriesSolution) {
  const auto r = run_sph("pois_wcsph_20", "-case poiseuille -solver wcsph -nx 20 -t_end 1");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_LT(error(r, "l1_velocity"), 0.02);
}

// Runs the cavity at 30 x 30 to steady state and bounds its centreline RMS errors against Ghia.
nlohmann::json expect_steady_cavity(const char* label, const char* solver, int re, double bound_u, double bound_v) {
  const auto r = run_sph(label, std::string("-case lid_driven_cavity -nx 30 -solver ") + solver + " -re " +
                                    std::to_string(re));
  EXPECT_EQ(r.exit_code, 0);
  if (r.exit_code != 0) return {};
  EXPECT_TRUE(r.summary["steady_state_reached"].get<bool>());
  EXPECT_LT(error(r, "centreline_rms_u"), bound_u);
  EXPECT_LT(error(r, "centreline_rms_v"), bound_v);
  return r.summary;
}

// Cavity Re = 100 at 30 x 30 particles, run to steady state. The interior Ghia values themselves have
// an RMS of about 0.35, so a stagnant or wrongly-driven cavity fails by far. Measured 0.45 % and 0.38 %
// (0.62 % and 0.72 % with -ppe_wall_velocity prescribed, the default before; the profiles read off by
// the linear fit; Shepard's average, the metric before that, gave 2.0 % and 0.9 %, its bias at the lid,
// and the bound on u was 5 % then).
TEST(Walls, IsphCavityRe100MatchesGhia) { expect_steady_cavity("cavity_isph_30", "isph", 100, 0.015, 0.02); }

// WCSPH cavity Re = 100 at 30 x 30 to steady state. The continuity equation must see walls at rest:
// with the lid's sliding velocity in it, the velocity jump where the lid ends drove a density source
// that compressed the cavity by 18% and gave 4.5% / 5.7% (Shepard's metric); measured now 0.50% / 0.71%
// (Shepard's: 2.2% / 0.7%; earlier runs spread over 1.9-2.1% / 0.5-1.0%: output and checkpoint cadence
// re-order particles, and round-off grows over 7000 steps).
//
// The box holds a fixed mass in a fixed volume, so its mean density cannot change (a conservation
// law). Without -closed_volume the continuity equation's truncation error compressed it by 3.1% by
// steady state (measured, RMS 2.0% / 0.9% all the same); with it, 0.013%. The bound, 0.1%, allows
// for the difference between the mean density and the total volume that is constrained, of the order
// of the squared density variations (Ma^2 = 1e-2 squared).
TEST(Walls, WcsphCavityRe100MatchesGhiaAndKeepsItsVolume) {
  const auto s = expect_steady_cavity("cavity_wcsph_30", "wcsph", 100, 0.015, 0.02);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["models"]["closed_volume"], true);
  EXPECT_LT(std::abs(s["conservation"]["mean_fluid_density_rel"].get<double>()), 1e-3);
}

// -lid_corners symmetric: both corner blocks at U/2. Run to t = 20 (past the transient, not to the
// steady-state stop, which fires before the errors settle), the profiles also averaged over t = 12-20.
// Measured 0.45 % and 0.33 % against Ghia at t = 20, 0.43 % and 0.32 % for the averaged profiles
// (0.49 % and 0.68 % against a finite-difference solution, whose v is 0.5 % off Ghia's; with
// -ppe_wall_velocity prescribed, the default before, 0.49 % and 0.05 % against Ghia); 1 % bounds that,
// where a corner block that drove the cavity wrongly would not.
TEST(Walls, IsphCavityWithSymmetricLidCornersMatchesGhia) {
  const auto r = run_sph("cavity_isph_30_symmetric", "-case lid_driven_cavity -nx 30 -re 100 -lid_corners symmetric "
                                                     "-steady_tol 0 -t_end 20 -profile_average_from 12 "
                                                     "-output_interval 0 -checkpoint_interval 0");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["parameters"]["lid_corners"], "symmetric");
  for (const char* name : {"centreline_rms_u", "centreline_rms_v", "centreline_rms_u_averaged", "centreline_rms_v_averaged"})
    EXPECT_LT(error(r, name), 0.01) << name;
}

// Cavity Re = 1000 at 30 x 30 particles. Its thin corner and wall layers are where particles used to
// leave through the lid/side-wall corner (a health-check failure); the run must reach steady state
// inside the box. Ghia's Re = 1000 centreline values have RMS 0.41 (u) and 0.31 (v), so 15% still
// separates a cavity with the right vortex from a stagnant or wrong one. The boundary layers span about
// one particle at nx 30 and the vortex is too weak (measured 8.9 % and 10.2 %; 4.3 % and 5.3 % at
// nx 50, 0.59 % and 0.43 % at nx 100, docs/verification/lid_driven_cavity.md).
TEST(Walls, IsphCavityRe1000StaysInsideAndApproachesGhia) {
  const auto s = expect_steady_cavity("cavity_isph_30_re1000", "isph", 1000, 0.15, 0.15);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["models"]["ppe_source"]["wall_velocity"], "zero");
}

// -ppe_wall_velocity prescribed (the default before): the PPE source sees the lid's velocity, whose jump
// at the fixed downstream corner block reads as a compression that drives the vortex harder, a
// first-order error that at Re 1000 and nx 30-50 offsets part of the under-resolved vortex's weakness
// (measured 4.6 % and 4.1 % at nx 30). The run must stay inside the box and reach steady state.
TEST(Walls, IsphCavityRe1000WithThePrescribedWallVelocityInTheSourceStaysInside) {
  const auto r = run_sph("cavity_isph_30_re1000_prescribed", "-case lid_driven_cavity -nx 30 -re 1000 "
                                                             "-ppe_wall_velocity prescribed -output_interval 0 "
                                                             "-checkpoint_interval 0");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["models"]["ppe_source"]["wall_velocity"], "prescribed");
  EXPECT_TRUE(r.summary["steady_state_reached"].get<bool>());
  EXPECT_LT(error(r, "centreline_rms_u"), 0.15);
  EXPECT_LT(error(r, "centreline_rms_v"), 0.15);
}

// The cubic cavity (-dim 3) at Re = 100 to steady state, against the finite-difference reference
// (cases/lid_driven_cavity/data/README.md: grid-converged, uncertain by 5e-4 U). Its interior centreline
// values have RMS 0.22 (u) and 0.14 (v), so a stagnant or wrongly driven cavity fails by far. At nx 12
// and 16 (4 096 fluid and 9 728 wall particles, about 450 steps; nx 20 takes 8 minutes on one core) the
// boundary layers, about Re^-1/2 = 0.1 thick, span 1.2-1.6 particles and the vortex is too weak (v by 24 %
// and 14 % in a least-squares fit to the reference), a deficit that falls at second order: measured
// 3.36 % and 3.65 % at nx 12, 1.95 % and 2.11 % at nx 16, orders 1.89 and 1.91. (With -ppe_wall_velocity
// prescribed, the default before, 1.34 % and 1.17 % at nx 16: the lid's corner term in the source
// offsets part of the deficit, docs/verification/lid_driven_cavity_3d.md.) The test asserts the order, and a bound at nx 16.
TEST(Walls, IsphCubicCavityRe100ConvergesToTheReference) {
  const char* options = "-case lid_driven_cavity -dim 3 -re 100 -output_interval 0 -checkpoint_interval 0 -nx ";
  const auto coarse = run_sph("cavity3d_isph_12", std::string(options) + "12");
  const auto fine = run_sph("cavity3d_isph_16", std::string(options) + "16");
  ASSERT_EQ(coarse.exit_code, 0);
  ASSERT_EQ(fine.exit_code, 0);
  EXPECT_EQ(fine.summary["dim"], 3);
  for (const auto* r : {&coarse, &fine}) EXPECT_TRUE(r->summary["steady_state_reached"].get<bool>());
  for (const char* name : {"centreline_rms_u", "centreline_rms_v"}) {
    EXPECT_LT(error(fine, name), 0.03) << name;
    EXPECT_GT(std::log(error(coarse, name) / error(fine, name)) / std::log(16.0 / 12.0), 1.5) << name;
  }
}

// Every 3D reference table is found and read (Re 400: the finite-difference table; Re 1000:
// Albensoeder & Kuhlmann): after one step the fluid is nearly at rest, so the norms are close to the
// RMS of each table's interior values (u, v: 0.17, 0.18 at Re 400; 0.28, 0.25 at Re 1000; measured
// 0.172, 0.176 and 0.288, 0.240).
TEST(Walls, CubicCavityReadsItsReferenceTables) {
  for (const char* re : {"400", "1000"}) {
    const auto r = run_sph(std::string("cavity3d_tables_") + re, std::string("-case lid_driven_cavity -dim 3 -nx 8 -re ") + re +
                                                                     " -max_steps 1 -output_interval 0 -checkpoint_interval 0");
    ASSERT_EQ(r.exit_code, 0) << re;
    EXPECT_GT(error(r, "centreline_rms_u"), 0.15) << re;
    EXPECT_LT(error(r, "centreline_rms_u"), 0.30) << re;
    EXPECT_GT(error(r, "centreline_rms_v"), 0.15) << re;
    EXPECT_LT(error(r, "centreline_rms_v"), 0.30) << re;
  }
}

TEST(Walls, ThinWallLayersAreRefused) {
  const auto r = run_sph("cavity_thin", "-case lid_driven_cavity -nx 16 -wall_layers 2");
  EXPECT_NE(r.exit_code, 0);
}

}  // namespace
