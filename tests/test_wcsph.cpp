// End-to-end: the explicit WCSPH twin on the Taylor-Green vortex, on the same kernels and neighbour
// search as ISPH, against the exact solution; its conservation of momentum; its acoustics.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

// Same derivation as the ISPH test: errors must stay below 10% of the physical decay at t = 1.
const double physical_decay = 1.0 - std::exp(-8.0 * M_PI * M_PI / 100.0);

TEST(Wcsph, TaylorGreenMatchesAnalyticDecay) {
  const auto r = run_sph("tgv_wcsph_32", "-case taylor_green -solver wcsph -nx 32 -re 100 -t_end 1");
  ASSERT_EQ(r.exit_code, 0);
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "completed");
  EXPECT_LT(s["errors"]["l1_velocity"].get<double>(), 0.1 * physical_decay);
  EXPECT_LT(s["errors"]["decay_rel"].get<double>(), 0.1 * physical_decay);
  EXPECT_EQ(s["models"]["equation_of_state"]["model"], "Tait");
  EXPECT_FALSE(s.contains("ksp"));  // no linear solve in an explicit scheme
}

// Pairwise antisymmetric pressure and AV forces, symmetric Morris viscosity, periodic images with the
// same geometry on both sides: total momentum is conserved to round-off (shifting is off: its Taylor
// correction is not a pairwise exchange).
TEST(Wcsph, ConservesMomentumToRoundOff) {
  const auto r = run_sph("wcsph_momentum",
                         "-case taylor_green -solver wcsph -nx 24 -t_end 0.2 -shifting 0 "
                         "-av_alpha 0.1 -density_diffusion none -wcsph_pressure_gradient symmetric "
                         "-wcsph_operators classic");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_LT(r.summary["conservation"]["momentum_drift"].get<double>(), 1e-13);
}

TEST(Wcsph, DensityOptionsAreReported) {
  const auto r = run_sph("wcsph_options",
                         "-case taylor_green -solver wcsph -nx 16 -t_end 0.02 -density_diffusion antuono "
                         "-av_alpha 0.02");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["models"]["density_diffusion"]["model"], "Antuono");
  EXPECT_EQ(r.summary["models"]["artificial_viscosity"]["alpha"], 0.02);
}

// Dam break: the released column's pressure cannot drop at once in a weakly compressible fluid, so
// it rings across the column as a quarter-wave standing wave: closed at the left wall, open at the
// free face, period 4 a / c0 (linear acoustics). The foot pressure's period, from its crossings of its
// mean over t = 0.3-1.5, is checked against that for two sound speeds (measured at nx 16: 0.207 and
// 0.105 against 0.2 and 0.1; 10% allows for the column widening as it collapses). This is why WCSPH's
// pressure differs from ISPH's pointwise while the period means agree (docs/verification/dam_break.md).
double foot_pressure_period(const std::string& dir) {
  std::ifstream in(dir + "/front_position.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "T,Z,P_foot,P_far,H");
  std::vector<double> t, p;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string T_text, Z_text, P_text;
    std::getline(fields, T_text, ','), std::getline(fields, Z_text, ','), std::getline(fields, P_text, ',');
    const double T = std::stod(T_text), P = std::stod(P_text);
    const double time = T * std::sqrt(0.5);  // T = t sqrt(2 g / a), a = g = 1
    if (time > 0.3 && time < 1.5) t.push_back(time), p.push_back(P);
  }
  if (t.size() < 10) return std::nan("");
  double mean = 0.0;
  for (double v : p) mean += v / p.size();
  // Upward crossings, with a band of 0.25 rho g a so that noise does not count as a crossing.
  std::vector<double> up;
  bool below = false;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (p[k] < mean - 0.25) below = true;
    if (below && p[k] > mean + 0.25) up.push_back(t[k]), below = false;
  }
  return up.size() < 3 ? std::nan("") : (up.back() - up.front()) / (up.size() - 1);
}

TEST(Wcsph, DamBreakPressureRingsAtTheQuarterWavePeriod) {
  for (const double factor : {10.0, 20.0}) {
    const auto r = run_sph(
        "dam_break_ringing_" + std::to_string(static_cast<int>(factor)),
        "-case dam_break -solver wcsph -nx 16 -t_end 1.5 -output_interval 0 -c0_factor " + std::to_string(factor));
    ASSERT_EQ(r.exit_code, 0);
    const double c0 = r.summary["models"]["equation_of_state"]["c0"].get<double>();
    EXPECT_NEAR(foot_pressure_period(r.output_dir), 4.0 / c0, 0.1 * 4.0 / c0) << "c0 = " << c0;
  }
}

}  // namespace
