// Particle shifting (src/sph/shifting.hpp): the fused pair loop against the separate operators, the
// strain-rate and particle-scale forms, and the powers of its concentration term.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include "operator_lattice.hpp"
#include "src/core/integer_power.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/pair_loop.hpp"
#include "src/sph/shifting.hpp"

namespace {

using namespace sph;
using namespace sph::test;

// The shifting term's and the Tait equation's powers, by repeated squaring, agree with std::pow to
// round-off; other exponents go to std::pow itself.
TEST(Shifting, IntegerPowerMatchesStdPow) {
  for (double x : {0.0, 0.37, 1.0, 1.9, -2.5})
    for (int n = 0; n <= 9; ++n) {
      const double tolerance = 4e-16 * std::max(1.0, std::abs(std::pow(x, n)));
      EXPECT_NEAR(integer_power(x, n), std::pow(x, n), tolerance) << x << "^" << n;
      EXPECT_NEAR(power(x, n), std::pow(x, n), tolerance) << x << "^" << n;
    }
  for (double x : {0.37, 1.0, 1.01})
    for (double e : {0.5, 1.0 / 7.0, 3.5, 40.0}) EXPECT_EQ(power(x, e), std::pow(x, e)) << x << "^" << e;
}

// Shifting gathers all its sums in one fused pair loop: it must move particles and correct fields
// bitwise as the separate operators do (the concentration gradient, correction_matrices,
// vector_gradient_corrected and gradient_corrected, one pair loop each), free-surface particles and
// walls included.
TEST(Shifting, FusedPairLoopEqualsTheSeparateOperators) {
  const int nx = 16;
  Patch S(nx, kCases[0]);
  Particles<2>& P = S.P;
  const std::size_t n = P.n_owned;
  std::vector<double> f(n);
  std::vector<char> surface(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    P.v[i] = u_tg(P.x[i]);
    f[i] = 1.0 + f_s(P.x[i]);
    if (i % 7 == 0) surface[i] = 1;
    if (i % 11 == 0) P.kind[i] = kWall;
  }
  const LindShifting model;
  const double dx = 1.0 / nx;
  const NeighbourList<2>& nl = S.nh->list();

  std::vector<V2> dr(n, V2::Zero());
  const double W_dx = S.K.W(dx);
  for_each_pair(P, nl, S.K, [&](int i, int j, const PairGeometry<2>& g) {
    dr[i] += (P.m[j] / P.rho[j] * (1.0 + model.R * integer_power(g.W / W_dx, model.n))) * g.gradW;
  });
  const double U = 1.0, dt = 0.2 * S.K.h() / U;  // D = A h U dt at CFL 0.2
  for (auto& d : dr) d *= -model.coefficient(S.K.h(), U, dt);
  for (std::size_t i = 0; i < n; ++i)
    if (surface[i]) dr[i].setZero();  // free-surface particles stay put
  const std::vector<T2> L = correction_matrices(P, nl, S.K);
  const std::vector<T2> grad_u = vector_gradient_corrected(P, nl, S.K, L, P.v);
  const std::vector<V2> grad_f = gradient_corrected(P, nl, S.K, L, f);
  std::vector<V2> x = P.x, v = P.v;
  std::vector<double> f_expected = f;
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] != kFluid) continue;
    x[i] += dr[i];
    v[i] += grad_u[i].transpose() * dr[i];
    f_expected[i] += grad_f[i].dot(dr[i]);
  }

  const ShiftBoundary<2> boundary{surface, std::vector<V2>(n, V2::Zero())};
  shift_particles(P, *S.nh, S.K, model, dx, U, dt, {&f}, &boundary);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(P.x[i], x[i]) << i;
    ASSERT_EQ(P.v[i], v[i]) << i;
    ASSERT_EQ(f[i], f_expected[i]) << i;
  }
  double largest_shift = 0.0;
  for (const V2& d : dr) largest_shift = std::max(largest_shift, d.norm());
  EXPECT_GT(largest_shift, 1e-3 * dx);  // the disorder does make particles move
}

