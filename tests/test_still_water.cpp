// End-to-end: free surfaces with known answers. Still water must stay still (the hydrostatic state it
// starts in), and the elliptical drop must follow the ODE of its semi-axes (Monaghan 1994), with both
// schemes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

// Still water at 20 particles a unit: the hydrostatic pressure to 1 % of rho g H, no particle moved by
// half a spacing, the level to 0.5 % (the verification table's bounds at t = 50). ISPH to t = 20 (40
// time units sqrt(H/g)), measured 2.1e-4, 0.003 dx, -2.1e-4. WCSPH to t = 50, where its surface layer
// used to sink (the density diffusion drained it: level -0.58 %, drift 0.83 dx); measured 1.4e-3,
// 0.035 dx, -1.5e-3 (its hydrostatic compression, rho g H / (2 rho c0^2) = 2.5e-3, is most of that
// level; 0.12 dx with Wendland C2 at 3 dx, whose lattice slips by a spacing from nx 40). Shifting at the
// flow's speed, WCSPH's density diffusion, Fourtakas' form kept from draining the surface layer, and
// its free-surface kernel are what keep the scene still (docs/verification/free_surface.md).
void expect_still(const std::string& solver, double t_end, const std::string& more = "-nx 20") {
  const auto r = run_sph(
      "still_water_" + solver + (more == "-nx 20" ? "" : "_3d"),
      "-case still_water -solver " + solver + " " + more + " -output_interval 0 -t_end " + std::to_string(t_end));
  ASSERT_EQ(r.exit_code, 0) << r.summary.dump();
  const auto& e = r.summary["errors"];
  std::printf("%s still water t = %g: hydrostatic_l1_rel %.2e, max_drift_dx %.3f, level_rel %.2e\n", solver.c_str(),
              t_end, e["hydrostatic_l1_rel"].get<double>(), e["max_drift_dx"].get<double>(),
              e["level_rel"].get<double>());
  EXPECT_LT(e["hydrostatic_l1_rel"].get<double>(), 0.01);
  EXPECT_LT(e["max_drift_dx"].get<double>(), 0.5);
  EXPECT_LT(std::abs(e["level_rel"].get<double>()), 0.005);
}

TEST(StillWater, IsphStaysStill) { expect_still("isph", 20.0); }
TEST(StillWater, WcsphStaysStillToFifty) { expect_still("wcsph", 50.0); }

// In 3D the particles where two side walls meet the surface were not flagged (div r 2.53 against the
// threshold 2.4) and sank: ISPH's largest drift was 1.52 dx at nx 10 by t = 2, now 0.005 dx
// (docs/verification/free_surface.md, "Surface particles in the corners").
TEST(StillWater, IsphStaysStillIn3D) { expect_still("isph", 2.0, "-dim 3 -nx 10"); }

// The drop to A0 t = 0.8 (a = 2.0 R) at 10 and 20 particles across its radius. Measured semi-axis
// errors: ISPH 1.5e-2, 3.9e-3 (40: 4.5e-4); WCSPH (the quintic spline at 2.79 dx, its free-surface
// default) 5.9e-3, 1.3e-3 for a and 8.8e-3, 8.3e-3 for b (40, 80: a 6.0e-4, 2.2e-4; b 7.5e-3, 3.9e-3:
// b converges slowly, docs/verification/free_surface.md, "Elliptical drop").
struct DropErrors {
  double a, b;
};
DropErrors drop(const std::string& solver, int nx) {
  const auto r = run_sph("drop_" + solver + std::to_string(nx), "-case elliptical_drop -solver " + solver + " -nx " +
                                                                    std::to_string(nx) + " -output_interval 0");
  EXPECT_EQ(r.exit_code, 0) << r.summary.dump();
  if (r.summary.is_null() || !r.summary["errors"].contains("semi_axis_rel")) return {NAN, NAN};
  const auto& e = r.summary["errors"];
  std::printf("%s drop nx %d: semi_axis_rel %.2e, semi_axis_b_rel %.2e\n", solver.c_str(), nx,
              e["semi_axis_rel"].get<double>(), e["semi_axis_b_rel"].get<double>());
  return {e["semi_axis_rel"].get<double>(), e["semi_axis_b_rel"].get<double>()};
}

TEST(EllipticalDrop, IsphFollowsTheOdeAndConverges) {
  const DropErrors coarse = drop("isph", 10), fine = drop("isph", 20);
  EXPECT_LT(fine.a, 0.01);
  EXPECT_LT(fine.b, 0.01);
  EXPECT_LT(fine.a, 0.5 * coarse.a);  // at least first order
}

TEST(EllipticalDrop, WcsphFollowsTheOdeAndConverges) {
  const DropErrors coarse = drop("wcsph", 10), fine = drop("wcsph", 20);
  EXPECT_LT(fine.a, 0.01);
  EXPECT_LT(fine.b, 0.01);
  EXPECT_LT(fine.a, 0.5 * coarse.a);  // at least first order
  EXPECT_LT(fine.b, coarse.b);
}

}  // namespace
