// The cavity's time-averaged centreline profiles (-profile_average_from): the average is the dt-weighted
// mean of the profiles over the steps that start inside the window, checked against the profile of the
// dt-weighted mean velocity field (the probe fit is linear in the velocities at fixed positions), and it
// carries over a restart bit for bit.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <string>
#include <vector>

#include "cases/lid_driven_cavity/lid_driven_cavity.hpp"
#include "run_sph.hpp"
#include "src/core/domain.hpp"

namespace {

using V2 = sph::Vector<2>;

sph::LidDrivenCavity<2> make_cavity(const char* average_from) {
  PetscOptionsSetValue(nullptr, "-nx", "20");
  PetscOptionsSetValue(nullptr, "-profile_average_from", average_from);
  sph::LidDrivenCavity<2> cavity;
  cavity.set_from_options();
  for (const char* name : {"-nx", "-profile_average_from"}) PetscOptionsClearValue(nullptr, name);
  return cavity;
}

// A flow unlike the reference's, scaled by a(t); the probes see its values only through the fit.
V2 shape(const V2& x) { return V2(std::sin(3.0 * x[1]) - 0.4 * x[0], 0.7 * x[0] * x[0] - std::cos(2.0 * x[1])); }
double amplitude(double t) { return 0.3 + 0.5 * t * t; }

void set_velocity(sph::Particles<2>& P, double a) {
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == sph::kFluid) P.v[i] = a * shape(P.x[i]);
}

TEST(CavityAverage, IsTheDtWeightedMeanOfTheProfilesInsideTheWindow) {
  sph::LidDrivenCavity<2> averaged = make_cavity("0.5"), instant = make_cavity("-1");
  sph::Particles<2> P;
  sph::Domain<2> domain;
  averaged.create(P, domain);
  // Uneven steps, some before the window: the mean weights each step's end-of-step profile by its dt.
  const std::vector<double> dts = {0.2, 0.25, 0.05, 0.3, 0.1, 0.4, 0.15};
  double t = 0.0, weighted = 0.0, weight = 0.0, unweighted = 0.0, all_steps = 0.0;
  int count = 0;
  for (double dt : dts) {
    t += dt;
    set_velocity(P, amplitude(t));
    averaged.accumulate(P, t, dt);
    all_steps += dt * amplitude(t) / 1.45;  // the steps' dt sum to 1.45
    if (t - dt < 0.5 - 1e-12) continue;
    weighted += dt * amplitude(t), weight += dt;
    unweighted += amplitude(t), ++count;
  }
  ASSERT_GT(weight, 0.0);
  // The reference: the instantaneous metric of the field scaled by the mean amplitude.
  set_velocity(P, weighted / weight);
  const auto expected = instant.errors(P, -1.0);
  const auto got = averaged.errors(P, -1.0);
  EXPECT_NEAR(got.at("centreline_rms_u_averaged"), expected.at("centreline_rms_u"), 1e-13);
  EXPECT_NEAR(got.at("centreline_rms_v_averaged"), expected.at("centreline_rms_v"), 1e-13);
  // Averaging every step instead, or without the dt weights, would give another value.
  for (double wrong : {unweighted / count, all_steps}) {
    set_velocity(P, wrong);
    EXPECT_GT(std::abs(got.at("centreline_rms_u_averaged") - instant.errors(P, -1.0).at("centreline_rms_u")), 1e-3);
  }
  EXPECT_EQ(instant.errors(P, -1.0).count("centreline_rms_u_averaged"), 0u);
}

TEST(CavityAverage, IsNotMeasuredBeforeItsWindowAndSaysWhy) {
  sph::LidDrivenCavity<2> cavity = make_cavity("2");
  sph::Particles<2> P;
  sph::Domain<2> domain;
  cavity.create(P, domain);
  set_velocity(P, 1.0);
  cavity.accumulate(P, 1.0, 0.1);
  const auto e = cavity.errors(P, 1.0);
  EXPECT_TRUE(std::isnan(e.at("centreline_rms_u_averaged")));
  EXPECT_TRUE(std::isfinite(e.at("centreline_rms_u")));
  EXPECT_NE(cavity.unmeasured_reason("centreline_rms_v_averaged").find("-profile_average_from 2"), std::string::npos);
  EXPECT_EQ(cavity.accumulated_state()["weight"], 0.0);
}

// The average's sums travel in the checkpoint: a run resumed inside the window ends with the averaged
// errors, and the timeseries, of the uninterrupted run (A straight to t = 0.2; B stops at step 20,
// t = 0.1; C resumes B).
TEST(CavityAverage, CarriesOverARestartExactly) {
  const std::string common =
      "-case lid_driven_cavity -nx 10 -solver isph -profile_average_from 0.05 -steady_tol 0 "
      "-t_end 0.2 -dt 0.005 -output_interval 0.05 -checkpoint_interval 0.1";
  const auto a = sph::testing::run_sph("cavity_average_a", common);
  const auto b = sph::testing::run_sph("cavity_average_b", common + " -max_steps 20");
  ASSERT_EQ(a.exit_code, 0);
  ASSERT_EQ(b.exit_code, 0);
  const auto c = sph::testing::run_sph("cavity_average_c", common + " -restart " + b.output_dir + "/checkpoint.bin");
  ASSERT_EQ(c.exit_code, 0);
  ASSERT_TRUE(a.summary["errors"]["centreline_rms_u_averaged"].is_number());
  EXPECT_EQ(c.summary["errors"], a.summary["errors"]);
  // B stopped inside the window: its own average covers t = 0.05 to 0.1 only, so it differs.
  EXPECT_NE(b.summary["errors"]["centreline_rms_u_averaged"], a.summary["errors"]["centreline_rms_u_averaged"]);
}

}  // namespace
