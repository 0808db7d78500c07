// End-to-end: the explicit WCSPH twin on the Taylor-Green vortex, on the same kernels and neighbour
// search as ISPH, against the exact solution; and its conservation of momentum.
#include <gtest/gtest.h>

#include <cmath>

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
  const auto r = run_sph("wcsph_momentum", "-case taylor_green -solver wcsph -nx 24 -t_end 0.2 -shifting 0 "
                                           "-av_alpha 0.1 -density_diffusion none -pressure_gradient symmetric "
                                           "-operators classic");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_LT(r.summary["conservation"]["momentum_drift"].get<double>(), 1e-13);
}

TEST(Wcsph, DensityOptionsAreReported) {
  const auto r = run_sph("wcsph_options", "-case taylor_green -solver wcsph -nx 16 -t_end 0.02 -density_diffusion antuono "
                                          "-av_alpha 0.02");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["models"]["density_diffusion"]["model"], "Antuono");
  EXPECT_EQ(r.summary["models"]["artificial_viscosity"]["alpha"], 0.02);
}

}  // namespace
