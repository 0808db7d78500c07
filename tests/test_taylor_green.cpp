// End-to-end: the sph program on the Taylor-Green vortex against its exact solution.
#include <gtest/gtest.h>

#include <cmath>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

// Bounds derived from the analytic solution: at Re = 100, t = 1 the vortex has lost
// 1 - e^{-8 pi^2 / 100} = 55% of its speed. A scheme that gets the physics right must reproduce that
// decay to a small fraction of it; we require errors below 10% of the decay itself (5.5%). A solver
// that froze the initial field would score 55% / 45% = 120% on l1_velocity, and one without the
// viscous term far above the bound on decay_rel.
const double physical_decay = 1.0 - std::exp(-8.0 * M_PI * M_PI / 100.0);

TEST(TaylorGreen, IsphMatchesAnalyticDecayAndConverges) {
  const auto coarse = run_sph("tgv_isph_32", "-case taylor_green -solver isph -nx 32 -re 100 -t_end 1");
  const auto fine = run_sph("tgv_isph_48", "-case taylor_green -solver isph -nx 48 -re 100 -t_end 1");
  ASSERT_EQ(coarse.exit_code, 0);
  ASSERT_EQ(fine.exit_code, 0);
  for (const auto* r : {&coarse, &fine}) {
    const auto& s = r->summary;
    EXPECT_EQ(s["status"], "completed");
    EXPECT_LT(s["errors"]["l1_velocity"].get<double>(), 0.1 * physical_decay);
    EXPECT_LT(s["errors"]["decay_rel"].get<double>(), 0.1 * physical_decay);
    EXPECT_LT(s["errors"]["l1_pressure"].get<double>(), 0.1);
    // The consistent Laplacian makes the PPE non-symmetric: GMRES by default.
    EXPECT_EQ(s["ksp"]["type"], "gmres");
    EXPECT_EQ(s["ksp"]["pc_type"], "hypre");
  }
  // The error splits into the amplitude's and the shape's: |u - u_e| <= |u - a u_e| + |a - 1| |u_e|,
  // and |u_e| <= U e^{bt}. On this run most of the error is the amplitude's (the decay rate).
  for (const auto* r : {&coarse, &fine}) {
    const auto& e = r->summary["errors"];
    const double l1 = e["l1_velocity"], shape = e["l1_velocity_shape"], amplitude = e["amplitude_rel"];
    EXPECT_LE(l1, shape + std::abs(amplitude) + 1e-12);
    EXPECT_LT(shape, 0.5 * l1);
  }
  // Refinement reduces the error.
  EXPECT_LT(fine.summary["errors"]["l1_velocity"].get<double>(), coarse.summary["errors"]["l1_velocity"].get<double>());
  EXPECT_LT(fine.summary["errors"]["decay_rel"].get<double>(), coarse.summary["errors"]["decay_rel"].get<double>());
  // AMG keeps the iteration count flat under refinement.
  EXPECT_LE(fine.summary["ksp"]["iterations_max"].get<int>(), coarse.summary["ksp"]["iterations_max"].get<int>() + 3);
}

TEST(TaylorGreen, SummaryCarriesRequiredFields) {
  const auto r = run_sph("tgv_fields", "-case taylor_green -nx 16 -t_end 0.05");
  ASSERT_EQ(r.exit_code, 0);
  for (const char* key : {"case", "solver", "dim", "n_particles", "steps", "t_end", "wall_time_s",
                          "time_per_particle_step_s", "ksp", "errors", "models", "status"})
    EXPECT_TRUE(r.summary.contains(key)) << key;
  EXPECT_EQ(r.summary["n_particles"], 256);
  EXPECT_EQ(r.summary["dim"], 2);
  for (const char* key : {"type", "pc_type", "iterations_mean", "iterations_max"})
    EXPECT_TRUE(r.summary["ksp"].contains(key)) << key;
  for (const char* key : {"l1_velocity", "linf_velocity", "decay_rel", "amplitude_rel", "l1_velocity_shape", "l1_pressure"})
    EXPECT_TRUE(r.summary["errors"].contains(key)) << key;
  EXPECT_TRUE(r.summary["models"].contains("shifting"));
  EXPECT_TRUE(r.summary["models"].contains("viscosity"));
}

TEST(TaylorGreen, ShiftingOffIsReportedAndCostsNothing) {
  const auto r = run_sph("tgv_noshift", "-case taylor_green -nx 16 -t_end 0.05 -shifting 0");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_FALSE(r.summary["models"].contains("shifting"));
}

}  // namespace
