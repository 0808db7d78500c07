// Free bodies (src/boundary/free_body.hpp): Newton-Euler with the kick-drift-kick the schemes use,
// against closed-form motion: a throw under gravity, a pendulum on a hinge, torque-free rotation in 3D
// (angular momentum and energy conserved), constraints, and the state a checkpoint carries. The
// coupled runs (a box floating at Archimedes' draft) are in tests/cli/free_bodies.sh and
// docs/verification/free_bodies.md.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "src/boundary/moving_bodies.hpp"

namespace {

using sph::FreeBody;
using sph::Vector;

// One kick-drift-kick step with a load that does not depend on the state (gravity alone).
template <int D> void step(FreeBody<D>& f, double dt, const Vector<D>& g) {
  f.kick(0.5 * dt);
  f.drift(dt);
  f.set_load(Vector<D>::Zero(), Eigen::Vector3d::Zero(), g);
  f.kick(0.5 * dt);
}

FreeBody<2> square(double mass, double side) {
  FreeBody<2> f;
  f.active = true;
  f.mass = mass;
  f.inertia(2, 2) = mass * side * side / 6.0;
  f.centre0 = f.centre = Vector<2>(1.0, 2.0);
  return f;
}

// Under a constant acceleration the kick-drift-kick is exact: the parabola of a throw.
TEST(FreeBody, ThrowUnderGravityFollowsTheParabola) {
  FreeBody<2> f = square(3.0, 0.2);
  const Vector<2> g(0.0, -9.81), v0(1.5, 4.0), x0 = f.centre;
  f.velocity = v0;
  f.set_load(Vector<2>::Zero(), Eigen::Vector3d::Zero(), g);
  const double dt = 1e-3;
  for (int n = 1; n <= 700; ++n) step(f, dt, g);
  const double t = 700 * dt;
  EXPECT_LT((f.centre - (x0 + t * v0 + 0.5 * t * t * g)).norm(), 1e-12);
  EXPECT_LT((f.velocity - (v0 + t * g)).norm(), 1e-12);
}

// A fixed axis takes no acceleration whatever the force; a fixed rotation no spin.
TEST(FreeBody, FixedAxesHoldStill) {
  FreeBody<2> f = square(2.0, 0.3);
  f.fixed_translation = {true, false};
  f.fixed_rotation = {true, true, true};
  f.set_load(Vector<2>(5.0, 1.0), Eigen::Vector3d(0, 0, 3.0), Vector<2>(0.0, -1.0));
  EXPECT_EQ(f.acceleration[0], 0.0);
  EXPECT_DOUBLE_EQ(f.acceleration[1], 1.0 / 2.0 - 1.0);
  EXPECT_EQ(f.alpha.norm(), 0.0);
}

// A square on a hinge at distance L from its centre swings with the compound pendulum's small-angle
// period 2 pi sqrt(I_p / (m g L)), I_p = I_c + m L^2, and keeps its energy to second order in dt.
TEST(FreeBody, HingedSquareSwingsWithThePendulumsPeriod) {
  const double m = 2.0, side = 0.2, L = 0.5, gravity = 9.81;
  FreeBody<2> f = square(m, side);
  f.hinged = true;
  f.hinge = f.centre + Vector<2>(0.0, L);  // hanging below the hinge
  const Vector<2> g(0.0, -gravity);
  const double Ip = f.inertia(2, 2) + m * L * L, period = 2.0 * M_PI * std::sqrt(Ip / (m * gravity * L));
  const double theta0 = 0.01;  // small: the period's amplitude correction is theta0^2 / 16
  f.omega = Eigen::Vector3d::Zero();
  // Start at angle theta0: the centre turned about the hinge.
  const Eigen::Rotation2Dd turn(theta0);
  f.centre = f.hinge + turn * Vector<2>(f.centre - f.hinge);
  f.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitZ()));
  auto energy = [&] { return f.kinetic_energy() - m * g.dot(f.centre); };
  const double e0 = energy();
  f.set_load(Vector<2>::Zero(), Eigen::Vector3d::Zero(), g);
  const double dt = period / 2000.0;
  double t = 0.0, last_angle = f.angle(), first_crossing = -1.0, crossing = -1.0;
  int crossings = 0;
  for (int n = 0; n < 8000; ++n) {
    step(f, dt, g);
    t += dt;
    const double a = f.angle();
    if (last_angle > 0.0 && a <= 0.0) {  // downward zero crossings, interpolated
      const double tc = t - dt * a / (a - last_angle);
      if (crossings++ == 0) first_crossing = tc;
      crossing = tc;
    }
    last_angle = a;
    // The centre stays at L from the hinge: a rigid swing.
    ASSERT_NEAR((f.centre - f.hinge).norm(), L, 1e-12);
  }
  ASSERT_GE(crossings, 3);
  const double measured = (crossing - first_crossing) / (crossings - 1);
  EXPECT_NEAR(measured / period, 1.0 + theta0 * theta0 / 16.0, 2e-5);
  EXPECT_NEAR(energy(), e0, 1e-6 * std::abs(m * gravity * L * theta0 * theta0));
}

