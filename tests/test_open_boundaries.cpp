// The open boundaries' bookkeeping (src/boundary/open_boundaries.hpp) on a hand-made channel along x,
// the box from x = 0 to 1, an inlet buffer beyond x = 0 and an outlet buffer beyond x = 1, both 3 dx
// deep: what becomes fluid, what is made and with which id, what leaves, and the mass that crossed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "src/boundary/open_boundaries.hpp"
#include "src/kernels/kernel_options.hpp"
#include "src/neighbours/neighbourhood.hpp"

namespace {

using namespace sph;
using V2 = Vector<2>;

constexpr double kDx = 0.1, kDepth = 3 * kDx;

struct Channel {
  OpenBoundaries<2> open;
  Particles<2> P;

  Channel() {
    OpenBoundary<2> in, out;
    in.type = OpenBoundary<2>::Type::Inlet, in.axis = 0, in.side = -1, in.plane = 0.0, in.depth = kDepth;
    in.section_lo = V2(0, 0), in.section_hi = V2(0, 1);
    in.inflow.profile = InletVelocity<2>::Profile::Parabolic, in.inflow.peak = 1.5;
    out.type = OpenBoundary<2>::Type::Outlet, out.axis = 0, out.side = 1, out.plane = 1.0, out.depth = kDepth;
    out.section_lo = V2(0, 0), out.section_hi = V2(0, 1), out.pressure = 2.0;
    open = OpenBoundaries<2>({in, out});
  }
  std::size_t add(const V2& x, int kind, const V2& v = V2::Zero()) {
    P.add(x, v, kDx * kDx, 1.0, 0.0, kind);
    assign_global_indices(P);
    return P.n_owned - 1;
  }
  int count(int kind) const { return static_cast<int>(std::count(P.kind.begin(), P.kind.begin() + P.n_owned, kind)); }
};

TEST(OpenBoundaries, ParabolicInflowPeaksOnTheSectionsMiddleAndRampsFromRest) {
  Channel c;
  const OpenBoundary<2>& in = c.open.boundaries()[0];
  EXPECT_DOUBLE_EQ(in.velocity_at(V2(-0.05, 0.5), 1.0)[0], 1.5);
  EXPECT_DOUBLE_EQ(in.velocity_at(V2(-0.05, 0.25), 1.0)[0], 1.5 * 4 * 0.25 * 0.75);
  EXPECT_DOUBLE_EQ(in.velocity_at(V2(-0.05, 0.25), 1.0)[1], 0.0);
  OpenBoundary<2> ramped = in;
  ramped.inflow.ramp = 2.0;
  EXPECT_DOUBLE_EQ(ramped.velocity_at(V2(-0.05, 0.5), 0.0)[0], 0.0);
  EXPECT_NEAR(ramped.velocity_at(V2(-0.05, 0.5), 1.0)[0], 0.75, 1e-15);
  EXPECT_DOUBLE_EQ(ramped.velocity_at(V2(-0.05, 0.5), 3.0)[0], 1.5);
}

// A speed table scales the inflow: linear between its rows, held outside them, times the ramp.
TEST(OpenBoundaries, ASpeedTableScalesTheInflowLinearlyBetweenItsRows) {
  Channel c;
  OpenBoundary<2> in = c.open.boundaries()[0];
  in.inflow.table_t = {0.5, 1.0, 2.0};
  in.inflow.table_factor = {1.0, 3.0, 0.0};
  const V2 middle(-0.05, 0.5);
  EXPECT_DOUBLE_EQ(in.velocity_at(middle, 0.0)[0], 1.5);         // before the first row: its factor
  EXPECT_DOUBLE_EQ(in.velocity_at(middle, 0.75)[0], 1.5 * 2.0);  // halfway from 1 to 3
  EXPECT_DOUBLE_EQ(in.velocity_at(middle, 1.5)[0], 1.5 * 1.5);   // halfway from 3 to 0
  EXPECT_DOUBLE_EQ(in.velocity_at(middle, 5.0)[0], 0.0);         // after the last row: its factor
  EXPECT_DOUBLE_EQ(in.inflow.top_factor(), 3.0);
  in.inflow.ramp = 1.0;
  EXPECT_NEAR(in.velocity_at(middle, 0.75)[0], 1.5 * 2.0 * 0.5 * (1.0 - std::cos(0.75 * M_PI)), 1e-15);
  OpenBoundary<2> uniform = in;
  uniform.inflow.profile = InletVelocity<2>::Profile::Uniform, uniform.inflow.velocity = V2(2.0, 0.5);
  EXPECT_NEAR((uniform.velocity_at(middle, 1.5) - 1.5 * V2(2.0, 0.5)).norm(), 0.0, 1e-15);
}

// Expressions of the place give each component; ramp and table scale them as they do the others.
TEST(OpenBoundaries, ExpressionsGiveTheVelocityAtTheParticlesPlace) {
  Channel c;
  OpenBoundary<2> in = c.open.boundaries()[0];
  in.inflow.profile = InletVelocity<2>::Profile::Expressions;
  in.inflow.expressions = {Expression("6 * y * (1 - y) + x", "xy"), Expression("sin(pi * y) / 4", "xy")};
  in.inflow.expressions_top = 1.5;
  const V2 x(-0.05, 0.3);
  EXPECT_NEAR(in.velocity_at(x, 1.0)[0], 6 * 0.3 * 0.7 - 0.05, 1e-15);
  EXPECT_NEAR(in.velocity_at(x, 1.0)[1], std::sin(M_PI * 0.3) / 4, 1e-15);
  in.inflow.ramp = 2.0, in.inflow.table_t = {0.0, 4.0}, in.inflow.table_factor = {1.0, 3.0};
  EXPECT_NEAR(in.velocity_at(x, 1.0)[1], 0.5 * 1.5 * std::sin(M_PI * 0.3) / 4, 1e-15);
  EXPECT_DOUBLE_EQ(in.inflow.top_speed(), 1.5 * 3.0);
  // A copy shares the parsed expression and evaluates it at its own arguments.
  const OpenBoundary<2> copy = in;
  EXPECT_NEAR(copy.velocity_at(V2(-0.1, 0.5), 3.0)[0], (1.5 - 0.1) * 2.5, 1e-15);  // ramped up; table 2.5
  EXPECT_THROW(Expression("y * (1 - t)", "xy"), Error);
  EXPECT_THROW(Expression("y * (1 - ", "xy"), Error);
}

TEST(OpenBoundaries, AnInletParticleThatEntersIsFluidAndANewOneTakesItsPlaceADepthBehind) {
  Channel c;
  const std::size_t entering = c.add(V2(0.01, 0.45), kInlet);  // just crossed the plane
  c.add(V2(-0.05, 0.55), kInlet);                              // still in the buffer
  c.add(V2(0.5, 0.5), kFluid);
  c.open.start_ids(c.P);
  const GlobalIndex entered_id = c.P.id[entering];
  ASSERT_TRUE(c.open.exchange(c.P, 0.0, [](double) { return 1.0; }));
  EXPECT_EQ(c.count(kFluid), 2);
  EXPECT_EQ(c.count(kInlet), 2);
  // The new particle: behind the one that entered by the buffer's depth, the next id, the inflow's velocity.
  const std::size_t made = c.P.n_owned - 1;
  EXPECT_EQ(c.P.kind[made], kInlet);
  EXPECT_NEAR(c.P.x[made][0], 0.01 - kDepth, 1e-15);
  EXPECT_EQ(c.P.x[made][1], 0.45);
  EXPECT_EQ(c.P.id[made], 3);
  EXPECT_NEAR(c.P.v[made][0], 1.5 * 4 * 0.45 * 0.55, 1e-15);
  EXPECT_EQ(c.P.kind[std::find(c.P.id.begin(), c.P.id.end(), entered_id) - c.P.id.begin()], kFluid);
  EXPECT_EQ(c.open.flux().in_count, 1);
  EXPECT_DOUBLE_EQ(c.open.flux().in_mass, kDx * kDx);
  EXPECT_EQ(c.open.next_id(), 4);
}

TEST(OpenBoundaries, FluidBeyondAnOutletHoldsItsPressureAndLeavesTheRunPastTheBuffer) {
  Channel c;
  const std::size_t crossing = c.add(V2(1.02, 0.5), kFluid, V2(1, 0));
  c.add(V2(1.0 + kDepth + 0.01, 0.5), kOutlet, V2(1, 0));  // past the buffer's far end
  c.add(V2(0.98, 0.3), kOutlet, V2(-1, 0));                // came back into the box
  c.add(V2(0.5, 0.5), kFluid);
  c.open.start_ids(c.P);
  ASSERT_TRUE(c.open.exchange(c.P, 0.0, [](double p) { return 1.0 + p / 100.0; }));
  ASSERT_EQ(c.P.n_owned, 3u);  // the one past the buffer left
  EXPECT_EQ(c.P.kind[crossing], kOutlet);
  EXPECT_EQ(c.P.p[crossing], 2.0);
  EXPECT_EQ(c.P.rho[crossing], 1.02);
  EXPECT_EQ(c.count(kFluid), 2);
  // Net out through the outlet's plane: one crossed out, one came back.
  EXPECT_EQ(c.open.flux().out_count, 0);
  EXPECT_EQ(c.open.flux().out_mass, 0.0);
  // Nothing more to do: no change.
  EXPECT_FALSE(c.open.exchange(c.P, 0.0, [](double) { return 1.0; }));
}

// An open channel's outlet keeps a level: below it each outlet particle holds the hydrostatic pressure
// of its depth (with gravity along -y, or tilted), above it the outlet's own; as a particle drifts, its
// pressure follows its place; fluid crossing into it takes that pressure and its density.
TEST(OpenBoundaries, ALevelKeepingOutletHoldsTheHydrostaticPressureOfItsDepth) {
  Channel c;
  OpenBoundary<2> out = c.open.boundaries()[1];
  out.keeps_level = true, out.level = 0.6, out.rho0 = 1000.0, out.gravity = V2(0, -9.81);
  EXPECT_DOUBLE_EQ(out.pressure_at(V2(1.1, 0.2)), 2.0 + 1000.0 * 9.81 * 0.4);
  EXPECT_DOUBLE_EQ(out.pressure_at(V2(1.1, 0.6)), 2.0);
  EXPECT_DOUBLE_EQ(out.pressure_at(V2(1.1, 0.9)), 2.0);  // above the level: the outlet's pressure
  OpenBoundary<2> tilted = out;                          // the level along -g, whichever way g points
  tilted.gravity = V2(3, -4);                            // |g| = 5; up = (-0.6, 0.8)
  EXPECT_NEAR(tilted.pressure_at(V2(1.0, 0.5)), 2.0 + 1000.0 * 5.0 * (0.6 - (-0.6 * 1.0 + 0.8 * 0.5)), 1e-9);
  OpenBoundary<2> flat = out;  // no gravity (-gravity 0,0): no head
  flat.gravity = V2::Zero();
  EXPECT_EQ(flat.pressure_at(V2(1.1, 0.2)), 2.0);

  OpenBoundary<2> in = c.open.boundaries()[0];
  c.open = OpenBoundaries<2>({in, out});
  const std::size_t crossing = c.add(V2(1.02, 0.25), kFluid, V2(1, 0));
  const std::size_t drifting = c.add(V2(1.15, 0.45), kOutlet, V2(1, 0));
  auto density = [](double p) { return 1000.0 + p / 1e4; };
  ASSERT_TRUE(c.open.exchange(c.P, 0.0, density));
  EXPECT_DOUBLE_EQ(c.P.p[crossing], out.pressure_at(V2(1.02, 0.25)));
  EXPECT_DOUBLE_EQ(c.P.rho[crossing], density(c.P.p[crossing]));
  c.P.x[drifting] = V2(1.2, 0.3);
  c.open.hold_outlet_pressure(c.P, density);
  EXPECT_DOUBLE_EQ(c.P.p[drifting], 2.0 + 1000.0 * 9.81 * 0.3);
  EXPECT_DOUBLE_EQ(c.P.rho[drifting], density(c.P.p[drifting]));
}

// Outlet particles placed at rest three layers deep take the fluid's velocity, exactly, within three
// steps (each carries it at least a layer outwards, and nothing comes back from deeper layers).
TEST(OpenBoundaries, OutletParticlesTakeTheirFluidNeighboursVelocity) {
  Channel c;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 8; ++i)
      c.add(V2(0.45 + i * kDx, (j + 0.5) * kDx), i < 5 ? kFluid : kOutlet, V2(i < 5 ? 1.0 : 0.0, 0));
  Domain<2> box;
  box.lo = V2(-1, -1), box.hi = V2(2, 2);
  Kernel<2> K = KernelChoice{}.make<2>(kDx);
  Neighbourhood<2> nh(box, K.support_radius(), 0.0);
  nh.update(c.P, true);
  for (int step = 0; step < 3; ++step) c.open.extrapolate_outlet_velocity(c.P, nh.list(), K);
  for (std::size_t i = 0; i < c.P.n_owned; ++i) {
    if (c.P.kind[i] == kOutlet) {
      EXPECT_NEAR(c.P.v[i][0], 1.0, 1e-14) << "outlet particle " << i;
    }
  }
}

