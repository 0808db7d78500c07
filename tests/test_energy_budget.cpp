// End-to-end: every scheme's energy budget (summary.json conservation.energy_budget, timeseries.csv's
// work_* columns) closes, and its terms have the properties their physics gives them
// (src/sph/energy_budget.hpp; docs/verification/free_surface.md, "Energy budgets").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;
using sph::testing::timeseries_column;

const char* const kCauses[] = {"gravity",  "body_force",           "pressure",
                               "viscous",  "artificial_viscosity", "density_diffusion",
                               "shifting", "wall_bounding",        "removed_fluid"};

// The baffle in a closed sloshing tank (walls, a plate, a free surface, shifting; WCSPH's wall bounding
// and density diffusion): the energies' change is the causes' sum to round-off (1e-10 of the potential
// energy, the largest energy), and the last timeseries row carries the summary's running totals.
void expect_budget_closes(const std::string& solver, const std::string& extra) {
  const auto r = run_sph("energy_budget_closes_" + solver,
                         "-case scene -scene_file " + std::string(SPH_SOURCE_DIR) +
                             "/cases/scenes/baffle_sloshing.yaml -nx 10 -t_end 0.4 -output_interval 0 -solver " +
                             solver + " " + extra);
  ASSERT_EQ(r.exit_code, 0) << r.summary.dump();
  const auto& b = r.summary["conservation"]["energy_budget"];
  const double scale = b["potential_energy_start"].get<double>();
  std::printf("%s: energy change %.6e, closure %.3e, gravity released %.4e\n", solver.c_str(),
              b["energy_change"].get<double>(), b["closure"].get<double>(), b["gravity_released"].get<double>());
  EXPECT_LT(std::abs(b["closure"].get<double>()), 1e-10 * scale);
  EXPECT_GT(b["gravity_released"].get<double>(), 0.0);  // the water fell
  double sum = 0.0;
  for (const char* cause : kCauses) {
    const std::vector<double> column = timeseries_column(r, std::string("work_") + cause);
    ASSERT_FALSE(column.empty()) << cause;
    EXPECT_DOUBLE_EQ(column.back(), b["work"][cause].get<double>()) << cause;
    sum += b["work"][cause].get<double>();
  }
  EXPECT_NEAR(b["energy_change"].get<double>(), sum, 1e-10 * scale);
  EXPECT_FALSE(timeseries_column(r, "potential_energy").empty());
  EXPECT_EQ(timeseries_column(r, "internal_energy").empty(), solver == "isph");
}

TEST(EnergyBudget, IsphClosesInAClosedTank) { expect_budget_closes("isph", ""); }
TEST(EnergyBudget, WcsphClosesInAClosedTank) { expect_budget_closes("wcsph", "-av_alpha 0.02"); }

// WCSPH's symmetric pressure force and continuity equation nearly exchange energy exactly: between
// fluid particles the pressure's work is the elastic energy the compression stores, but for the
// factor rho_i / rho_j in each pair's continuity term (the exact adjoint is sum_j m_j u_ij . grad W), a
// rest of the size of the density variation, here 3e-3 of the exchange. In a periodic box without
// dissipation the pressure's total (kinetic + internal) is that rest plus the leapfrog's error, which
// falls at second order in dt. A wrong elastic energy e(rho), or a kick credited with the wrong rates,
// would leave an O(1) rest or a first-order one. Taylor-Green at Re 10^6; measured -1.30e-4, -2.23e-4,
// -2.43e-4, -2.48e-4 at dt 2, 1, 0.5, 0.25e-3 (successive differences fall 4.5x, 4.3x).
struct PressureTotal {
  double total, exchanged;
};
PressureTotal wcsph_pressure_total(double dt, const std::string& tag) {
  const auto r =
      run_sph("energy_budget_adjoint_" + tag,
              "-case taylor_green -solver wcsph -nx 16 -re 1e6 -t_end 0.2 -output_interval 0 "
              "-checkpoint_interval 0 -wcsph_pressure_gradient symmetric -density_diffusion none -shifting 0 "
              "-closed_volume 0 -dt " +
                  std::to_string(dt));
  EXPECT_EQ(r.exit_code, 0) << r.summary.dump();
  const auto& b = r.summary["conservation"]["energy_budget"];
  EXPECT_LT(std::abs(b["closure"].get<double>()), 1e-12 * b["kinetic_energy_start"].get<double>());
  const auto& pressure = b["work_by_form"]["pressure"];
  std::printf("dt %g: pressure's work %.6e, compression %.6e, total %.4e\n", dt, pressure["kinetic"].get<double>(),
              pressure["internal"].get<double>(), b["work"]["pressure"].get<double>());
  return {b["work"]["pressure"].get<double>(), std::abs(pressure["internal"].get<double>())};
}

TEST(EnergyBudget, WcsphPressureWorkIsTheCompressionsToSecondOrderInDt) {
  const PressureTotal p1 = wcsph_pressure_total(1e-3, "1"), p2 = wcsph_pressure_total(5e-4, "2"),
                      p4 = wcsph_pressure_total(2.5e-4, "4");
  const double order = std::log2(std::abs((p1.total - p2.total) / (p2.total - p4.total)));
  std::printf("order in dt: %.2f\n", order);
  EXPECT_GT(order, 1.8);
  EXPECT_LT(std::abs(p4.total), 0.01 * p4.exchanged);
}

}  // namespace