// Torque-free rotation of a body with three different moments of inertia about an axis near its
// middle (unstable) one: its angular momentum in space stays to round-off (the kicks and the drift
// keep it), its kinetic energy to second order in dt.
TEST(FreeBody, TorqueFreeRotationKeepsAngularMomentumAndEnergy) {
  FreeBody<3> f;
  f.active = true;
  f.mass = 1.0;
  f.inertia = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  f.omega = Eigen::Vector3d(0.1, 2.0, 0.1);
  const Eigen::Vector3d L0 = f.world_inertia() * f.omega;
  const double e0 = f.kinetic_energy();
  f.set_load(Vector<3>::Zero(), Eigen::Vector3d::Zero(), Vector<3>::Zero());
  std::vector<double> drift;
  for (const double dt : {2e-3, 1e-3}) {
    FreeBody<3> g = f;
    for (int n = 0; n < static_cast<int>(std::lround(4.0 / dt)); ++n) step(g, dt, Vector<3>(Vector<3>::Zero()));
    EXPECT_LT((Eigen::Vector3d(g.world_inertia() * g.omega) - L0).norm(), 1e-13 * L0.norm());
    EXPECT_NEAR(g.orientation.norm(), 1.0, 1e-14);
    drift.push_back(std::abs(g.kinetic_energy() - e0) / e0);
  }
  EXPECT_LT(drift[1], 1e-4);
  EXPECT_GT(drift[0] / drift[1], 3.0) << drift[0] << " " << drift[1];  // second order
}

// MovingBodies moves a free body's particles rigidly with its state and gives them its point velocity;
// other particles stay.
TEST(FreeBody, MovingBodiesCarriesItsParticles) {
  sph::Particles<2> P;
  const Vector<2> xs[] = {Vector<2>(0.9, 1.9), Vector<2>(1.1, 2.1), Vector<2>(3.0, 3.0)};
  for (int i = 0; i < 3; ++i) {
    P.add(xs[i], Vector<2>::Zero(), 1.0, 1.0, 0.0, i < 2 ? sph::kWall : sph::kFluid);
    P.id[static_cast<std::size_t>(i)] = i;
  }
  FreeBody<2> f = square(1.0, 0.2);
  f.velocity = Vector<2>(0.5, 0.0);
  f.omega = Eigen::Vector3d(0, 0, 2.0);
  sph::MovingBodies<2> bodies({sph::PrescribedMotion<2>{}}, {0, 0, -1}, 0.0, {}, {f});
  ASSERT_TRUE(bodies.any_free());
  const double d0 = (P.x[0] - P.x[1]).norm();
  bodies.move_to(P, 0.3);
  const FreeBody<2>& now = *bodies.free_body(0);
  EXPECT_NEAR((now.centre - Vector<2>(1.15, 2.0)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((P.x[0] - P.x[1]).norm(), d0, 1e-14);
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT((P.x[i] - now.placed(xs[i])).norm(), 1e-14);
    EXPECT_LT((P.v[i] - now.point_velocity(P.x[i])).norm(), 1e-14);
  }
  EXPECT_EQ(P.x[2], xs[2]);
  EXPECT_NEAR(now.angle(), 0.6, 1e-14);
}

// The step limit holds a free body's fastest point, the translation's speed plus the spin's at its
// farthest particle, to the given fraction of h a step.
TEST(FreeBody, StepLimitSeesTheFastestPoint) {
  FreeBody<2> f = square(1.0, 0.2);
  f.reach = 0.1 * std::sqrt(2.0);
  f.velocity = Vector<2>(3.0, 4.0);
  f.omega = Eigen::Vector3d(0, 0, 10.0);
  sph::MovingBodies<2> bodies({sph::PrescribedMotion<2>{}}, {0}, 0.0, {}, {f});
  EXPECT_DOUBLE_EQ(bodies.free_step(0.02, 0.25), 0.25 * 0.02 / (5.0 + 10.0 * f.reach));
  sph::MovingBodies<2> none({sph::PrescribedMotion<2>{}}, {0}, 0.0, {}, {});
  EXPECT_TRUE(std::isinf(none.free_step(0.02, 0.25)));
}

// The checkpoint's state gives back the same body bit for bit.
TEST(FreeBody, StateRoundTripsExactly) {
  FreeBody<3> f;
  f.active = true;
  f.centre = Vector<3>(0.1, 1.0 / 3.0, -2.0), f.velocity = Vector<3>(M_PI, 0.0, 1e-17);
  f.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  f.omega = Eigen::Vector3d(0.3, -1.0 / 7.0, 2.0), f.alpha = Eigen::Vector3d(1, 2, 3);
  f.acceleration = Vector<3>(-9.81, 1.0 / 9.0, 0.0);
  FreeBody<3> g;
  g.restore(nlohmann::json::parse(f.state().dump()));
  EXPECT_EQ(g.centre, f.centre);
  EXPECT_EQ(g.velocity, f.velocity);
  EXPECT_EQ(g.acceleration, f.acceleration);
  EXPECT_EQ(g.omega, f.omega);
  EXPECT_EQ(g.alpha, f.alpha);
  EXPECT_EQ(g.orientation.coeffs(), f.orientation.coeffs());
}

}  // namespace
