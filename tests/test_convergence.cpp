// Convergence in dt and in h on the Taylor-Green vortex (Re = 100, t = 1) against its exact solution,
// at resolutions that fit CI. The README's tables (cases/studies/taylor_green*.yaml) go further.
//
// What used to fail: ISPH's error grew as dt fell (nx 64: 2.2e-3, 1.5e-3, 3.7e-3 at CFL 0.2, 0.1,
// 0.05), because the projection's operators were inconsistent and shifting was defined per step;
// WCSPH's error stalled at 4.4e-3 from nx 64 on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

// The errors of a Taylor-Green run (Re 100, t = 1); null if it wrote no summary.
nlohmann::json taylor_green_errors(const std::string& tag, const std::string& args) {
  const auto r = run_sph(tag, "-case taylor_green -re 100 -t_end 1 -output_interval 0 -checkpoint_interval 0 " + args);
  EXPECT_EQ(r.exit_code, 0) << tag;
  if (r.summary.is_null()) return nullptr;
  EXPECT_EQ(r.summary["status"], "completed") << tag;
  return r.summary["errors"];
}

double l1_velocity(const std::string& tag, const std::string& args) {
  const nlohmann::json e = taylor_green_errors(tag, args);
  return e.is_null() ? NAN : e["l1_velocity"].get<double>();
}

// Halving dt at fixed h: the error approaches a limit (the spatial error), so the change from one
// halving to the next shrinks: by 25x here (measured 3.52e-3, 4.10e-3, 4.12e-3 at CFL 0.1, 0.05,
// 0.025; the limit is approached from below, the time error having the opposite sign). An error per
// step would instead grow without bound as dt falls.
TEST(Convergence, IsphErrorApproachesALimitAsDtFalls) {
  double e[3];
  const double cfl[] = {0.1, 0.05, 0.025};
  for (int k = 0; k < 3; ++k)
    e[k] = l1_velocity("conv_isph_dt" + std::to_string(k), "-solver isph -nx 32 -cfl " + std::to_string(cfl[k]));
  std::printf("ISPH nx 32, CFL 0.1 / 0.05 / 0.025: l1_velocity %.3e %.3e %.3e\n", e[0], e[1], e[2]);
  const double d1 = std::abs(e[1] - e[0]), d2 = std::abs(e[2] - e[1]);
  EXPECT_LT(d2, 0.25 * d1);        // the time error falls at least at second order
  EXPECT_LT(d2, 0.02 * e[2]);      // and is within 2% of the limit at CFL 0.05
}

// ISPH's pressure as dt falls (README, "ISPH's pressure as dt falls"). The velocity that the last
// projection made divergence-free keeps, at the particles' new positions, a particle-scale divergence
// that the projection cannot remove; the default source divides it by dt/2 every step, and l1_pressure
// creeps up without a limit (measured 2.50e-2, 2.67e-2, 2.86e-2 at CFL 0.1, 0.05, 0.025: the second
// change larger than the first). Left out of the source (-ppe_particle_divergence_rate 0), the
// pressure approaches a limit at first order or better (measured 2.26e-2, 2.46e-2, 2.54e-2: the
// second change 0.40 of the first; first order would be 0.5).
TEST(Convergence, IsphPressureApproachesALimitWithoutParticleScaleDivergence) {
  double p[3], u[3];
  const double cfl[] = {0.1, 0.05, 0.025};
  for (int k = 0; k < 3; ++k) {
    const nlohmann::json e = taylor_green_errors("conv_isph_pdt" + std::to_string(k),
                                                 "-solver isph -nx 32 -ppe_particle_divergence_rate 0 -cfl " + std::to_string(cfl[k]));
    ASSERT_FALSE(e.is_null());
    p[k] = e["l1_pressure"].get<double>(), u[k] = e["l1_velocity"].get<double>();
  }
  std::printf("ISPH nx 32, particle divergence left out, CFL 0.1 / 0.05 / 0.025: l1_pressure %.3e %.3e %.3e, "
              "l1_velocity %.3e %.3e %.3e\n", p[0], p[1], p[2], u[0], u[1], u[2]);
  EXPECT_LT(std::abs(p[2] - p[1]), 0.6 * std::abs(p[1] - p[0]));
}

// Observed order in h at the default CFL (measured: ISPH 2.18e-3 -> 1.02e-3, order 1.1; WCSPH
// 1.46e-3 -> 2.70e-4, order 2.4). ISPH's order at fixed CFL mixes the spatial error with a time
// error of the other sign (its spatial errors alone, at CFL 0.025 / 0.05: 4.12e-3 -> 1.26e-3, order 1.7).
TEST(Convergence, ObservedOrderInH) {
  const double i32 = l1_velocity("conv_isph_32", "-solver isph -nx 32");
  const double i64 = l1_velocity("conv_isph_64", "-solver isph -nx 64");
  const double w32 = l1_velocity("conv_wcsph_32", "-solver wcsph -nx 32");
  const double w64 = l1_velocity("conv_wcsph_64", "-solver wcsph -nx 64");
  std::printf("ISPH  nx 32 / 64: %.3e %.3e order %.2f\n", i32, i64, std::log2(i32 / i64));
  std::printf("WCSPH nx 32 / 64: %.3e %.3e order %.2f\n", w32, w64, std::log2(w32 / w64));
  EXPECT_GE(std::log2(i32 / i64), 1.0);
  EXPECT_GE(std::log2(w32 / w64), 1.5);
}

}  // namespace