// -shift_rate strain: D = A h^2 |S| dt with S the corrected strain-rate tensor. A rigid rotation has no
// strain, so nothing moves, however disordered the particles; a simple shear u = (g y, 0) has
// |S| = g / sqrt(2) everywhere, so the shift is the speed form's times A_s h |S| / (A U) at every
// particle (the corrected gradient is exact for linear fields on any distribution).
TEST(Shifting, StrainRateShiftFollowsTheStrainNotTheRotation) {
  const int nx = 16;
  const double dx = 1.0 / nx, U = 1.0, gamma = 0.8;
  LindShifting strain;
  strain.rate = ShiftRate::Strain;
  const LindShifting speed;
  auto shifts = [&](const LindShifting& model, auto velocity) {
    Patch S(nx, kCases[0]);
    for (std::size_t i = 0; i < S.P.n_owned; ++i) S.P.v[i] = velocity(S.P.x[i]);
    const std::vector<V2> x0 = S.P.x;
    const double dt = 0.05 * S.K.h() / U;
    shift_particles(S.P, *S.nh, S.K, model, dx, U, dt);
    std::vector<V2> dr(S.P.n_owned);
    for (std::size_t i = 0; i < dr.size(); ++i) dr[i] = S.P.x[i] - x0[i];
    return std::make_pair(dr, S.K.h());
  };
  const auto [rotation, h] = shifts(strain, [](const V2& x) { return V2(-(x[1] - 0.5), x[0] - 0.5); });
  double largest = 0.0;
  for (const V2& d : rotation) largest = std::max(largest, d.norm());
  EXPECT_LT(largest, 1e-12 * dx);

  auto shear = [&](const V2& x) { return V2(gamma * x[1], 0.0); };
  const auto by_strain = shifts(strain, shear).first, by_speed = shifts(speed, shear).first;
  const double ratio = strain.coefficient_A() * h * (gamma / std::sqrt(2.0)) / (speed.coefficient_A() * U);
  double moved = 0.0;
  for (std::size_t i = 0; i < by_strain.size(); ++i) {
    EXPECT_NEAR(by_strain[i][0], ratio * by_speed[i][0], 1e-9 * dx) << i;
    EXPECT_NEAR(by_strain[i][1], ratio * by_speed[i][1], 1e-9 * dx) << i;
    moved = std::max(moved, by_strain[i].norm());
  }
  EXPECT_GT(moved, 1e-5 * dx);
}

}  // namespace

