// Checkpoint/restart reproduces an uninterrupted run bit for bit; run-health checks stop bad runs
// with a one-line cause, status "failed" in summary.json and a non-zero exit.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "run_sph.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/run_identity.hpp"

namespace {

using sph::testing::run_sph;

// Run A goes straight to `steps` steps; run B stops halfway (where a checkpoint is due); run C resumes
// B's checkpoint to A's end. C's final checkpoint and time series must equal A's.
nlohmann::json expect_restart_is_exact(const std::string& solver, double dt,
                                       const std::string& scene = "taylor_green -nx 16", int steps = 40) {
  const std::string common = "-case " + scene + " -solver " + solver + " -t_end " + std::to_string(steps * dt) +
                             " -dt " + std::to_string(dt) + " -output_interval " + std::to_string(steps / 4 * dt) +
                             " -checkpoint_interval " + std::to_string(steps / 2 * dt);
  std::string tag = solver + "_" + scene;  // one folder per scene: ctest runs these side by side
  for (char& ch : tag)
    if (ch == ' ' || ch == '-' || ch == '/' || ch == '.') ch = '_';
  const auto a = run_sph("restart_a_" + tag, common);
  const auto b = run_sph("restart_b_" + tag, common + " -max_steps " + std::to_string(steps / 2));
  EXPECT_EQ(a.exit_code, 0);
  EXPECT_EQ(b.exit_code, 0);
  if (a.exit_code != 0 || b.exit_code != 0) return {};
  const auto c = run_sph("restart_c_" + tag, common + " -restart " + b.output_dir + "/checkpoint.bin");
  EXPECT_EQ(c.exit_code, 0);
  if (c.exit_code != 0) return {};
  EXPECT_EQ(c.summary["steps"], a.summary["steps"]);
  const std::string ca = sph::testing::checkpoint_state(a.output_dir + "/checkpoint.bin"),
                    cc = sph::testing::checkpoint_state(c.output_dir + "/checkpoint.bin");
  EXPECT_FALSE(ca.empty());
  EXPECT_TRUE(ca == cc) << "final checkpoints differ";
  EXPECT_EQ(c.summary["errors"], a.summary["errors"]);
  // Statistics over all steps, and the history of the two runs that made C.
  EXPECT_EQ(c.summary.value("ksp", nlohmann::json()).dump(), a.summary.value("ksp", nlohmann::json()).dump());
  EXPECT_EQ(c.summary["history"].size(), 2u);
  if (c.summary["history"].size() == 2) {
    EXPECT_EQ(c.summary["history"][0]["steps"], nlohmann::json({0, steps / 2}));
    EXPECT_EQ(c.summary["history"][1]["steps"], nlohmann::json({steps / 2, steps}));
  }
  return c.summary;
}

TEST(Restart, IsphMatchesUninterruptedRunExactly) { expect_restart_is_exact("isph", 0.005); }
TEST(Restart, WcsphMatchesUninterruptedRunExactly) { expect_restart_is_exact("wcsph", 0.001); }
// The free-surface flags carry over a restart (the hysteresis of -free_surface_exit_threshold).
TEST(Restart, IsphFreeSurfaceMatchesUninterruptedRunExactly) {
  expect_restart_is_exact("isph", 0.01, "dam_break -nx 12");
}
// 3D: the periodic cube, and the free surface between walls.
TEST(Restart, Isph3DMatchesUninterruptedRunExactly) { expect_restart_is_exact("isph", 0.02, "beltrami -nx 8"); }
TEST(Restart, Isph3DFreeSurfaceMatchesUninterruptedRunExactly) {
  expect_restart_is_exact("isph", 0.01, "dam_break -dim 3 -nx 6");
}

// The wall bounding (WCSPH's default at a free surface) resumes as it was: its walls' normals, taken
// again after the restart, are those of the uninterrupted run. The falling block at its defaults (the
// quintic spline at 2.79 dx), to t = 1.6: its first moves come after the checkpoint at t = 0.8 (40 at nx 20).
TEST(Restart, WcsphWallBoundingMatchesUninterruptedRunExactly) {
  const std::string scene =
      "scene -scene_file " + std::string(SPH_SOURCE_DIR) + "/cases/scenes/falling_block.yaml -nx 20 -threads 1";
  const nlohmann::json resumed = expect_restart_is_exact("wcsph", 0.0005, scene, 3200);
  ASSERT_FALSE(resumed.is_null());
  EXPECT_GT(resumed["models"]["walls"]["bounding"]["moves"].get<long>(), 0);
}

// A body with prescribed motion resumes where it was, with its velocity (both schemes).
TEST(Restart, MovingBodyMatchesUninterruptedRunExactly) {
  const std::string scene =
      "scene -scene_file " + std::string(SPH_SOURCE_DIR) + "/cases/scenes/oscillating_cylinder.yaml -nx 20";
  expect_restart_is_exact("isph", 0.005, scene);
  expect_restart_is_exact("wcsph", 0.001, scene);
}

TEST(Restart, MismatchedCheckpointIsRefused) {
  const auto b = run_sph("restart_src", "-case taylor_green -nx 16 -t_end 0.02");
  ASSERT_EQ(b.exit_code, 0);
  const auto c =
      run_sph("restart_bad", "-case taylor_green -nx 20 -t_end 0.04 -restart " + b.output_dir + "/checkpoint.bin");
  EXPECT_NE(c.exit_code, 0);
}

// A checkpoint written before the pressure solve's options took the prefix ppe_ records -ksp_rtol:
// a restart reads it as -ppe_ksp_rtol, the same option, changed or not.
TEST(Restart, CheckpointOfTheOldOptionNamesReadsThemUnderTheNewOnes) {
  const nlohmann::json saved = {{"case", "taylor_green"},
                                {"solver", "isph"},
                                {"dim", 2},
                                {"parameters", nlohmann::json::object()},
                                {"options", {{"ksp_rtol", "1e-6"}, {"nx", "16"}}}};
  nlohmann::json now = saved;
  now["options"] = {{"ppe_ksp_rtol", "1e-06"}, {"nx", "16"}};
  EXPECT_EQ(sph::check_same_run(saved, now, "checkpoint.bin"), nlohmann::json::object());
  now["options"] = {{"nx", "16"}};
  const nlohmann::json changed = {{"ppe_ksp_rtol", {{"was", "1e-6"}, {"now", "default"}}}};
  EXPECT_EQ(sph::check_same_run(saved, now, "checkpoint.bin"), changed);

  // An explicit scheme's -cfl is now -acoustic_cfl; ISPH's keeps its name.
  nlohmann::json wcsph = saved;
  wcsph["solver"] = "wcsph";
  wcsph["options"] = {{"cfl", "0.1"}, {"nx", "16"}};
  nlohmann::json wcsph_now = wcsph;
  wcsph_now["options"] = {{"acoustic_cfl", "0.1"}, {"nx", "16"}};
  EXPECT_EQ(sph::check_same_run(wcsph, wcsph_now, "checkpoint.bin"), nlohmann::json::object());
  nlohmann::json isph = wcsph, isph_now = wcsph;
  isph["solver"] = isph_now["solver"] = "isph";
  EXPECT_EQ(sph::check_same_run(isph, isph_now, "checkpoint.bin"), nlohmann::json::object());

  // The schemes' own operator choices now carry the scheme's prefix.
  isph["options"] = {{"operators", "classic"}, {"pressure_gradient", "symmetric"}};
  isph_now["options"] = {{"isph_operators", "classic"}, {"isph_pressure_gradient", "symmetric"}};
  EXPECT_EQ(sph::check_same_run(isph, isph_now, "checkpoint.bin"), nlohmann::json::object());
  wcsph["options"] = {{"operators", "classic"}};
  wcsph_now["options"] = {{"wcsph_operators", "classic"}};
  EXPECT_EQ(sph::check_same_run(wcsph, wcsph_now, "checkpoint.bin"), nlohmann::json::object());
}

// Each health check on a constructed bad state.
struct Box {
  sph::Particles<2> P;
  sph::Domain<2> domain;
  Box() {
    domain.periodic = {true, false};
    for (int k = 0; k < 4; ++k) {
      P.add(sph::Vector<2>(0.2 + 0.2 * k, 0.5), sph::Vector<2>(1.0, 0.0), 1.0, 1.0);
      P.id.back() = k;
    }
  }
};

TEST(Health, NanStopsTheRun) {
  Box b;
  EXPECT_NO_THROW(sph::check_health(b.P, b.domain, 100.0, "-cfl"));
  b.P.v[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(sph::check_health(b.P, b.domain, 100.0, "-cfl"), sph::Error);
}

TEST(Health, ParticleThroughAWallStopsTheRun) {
  Box b;
  b.P.x[1][0] = 1.5;  // periodic axis: fine (wrapped at the next rebuild)
  EXPECT_NO_THROW(sph::check_health(b.P, b.domain, 100.0, "-cfl"));
  b.P.x[1][1] = -0.01;  // below the bottom wall
  b.P.x[3][1] = 1.02;   // and another one above the top
  try {
    sph::check_health(b.P, b.domain, 100.0, "-cfl");
    FAIL() << "no error";
  } catch (const sph::Error& e) {
    // The message names the first such particle (smallest label) and where it is.
    EXPECT_NE(std::string(e.what()).find("fluid particle 1 near (1.5, -0.01) left the box"), std::string::npos)
        << e.what();
  }
}

TEST(Health, EnergyGrowthStopsTheRun) {
  Box b;
  EXPECT_NO_THROW(sph::check_health(b.P, b.domain, 2.1, "-cfl"));  // KE = 4 * 0.5
  EXPECT_THROW(sph::check_health(b.P, b.domain, 1.9, "-cfl"), sph::Error);
  b.P.v[2] = sph::Vector<2>(3.0, 0.0);  // the fastest particle is named
  try {
    sph::check_health(b.P, b.domain, 1.9, "-acoustic_cfl");
    FAIL() << "no error";
  } catch (const sph::Error& e) {
    EXPECT_NE(std::string(e.what()).find("fluid particle 2 near (0.6, 0.5) the fastest at speed 3"), std::string::npos)
        << e.what();
    // The advice names the scheme's own Courant number.
    EXPECT_NE(std::string(e.what()).find("a smaller -acoustic_cfl or -dt"), std::string::npos) << e.what();
  }
}

TEST(Health, BlowUpEndsWithFailedSummaryAndFinalFrame) {
  // A time step ten times the acoustic limit (forced past the start-up refusal): WCSPH must blow up,
  // and the run must say so.
  const auto r =
      run_sph("blowup", "-case taylor_green -solver wcsph -nx 16 -t_end 1 -dt 0.02 -dt_force 1 -output_interval 0.5");
  EXPECT_NE(r.exit_code, 0);
  ASSERT_FALSE(r.summary.is_null());
  EXPECT_EQ(r.summary["status"], "failed");
  EXPECT_FALSE(r.summary["failure"].get<std::string>().empty());
  EXPECT_TRUE(std::ifstream(r.output_dir + "/particles_00001.vtp").good());  // the failed state, for inspection
}

TEST(Health, DivergedPressureSolveStopsTheRun) {
  const auto r = run_sph("ksp_diverged",
                         "-case taylor_green -nx 16 -t_end 0.1 -ppe_ksp_type cg -ppe_pc_type none -ppe_ksp_max_it 2");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.summary["status"], "failed");
  EXPECT_NE(r.summary["failure"].get<std::string>().find("did not converge"), std::string::npos);
}

// A periodic lattice with its neighbour lists, for the neighbour-count check.
struct Lattice {
  sph::Particles<2> P;
  sph::Domain<2> domain;
  sph::Neighbourhood<2> nh{make_domain(), 0.3, 0.0};
  static sph::Domain<2> make_domain() {
    sph::Domain<2> d;
    d.periodic = {true, true};
    return d;
  }
  Lattice() {
    domain = make_domain();
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i)
        P.add(sph::Vector<2>((i + 0.5) / 20, (j + 0.5) / 20), sph::Vector<2>::Zero(), 1.0, 1.0);
    sph::assign_global_indices(P);
    nh.update(P, true);
  }
};

TEST(Health, NeighbourCountCollapseStopsTheRun) {
  for (bool free_surface : {false, true}) {
    Lattice a;  // support 0.3 = 6 dx: about 113 neighbours each
    sph::NeighbourCountCheck<2> check(free_surface, "-cfl");
    check(a.P, a.nh.list(), 0.3);  // reference counts
    EXPECT_NO_THROW(check(a.P, a.nh.list(), 0.3));
    // One particle in a void (its old neighbours out of reach): a collapse only without a free surface.
    a.P.x[210] += sph::Vector<2>(0.5, 0.5);
    if (free_surface) EXPECT_NO_THROW(check(a.P, a.nh.list(), 0.3));
    else EXPECT_THROW(check(a.P, a.nh.list(), 0.3), sph::Error);
  }
  // The whole lattice spread to twice its spacing: a quarter of the neighbours on average.
  Lattice b;
  sph::NeighbourCountCheck<2> check(true, "-cfl");
  check(b.P, b.nh.list(), 0.3);
  for (std::size_t i = 0; i < b.P.size(); ++i) b.P.x[i] *= 2.0;
  EXPECT_THROW(check(b.P, b.nh.list(), 0.3), sph::Error);
}

}  // namespace