// A block of fluid against a transmissive outlet (src/boundary/open_boundaries.hpp): five fluid
// columns and three outlet columns, ten rows, at pressure p0 and speed u0 along x.
struct TransmissiveOutlet : Channel {
  static constexpr double kImpedance = 10.0, p0 = 2.0, u0 = 1.0;
  Domain<2> box;
  Kernel<2> K = KernelChoice{}.make<2>(kDx);
  Neighbourhood<2> nh;

  TransmissiveOutlet() : nh(make_box(), K.support_radius(), 0.0) {
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 8; ++i) {
        const std::size_t k = add(V2(0.55 + i * kDx, (j + 0.5) * kDx), i < 5 ? kFluid : kOutlet, V2(u0, 0));
        P.p[k] = p0;
      }
    open.use_transmissive_outlets(P, kImpedance);
    open.start_ids(P);
    nh.update(P, true);
  }
  static Domain<2> make_box() {
    Domain<2> b;
    b.lo = V2(-1, -1), b.hi = V2(2, 2);
    return b;
  }
  double outlet_pressure(std::size_t i) const { return P.kind[i] == kOutlet ? P.p[i] : p0; }
};

// An outgoing plane sound wave carries p' = rho0 c0 u': the outlet's pressure follows the fluid's
// velocity by that impedance, so the wave meets no jump at the outlet and is not reflected.
TEST(OpenBoundaries, ATransmissiveOutletsPressureFollowsAnOutgoingPlaneWave) {
  TransmissiveOutlet c;
  ASSERT_TRUE(c.open.transmit_outlet_pressure(c.P, c.nh.list(), c.K));  // the first call: no change
  for (std::size_t i = 0; i < c.P.n_owned; ++i) EXPECT_EQ(c.outlet_pressure(i), c.p0);
  const double du = 0.03;
  for (std::size_t i = 0; i < c.P.n_owned; ++i) c.P.v[i][0] += du;
  c.P.written(c.P.v);
  c.open.transmit_outlet_pressure(c.P, c.nh.list(), c.K);
  for (std::size_t i = 0; i < c.P.n_owned; ++i) {
    if (c.P.kind[i] == kOutlet) {
      EXPECT_NEAR(c.P.p[i], c.p0 + c.kImpedance * du, 1e-12) << "outlet particle " << i;
    }
  }
  // Called again without a change of velocity: nothing more.
  c.open.transmit_outlet_pressure(c.P, c.nh.list(), c.K);
  for (std::size_t i = 0; i < c.P.n_owned; ++i) {
    if (c.P.kind[i] == kOutlet) {
      EXPECT_NEAR(c.P.p[i], c.p0 + c.kImpedance * du, 1e-12);
    }
  }
}

