// End-to-end: Adami et al. (2012) walls in ISPH and WCSPH, against the Poiseuille series solution
// (Morris et al. 1997) and the lid-driven cavity tables of Ghia, Ghia & Shin (1982).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

double error(const sph::testing::RunResult& r, const char* name) { return r.summary["errors"][name].get<double>(); }

// Start-up Poiseuille flow at Re = 10 to t = 1 (about the viscous time L^2/nu / 10). A wall that let
// the fluid slip would give a plug profile, an error of tens of percent; 2% at 20 particles across
// is a fifth of the smallest such failure and the error must shrink with resolution (it converges at about second
// order; docs/verification/speed_against_error.md, "Where it is worse" and "Design measurements").
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
  const auto r =
      run_sph(label, std::string("-case lid_driven_cavity -nx 30 -solver ") + solver + " -re " + std::to_string(re));
  EXPECT_EQ(r.exit_code, 0);
  if (r.exit_code != 0) return {};
  EXPECT_TRUE(r.summary["steady_state_reached"].get<bool>());
  EXPECT_LT(error(r, "centreline_rms_u"), bound_u);
  EXPECT_LT(error(r, "centreline_rms_v"), bound_v);
  return r.summary;
}

// Cavity Re = 100 at 30 x 30 particles, run to steady state. The interior Ghia values themselves have
// an RMS of about 0.35, so a stagnant or wrongly-driven cavity fails by far; the bounds sit a few times
// above the measured errors (docs/verification/lid_driven_cavity.md, "Design measurements").
TEST(Walls, IsphCavityRe100MatchesGhia) { expect_steady_cavity("cavity_isph_30", "isph", 100, 0.015, 0.02); }

// WCSPH cavity Re = 100 at 30 x 30 to steady state. The continuity equation must see walls at rest:
// with the lid's sliding velocity in it, the velocity jump where the lid ends drives a density source
// that compresses the cavity (docs/verification/lid_driven_cavity.md, "Design measurements").
//
// The box holds a fixed mass in a fixed volume, so its mean density cannot change (a conservation
// law); without -closed_volume the continuity equation's truncation error compresses it
// (docs/verification/lid_driven_cavity.md, "WCSPH in a closed box keeps its volume"). The bound, 0.1%,
// allows for the difference between the mean density and the total volume that is constrained, of the
// order of the squared density variations (Ma^2 = 1e-2 squared).
TEST(Walls, WcsphCavityRe100MatchesGhiaAndKeepsItsVolume) {
  const auto s = expect_steady_cavity("cavity_wcsph_30", "wcsph", 100, 0.015, 0.02);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["models"]["closed_volume"], true);
  EXPECT_LT(std::abs(s["conservation"]["mean_fluid_density_rel"].get<double>()), 1e-3);
}

// -lid_corners symmetric: both corner blocks at U/2. Run to t = 20 (past the transient, not to the
// steady-state stop, which fires before the errors settle), the profiles also averaged over t = 12-20.
// The 1 % bound holds the measured errors (docs/verification/lid_driven_cavity.md, "Design measurements"),
// where a corner block that drove the cavity wrongly would not.
TEST(Walls, IsphCavityWithSymmetricLidCornersMatchesGhia) {
  const auto r = run_sph("cavity_isph_30_symmetric",
                         "-case lid_driven_cavity -nx 30 -re 100 -lid_corners symmetric "
                         "-steady_tol 0 -t_end 20 -profile_average_from 12 "
                         "-output_interval 0 -checkpoint_interval 0");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["parameters"]["lid_corners"], "symmetric");
  for (const char* name :
       {"centreline_rms_u", "centreline_rms_v", "centreline_rms_u_averaged", "centreline_rms_v_averaged"})
    EXPECT_LT(error(r, name), 0.01) << name;
}

// Cavity Re = 1000 at 30 x 30 particles. Its thin corner and wall layers are where particles used to
// leave through the lid/side-wall corner (a health-check failure); the run must reach steady state
// inside the box. Ghia's Re = 1000 centreline values have RMS 0.41 (u) and 0.31 (v), so 15% still
// separates a cavity with the right vortex from a stagnant or wrong one. The boundary layers span about
// one particle at nx 30 and the vortex is too weak (docs/verification/lid_driven_cavity.md, "Against
// Ghia et al. (1982), run to steady state").
TEST(Walls, IsphCavityRe1000StaysInsideAndApproachesGhia) {
  const auto s = expect_steady_cavity("cavity_isph_30_re1000", "isph", 1000, 0.15, 0.15);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["models"]["ppe_source"]["wall_velocity"], "zero");
}

