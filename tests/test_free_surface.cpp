// End-to-end: ISPH free surface (Lind et al. 2012) on the dam break against Martin & Moyce (1952)
// and on the rotating square patch.
#include <gtest/gtest.h>

#include <cmath>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

// Collapse to T = t sqrt(2g/a) = 2.5 at 16 particles across the column. The two Martin & Moyce
// series (a = 1.125 in and 2.25 in) differ by 2-3%, and simulations without the experiment's gate
// and wall friction run ahead of it: Koshizuka & Oka's MPS and most SPH results lead by 5-10% at
// T = 2-3 (we measure 10.7% for ISPH and 9.2% for WCSPH at nx = 20 to T = 3). The 15% bound is
// that lead plus the scatter; a run without a working free surface or wall pressure (a column
// that does not collapse, or falls through the floor) misses it by far.
TEST(DamBreak, IsphFrontFollowsMartinMoyce) {
  const auto r = run_sph("dam_break_isph", "-case dam_break -solver isph -nx 16 -t_end 1.77 -output_interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.summary.dump();
  EXPECT_EQ(r.summary["status"], "completed");
  EXPECT_LT(r.summary["errors"]["front_position_rel"].get<double>(), 0.15);
  EXPECT_GT(r.summary["errors"]["front_position"].get<double>(), 2.0);  // the column did collapse
  EXPECT_EQ(r.summary["models"]["free_surface"]["model"], "SurfaceNodes");
}

// The 3D column (a x 2a x a, walls in front and behind) to T = 2.5, both solvers, against the same
// experiment and the same 15 % bound (the front and back walls' friction slows the front a little against 2D's;
// docs/verification/dam_break.md, "3D dam break"). ISPH at nx 10 (2 000 fluid and 17 376 wall particles), WCSPH
// at nx 8, whose acoustic step makes it the dearer of the two.
TEST(DamBreak, FrontFollowsMartinMoyceIn3D) {
  for (const char* run : {"isph -nx 10", "wcsph -nx 8"}) {
    const std::string solver(run);
    const auto r =
        run_sph("dam_break_3d_" + solver.substr(0, solver.find(' ')),
                "-case dam_break -dim 3 -solver " + solver + " -t_end 1.77 -output_interval 0 -checkpoint_interval 0");
    ASSERT_EQ(r.exit_code, 0) << run << ": " << r.summary.dump();
    EXPECT_EQ(r.summary["dim"], 3);
    EXPECT_EQ(r.summary["status"], "completed");
    EXPECT_LT(r.summary["errors"]["front_position_rel"].get<double>(), 0.15) << run;
    EXPECT_GT(r.summary["errors"]["front_position"].get<double>(), 2.0) << run;  // the column did collapse
  }
}

}  // namespace

namespace {

// Rotating square patch (Colagrossi 2005): inviscid, so angular momentum and kinetic energy are
// invariants of the exact flow. The scheme breaks them only through the free-surface treatment and
// shifting: measured 1.1% / 1.4% at nx 24 to t = 0.5, the price of the plain PPE source next to the surface
// (docs/verification/dam_break.md, "ISPH at nx 40, a blow-up found and fixed"). A 3% bound catches a patch that
// flies apart or whose corners collapse (tensile instability).
TEST(SquarePatch, IsphKeepsInviscidInvariants) {
  const auto r = run_sph("square_patch_isph", "-case square_patch -solver isph -nx 24 -t_end 0.5 -output_interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.summary.dump();
  EXPECT_LT(r.summary["errors"]["angular_momentum_drift_rel"].get<double>(), 0.03);
  EXPECT_LT(std::abs(r.summary["errors"]["kinetic_energy_change_rel"].get<double>()), 0.03);
}

}  // namespace