// Its level relaxes to the outlet's at K = sigma c0 / L: after n steps p - p_out is (1 - K dt)^n of
// what it was.
TEST(OpenBoundaries, ATransmissiveOutletsLevelRelaxesToItsPressure) {
  TransmissiveOutlet c;
  const double sigma_c0 = 0.25 * 10.0, dt = 0.01;
  const V2 length(4.0, 3.0);                                     // K = 2.5 / 4 along the outlet's axis x
  for (std::size_t i = 0; i < c.P.n_owned; ++i) c.P.p[i] = 5.0;  // the outlet's pressure is 2
  for (int n = 0; n < 50; ++n) c.open.relax_outlet_pressure(c.P, dt, sigma_c0, length);
  for (std::size_t i = 0; i < c.P.n_owned; ++i) {
    const double expected = c.P.kind[i] == kOutlet ? 2.0 + 3.0 * std::pow(1.0 - 0.625 * dt, 50) : 5.0;
    EXPECT_NEAR(c.P.p[i], expected, 1e-13);
  }
}

// Fluid that crosses into a transmissive outlet takes the pressure the outlet holds there, not its own:
// the outlet particles around it carry the condition's memory at that place.
TEST(OpenBoundaries, FluidEnteringATransmissiveOutletTakesThePressureAroundIt) {
  TransmissiveOutlet c;
  c.open.transmit_outlet_pressure(c.P, c.nh.list(), c.K);
  std::size_t crossing = 0;
  for (std::size_t i = 0; i < c.P.n_owned; ++i) {
    if (c.P.kind[i] == kFluid && c.P.x[i][0] > 0.9 && c.P.x[i][1] > 0.4 && c.P.x[i][1] < 0.5) crossing = i;
    if (c.P.kind[i] == kOutlet) c.P.p[i] = 3.0;
  }
  c.P.x[crossing][0] = 1.01, c.P.p[crossing] = 7.0;
  ASSERT_TRUE(c.open.exchange(c.P, 0.0, [](double) { return 1.0; }));
  ASSERT_EQ(c.P.kind[crossing], kOutlet);
  EXPECT_EQ(c.P.p[crossing], 7.0);  // until the outlet's pressure is transmitted
  c.nh.update(c.P, true);
  c.open.transmit_outlet_pressure(c.P, c.nh.list(), c.K);
  EXPECT_NEAR(c.P.p[crossing], 3.0, 1e-14);
}

}  // namespace