// -ppe_wall_velocity prescribed: the PPE source sees the lid's velocity, whose jump at the fixed
// downstream corner block reads as a compression that drives the vortex harder, a first-order error
// that on coarse grids at Re 1000 offsets part of the under-resolved vortex's weakness
// (docs/verification/lid_driven_cavity.md, "Against Ghia et al. (1982), run to steady state"). The run
// must stay inside the box and reach steady state.
TEST(Walls, IsphCavityRe1000WithThePrescribedWallVelocityInTheSourceStaysInside) {
  const auto r = run_sph("cavity_isph_30_re1000_prescribed",
                         "-case lid_driven_cavity -nx 30 -re 1000 "
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
// and 16 the boundary layers, about Re^-1/2 = 0.1 thick, span 1.2-1.6 particles and the vortex is too
// weak, a deficit that falls at second order (docs/verification/lid_driven_cavity_3d.md, "Re = 100" and
// "Design measurements"). The test asserts the order, and a bound at nx 16.
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
// RMS of each table's interior values (u, v: 0.17, 0.18 at Re 400; 0.28, 0.25 at Re 1000;
// docs/verification/lid_driven_cavity_3d.md, "Design measurements").
TEST(Walls, CubicCavityReadsItsReferenceTables) {
  for (const char* re : {"400", "1000"}) {
    const auto r =
        run_sph(std::string("cavity3d_tables_") + re, std::string("-case lid_driven_cavity -dim 3 -nx 8 -re ") + re +
                                                          " -max_steps 1 -output_interval 0 -checkpoint_interval 0");
    ASSERT_EQ(r.exit_code, 0) << re;
    EXPECT_GT(error(r, "centreline_rms_u"), 0.15) << re;
    EXPECT_LT(error(r, "centreline_rms_u"), 0.30) << re;
    EXPECT_GT(error(r, "centreline_rms_v"), 0.15) << re;
    EXPECT_LT(error(r, "centreline_rms_v"), 0.30) << re;
  }
}

// cases/scenes/free_slip_channel.yaml: a periodic channel between free-slip walls driven from rest by
// g = 1 along x. Without shear the fluid moves as a plug, its momentum M g t (M = 0.5) exactly; the
// same channel with no-slip walls (the slip keys removed) is held back by them (measured at t = 0.2, nx
// 20: 0.0594 of 0.1 for ISPH, 0.0590 for WCSPH; free-slip: 1 - 2.3e-4 of M g t for both).
TEST(Walls, FreeSlipWallsLeaveADrivenChannelAPlug) {
  const std::string scene = std::string(SPH_SOURCE_DIR) + "/cases/scenes/free_slip_channel.yaml";
  std::ifstream in(scene);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at; (at = text.find(", slip: free")) != std::string::npos;) text.erase(at, 12);
  const std::string no_slip = std::string(SPH_BINARY_DIR) + "/test-output/no_slip_channel.yaml";
  std::filesystem::create_directories(std::string(SPH_BINARY_DIR) + "/test-output");
  std::ofstream(no_slip) << text;
  const double plug = 0.5 * 1.0 * 0.2;  // M g t
  for (const std::string solver : {"isph", "wcsph"}) {
    const std::string common = " -nx 20 -solver " + solver + " -output_interval 0 -threads 1";
    const auto free = run_sph("free_slip_" + solver, "-case scene -scene_file " + scene + common);
    const auto held = run_sph("no_slip_" + solver, "-case scene -scene_file " + no_slip + common);
    ASSERT_EQ(free.exit_code, 0) << solver;
    ASSERT_EQ(held.exit_code, 0) << solver;
    const double m_free = sph::testing::timeseries_column(free, "momentum_x").back(),
                 m_held = sph::testing::timeseries_column(held, "momentum_x").back();
    EXPECT_NEAR(m_free / plug, 1.0, 1e-3) << solver;
    EXPECT_LT(m_held / plug, 0.7) << solver;
    // The free-slip walls feel no shear either (their viscous force is the fluid's, by Newton's third law).
    EXPECT_LT(std::abs(sph::testing::timeseries_column(free, "force_walls_viscous_x").back()), 1e-3 * 0.5)
        << solver;  // of M g
  }
}

TEST(Walls, ThinWallLayersAreRefused) {
  const auto r = run_sph("cavity_thin", "-case lid_driven_cavity -nx 16 -wall_layers 2");
  EXPECT_NE(r.exit_code, 0);
}

}  // namespace
