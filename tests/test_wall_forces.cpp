// Forces on bodies and walls (src/sph/wall_forces.hpp, timeseries.csv's force columns), against
// Archimedes and the momentum balance; and that writing them leaves the run bitwise the same.
// docs/verification/body_forces.md has the convergence tables.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/run_sph.hpp"

namespace {

using sph::testing::run_sph;
using sph::testing::RunResult;
using sph::testing::timeseries_column;

const std::string kScene = std::string(SPH_SOURCE_DIR) + "/cases/scenes/submerged_cylinder.yaml";
constexpr double kRadius = 0.2, kCx = 1.0, kCy = 0.5;

// The body's area as sampled at spacing dx: lattice points (i + 1/2) dx inside the circle, each dx^2
// (the YAML sampler's lattice, cases/scene/scene_yaml.hpp), counted here by brute force.
double sampled_area(int nx) {
  const double dx = 1.0 / nx;
  long inside = 0;
  for (int i = 0; (i + 0.5) * dx < 2.0; ++i)
    for (int j = 0; (j + 0.5) * dx < 1.0; ++j) {
      const double x = (i + 0.5) * dx - kCx, y = (j + 0.5) * dx - kCy;
      inside += x * x + y * y <= kRadius * kRadius + 1e-12;
    }
  return static_cast<double>(inside) * dx * dx;
}

// The mean of a column over the last quarter of the run (WCSPH's acoustic waves still ring).
double late_mean(const std::vector<double>& v) {
  const std::size_t from = 3 * v.size() / 4;
  double sum = 0;
  for (std::size_t k = from; k < v.size(); ++k) sum += v[k];
  return v.size() > from ? sum / static_cast<double>(v.size() - from) : std::nan("");
}

// A cylinder held in still water (rho0 = 1, g = 1) feels rho g V upwards. Its pressure force summed
// over its surface (the default) gives V = pi R^2, the circle's area; summed over the wall-fluid pairs
// it gives the area the particles sample, 3.4 % above pi R^2 at 20 particles a unit. Measured at nx 20:
// ISPH 0.9992 rho g pi R^2 from the surface, 0.995 rho g V_sampled from the pairs (t = 1); WCSPH 1.00x
// (mean over t in [2.25, 3]) (docs/verification/body_forces.md).
void expect_archimedes(const std::string& solver, double t_end, const std::string& method = "surface") {
  const int nx = 20;
  const RunResult r =
      run_sph("wall_forces_buoyancy_" + solver + "_" + method,
              "-case scene -scene_file " + kScene + " -nx 20 -solver " + solver + " -t_end " + std::to_string(t_end) +
                  " -output_interval 0 -threads 1 -body_pressure_force " + method);
  ASSERT_EQ(r.exit_code, 0);
  const double weight_displaced = method == "surface" ? M_PI * kRadius * kRadius : sampled_area(nx);  // rho0 g V
  const double lift = late_mean(timeseries_column(r, "force_c_y"));
  EXPECT_NEAR(lift / weight_displaced, 1.0, 0.01) << solver << ": lift " << lift << ", rho g V " << weight_displaced;
  EXPECT_NEAR(late_mean(timeseries_column(r, "force_c_x")), 0.0, 1e-6 * weight_displaced);
  EXPECT_NEAR(late_mean(timeseries_column(r, "moment_c")), 0.0, 1e-6 * weight_displaced * kRadius);
  // At rest the walls and the body together carry the fluid's weight (the fluid's particles fill the
  // tank less the sampled body).
  const double fluid_weight = (2.0 - sampled_area(nx));
  const double carried =
      late_mean(timeseries_column(r, "force_c_y")) + late_mean(timeseries_column(r, "force_walls_y"));
  EXPECT_NEAR(-carried / fluid_weight, 1.0, 0.01) << solver;
}

TEST(WallForces, IsphSubmergedCylinderFeelsArchimedes) { expect_archimedes("isph", 1.0); }
TEST(WallForces, IsphSubmergedCylinderFeelsArchimedesFromThePairs) { expect_archimedes("isph", 1.0, "pairs"); }
TEST(WallForces, WcsphSubmergedCylinderFeelsArchimedes) { expect_archimedes("wcsph", 3.0); }

// The force columns are read-only: a run writing them ends in the same state, bit for bit.
TEST(WallForces, WritingThemLeavesTheRunUnchanged) {
  for (const std::string solver : {"isph", "wcsph"}) {
    const std::string common =
        "-case scene -scene_file " + kScene + " -nx 20 -solver " + solver + " -t_end 0.3 -output_interval 0 -threads 1";
    const RunResult with = run_sph("wall_forces_on_" + solver, common + " -wall_forces 1");
    const RunResult without = run_sph("wall_forces_off_" + solver, common + " -wall_forces 0");
    ASSERT_EQ(with.exit_code, 0);
    ASSERT_EQ(without.exit_code, 0);
    EXPECT_FALSE(timeseries_column(with, "force_c_y").empty());
    EXPECT_TRUE(timeseries_column(without, "force_c_y").empty());
    const std::string a = sph::testing::checkpoint_state(with.output_dir + "/checkpoint.bin");
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == sph::testing::checkpoint_state(without.output_dir + "/checkpoint.bin")) << solver;
  }
}

}  // namespace