namespace {

// -shift_scales particle shifts along grad C minus its kernel average. On a lattice sheared by the
// area-preserving map x -> x + a sin(2 pi y) the number density is exactly uniform, but the kernel sum C
// varies with the local shear on the flow's scale: the whole grad C moves the particles coherently
// (mass at the resolved scale, which fixed particle volumes do not account for), the particle-scale
// part must not, and what is left of the resolved part must shrink faster than h. On a jittered
// lattice, where grad C is particle-scale noise, the two must shift alike.
std::vector<V2> shifts_with(ShiftScales scales, int nx, const std::function<V2(const V2&, int)>& place) {
  Lattice S(nx, kCases[0]);
  for (std::size_t i = 0; i < S.P.n_owned; ++i) S.P.x[i] = place(S.P.x[i], static_cast<int>(i));
  S.nh->update(S.P, true);
  const std::vector<V2> x0(S.P.x.begin(), S.P.x.begin() + S.P.n_owned);
  LindShifting model;
  model.scales = scales;
  const double U = 1.0, dt = 0.2 * S.K.h() / U;
  shift_particles(S.P, *S.nh, S.K, model, S.dx, U, dt);
  std::vector<V2> dr(S.P.n_owned);
  for (std::size_t i = 0; i < dr.size(); ++i) dr[i] = S.P.x[i] - x0[i];
  return dr;
}

double mean_norm(const std::vector<V2>& v) {
  double s = 0.0;
  for (const V2& a : v) s += a.norm();
  return s / static_cast<double>(v.size());
}

// The explicit shift dr = -D grad C is a diffusion of the particle concentration, stable for
// D <= 0.5 h^2 a step. D = A h U dt is capped there instead of bounding the step, so at a step far
// past that bound (CFL 2: D = 4 h^2 uncapped) a jittered lattice must still relax, every step, not blow up.
TEST(Shifting, ShiftRelaxesDisorderAtAnyStep) {
  Lattice S(24, kCases[0]);
  for (std::size_t i = 0; i < S.P.n_owned; ++i) {
    std::mt19937_64 rng(i + 3u);
    std::uniform_real_distribution<double> u(-0.2 * S.dx, 0.2 * S.dx);
    for (int a = 0; a < 2; ++a) S.P.x[i][a] += u(rng);
  }
  S.nh->update(S.P, true);
  auto concentration_spread = [&S] {  // RMS of C_i - 1, C_i = sum_j V_j W_ij (self term included)
    std::vector<double> C(S.P.n_owned, S.K.W(0.0) * S.dx * S.dx);
    for_each_pair(S.P, S.nl(), S.K,
                  [&](int i, int j, const PairGeometry<2>& g) { C[i] += S.P.m[j] / S.P.rho[j] * g.W; });
    double sum = 0.0;
    for (double c : C) sum += (c - 1.0) * (c - 1.0);
    return std::sqrt(sum / static_cast<double>(C.size()));
  };
  const LindShifting model;
  const double U = 1.0, dt = 2.0 * S.K.h() / U;
  const double start = concentration_spread();
  double last = start;
  for (int step = 0; step < 20; ++step) {
    shift_particles(S.P, *S.nh, S.K, model, S.dx, U, dt);
    S.nh->update(S.P, true);
    const double now = concentration_spread();
    EXPECT_LE(now, last) << "step " << step;
    last = now;
  }
  std::printf("concentration spread %.3e -> %.3e after 20 shifts at CFL 2\n", start, last);
  EXPECT_LT(last, 0.5 * start);
}

TEST(Shifting, ParticleScalesLeaveAResolvedShearedLatticeAlone) {
  auto sheared = [](const V2& x, int) {
    V2 y(x[0] + 0.05 * std::sin(k2pi * x[1]), x[1]);
    y[0] -= std::floor(y[0]);
    return y;
  };
  double ratio[2];
  const int nx[] = {32, 64};
  for (int k = 0; k < 2; ++k) {
    const double all = mean_norm(shifts_with(ShiftScales::All, nx[k], sheared));
    const double particle = mean_norm(shifts_with(ShiftScales::Particle, nx[k], sheared));
    ratio[k] = particle / all;
    std::printf("sheared lattice nx %d: mean shift all %.3e, particle %.3e (ratio %.3e)\n", nx[k], all, particle,
                ratio[k]);
  }
  EXPECT_LT(ratio[0], 0.1);
  EXPECT_GT(std::log2(ratio[0] / ratio[1]), 1.5);  // the resolved part left falls faster than h
}

TEST(Shifting, ParticleScalesKeepTheShiftOfParticleScaleDisorder) {
  const int nx = 32;
  const double dx = 1.0 / nx;
  auto jittered = [dx](const V2& x, int i) {
    std::mt19937_64 rng(static_cast<unsigned long>(i) + 7u);
    std::uniform_real_distribution<double> u(-0.1 * dx, 0.1 * dx);
    V2 y = x + V2(u(rng), u(rng));
    for (int a = 0; a < 2; ++a) y[a] -= std::floor(y[a]);
    return y;
  };
  const std::vector<V2> all = shifts_with(ShiftScales::All, nx, jittered);
  const std::vector<V2> particle = shifts_with(ShiftScales::Particle, nx, jittered);
  std::vector<V2> difference(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) difference[i] = particle[i] - all[i];
  std::printf("jittered lattice: mean shift all %.3e, particle - all %.3e\n", mean_norm(all), mean_norm(difference));
  // The kernel average of uncorrelated noise keeps about 1/sqrt(N_eff) of it, N_eff = (sum W)^2 / sum W^2
  // ~ 10 neighbours here: 0.32.
  EXPECT_LT(mean_norm(difference), 0.35 * mean_norm(all));
}

}  // namespace
