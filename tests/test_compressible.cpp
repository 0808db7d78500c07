// Compressible SPH: the exact Riemann solver against Toro's published values; the pair physics of the
// grad-h scheme (conservation pair by pair); end-to-end Sod shock tube and toy star runs of the sph
// program against their exact references, with conservation of momentum and energy.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "cases/sod/exact_riemann.hpp"
#include "run_sph.hpp"
#include "solvers/compressible/compressible_iact.hpp"
#include "src/core/error.hpp"

namespace {

using sph::ExactRiemann;
using sph::GasState;
using sph::testing::run_sph;
namespace cs = sph::compressible;

// ------------------------------------------------------------------------------------------------
// Exact Riemann solver: Toro (2009), Table 4.3 (gamma = 1.4), values published to 5-6 significant digits.

struct ToroCase {
  GasState L, R;
  double p, u, rhoL, rhoR;  // published p*, u*, rho*_L, rho*_R
};

// Half a unit of the last published digit (the table is rounded), with a hair of slack.
double published_tolerance(double v) {
  const double a = std::abs(v);
  if (a == 0.0) return 5e-6;
  const int digits = a >= 1000 ? 2 : a >= 100 ? 3 : a >= 10 ? 4 : a >= 1 ? 5 : 5;
  return 0.5 * std::pow(10.0, -digits) * 1.01;
}

TEST(ExactRiemann, ToroTest1StarRegion) {
  const ExactRiemann rs({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  EXPECT_NEAR(rs.p_star(), 0.30313, 5e-6);
  EXPECT_NEAR(rs.u_star(), 0.92745, 5e-6);
  EXPECT_NEAR(rs.rho_star_left(), 0.42632, 5e-6);
  EXPECT_NEAR(rs.rho_star_right(), 0.26557, 5e-6);
  EXPECT_FALSE(rs.left_is_shock());  // rarefaction to the left, shock to the right
  EXPECT_TRUE(rs.right_is_shock());
  EXPECT_LT(rs.iterations(), 10);
}

TEST(ExactRiemann, ToroTests2To5StarRegion) {
  const ToroCase cases[] = {
      {{1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 0.00189, 0.0, 0.02185, 0.02185},         // two rarefactions
      {{1.0, 0.0, 1000.0}, {1.0, 0.0, 0.01}, 460.894, 19.5975, 0.57506, 5.99924},  // strong shock
      {{1.0, 0.0, 0.01}, {1.0, 0.0, 100.0}, 46.0950, -6.19633, 5.99242, 0.57511},  // mirrored
      {{5.99924, 19.5975, 460.894}, {5.99242, -6.19633, 46.0950}, 1691.64, 8.68975, 14.2823, 31.0426},  // collision
  };
  int k = 2;
  for (const auto& c : cases) {
    const ExactRiemann rs(c.L, c.R, 1.4);
    // Test 5's data are tests 3 and 4's star states rounded to 6 digits, which moves its solution by
    // a few 1e-6 relative (p* = 1691.647 against the published 1691.64): relative 2e-5 there.
    auto tol = [&](double v) { return k == 5 ? 2e-5 * std::abs(v) : published_tolerance(v); };
    EXPECT_NEAR(rs.p_star(), c.p, c.p < 0.01 ? 5e-6 : tol(c.p)) << "Toro test " << k;
    EXPECT_NEAR(rs.u_star(), c.u, tol(c.u)) << "Toro test " << k;
    EXPECT_NEAR(rs.rho_star_left(), c.rhoL, tol(c.rhoL)) << "Toro test " << k;
    EXPECT_NEAR(rs.rho_star_right(), c.rhoR, tol(c.rhoR)) << "Toro test " << k;
    ++k;
  }
}

// The sampled solution: the outer states, Rankine-Hugoniot across the shock, continuity of the fan.
TEST(ExactRiemann, SampledSodSolutionIsConsistent) {
  const GasState L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  const ExactRiemann rs(L, R, 1.4);
  const double S = rs.right_head_speed();
  // Mass and momentum fluxes through the moving shock balance.
  EXPECT_NEAR(R.rho * (S - R.u), rs.rho_star_right() * (S - rs.u_star()), 1e-12);
  EXPECT_NEAR(R.p + R.rho * (S - R.u) * (S - R.u),
              rs.p_star() + rs.rho_star_right() * (S - rs.u_star()) * (S - rs.u_star()), 1e-12);
  EXPECT_NEAR(S, 1.75216, 1e-5);  // Sod's shock speed
  EXPECT_EQ(rs.sample(S + 1e-9).rho, R.rho);
  EXPECT_NEAR(rs.sample(S - 1e-9).rho, rs.rho_star_right(), 1e-12);
  EXPECT_EQ(rs.sample(-10.0).p, L.p);
  // The rarefaction fan joins its head and tail states continuously.
  const double head = rs.left_head_speed(), tail = rs.left_tail_speed();
  EXPECT_NEAR(head, -std::sqrt(1.4), 1e-14);
  EXPECT_NEAR(rs.sample(head + 1e-10).rho, L.rho, 1e-8);
  EXPECT_NEAR(rs.sample(tail - 1e-10).rho, rs.rho_star_left(), 1e-8);
  EXPECT_NEAR(rs.sample(tail - 1e-10).u, rs.u_star(), 1e-8);
  // Pressure and velocity are continuous across the contact, density jumps.
  EXPECT_NEAR(rs.sample(rs.u_star() - 1e-9).p, rs.sample(rs.u_star() + 1e-9).p, 1e-12);
  EXPECT_GT(rs.sample(rs.u_star() - 1e-9).rho - rs.sample(rs.u_star() + 1e-9).rho, 0.15);
  // Initial data at t = 0.
  EXPECT_EQ(rs.at(-0.1, 0.0).rho, L.rho);
  EXPECT_EQ(rs.at(0.1, 0.0).rho, R.rho);
}

TEST(ExactRiemann, RefusesVacuum) { EXPECT_THROW(ExactRiemann({1.0, -20.0, 0.4}, {1.0, 20.0, 0.4}, 1.4), sph::Error); }

// ------------------------------------------------------------------------------------------------
// Pair physics.

template <int D>
sph::VariableHPair<D> make_pair(const sph::Vector<D>& rij, const sph::Kernel<D>& Ki, const sph::Kernel<D>& Kj) {
  sph::VariableHPair<D> g;
  g.rij = rij, g.r = rij.norm();
  g.Wi = Ki.W(g.r), g.dWi = Ki.dWdr(g.r), g.Wj = Kj.W(g.r), g.dWj = Kj.dWdr(g.r);
  return g;
}

// dW/dh from W and dW/dr against a central difference of the shared kernels, every kernel, 1-3D.
template <int D> void check_dW_dh() {
  for (std::size_t k = 0; k < sph::kernel_names().size(); ++k) {
    const auto type = static_cast<sph::KernelType>(k);
    const double h = 0.7, dh = 1e-6;
    for (double r : {0.0, 0.3, 0.9, 1.4}) {
      const sph::Kernel<D> K(type, h), Kp(type, h + dh), Km(type, h - dh);
      const double fd = (Kp.W(r) - Km.W(r)) / (2 * dh);
      EXPECT_NEAR(cs::dW_dh(D, K.W(r), r, K.dWdr(r), h), fd, 1e-6 * (1 + std::abs(fd)))
          << sph::kernel_names()[k] << " D=" << D << " r=" << r;
    }
  }
}

TEST(CompressibleIact, KernelDerivativeWithRespectToH) {
  check_dW_dh<1>();
  check_dW_dh<2>();
  check_dW_dh<3>();
}

// With different smoothing lengths the pressure, viscous and conductive exchanges of a pair are still
// equal and opposite (momentum, thermal energy), and the viscous work equals the viscous heating.
TEST(CompressibleIact, PairExchangesAreAntisymmetricWithDifferentH) {
  constexpr int D = 2;
  using V = sph::Vector<D>;
  const sph::Kernel<D> Ki(sph::KernelType::CubicSpline, 0.8), Kj(sph::KernelType::CubicSpline, 1.1);
  const V xi(0.1, 0.2), xj(0.9, -0.3), vi(0.5, -0.1), vj(-0.4, 0.3);
  const double mi = 1.3, mj = 0.7, rho_i = 1.1, rho_j = 0.6, Pi = 1.0, Pj = 0.4, Om_i = 0.97, Om_j = 1.02;
  const double ci = std::sqrt(1.4 * Pi / rho_i), cj = std::sqrt(1.4 * Pj / rho_j);
  const double qi = Pi / (Om_i * rho_i * rho_i), qj = Pj / (Om_j * rho_j * rho_j);
  const auto gij = make_pair<D>(xi - xj, Ki, Kj), gji = make_pair<D>(xj - xi, Kj, Ki);

  const V ai = cs::pressure_acceleration(mj, qi, qj, gij), aj = cs::pressure_acceleration(mi, qj, qi, gji);
  EXPECT_LT((mi * ai + mj * aj).norm(), 1e-15 * (mi * ai).norm());
  // pdV work: the thermal energy gained is the kinetic energy lost.
  const double work = mi * vi.dot(ai) + mj * vj.dot(aj);
  const double heat = mi * cs::pdv_heating(mj, qi, V(vi - vj), gij) + mj * cs::pdv_heating(mi, qj, V(vj - vi), gji);
  EXPECT_NEAR(work + heat, 0.0, 1e-14);

  for (auto model : {cs::ViscosityModel::SignalVelocity, cs::ViscosityModel::Monaghan1992}) {
    cs::ArtificialViscosity av;
    av.model = model;
    const double Pij = av.Pi(1.0, ci, cj, rho_i, rho_j, 0.8, 1.1, V(vi - vj), gij);
    const double Pji = av.Pi(1.0, cj, ci, rho_j, rho_i, 1.1, 0.8, V(vj - vi), gji);
    ASSERT_GT(Pij, 0.0);  // the pair approaches
    EXPECT_DOUBLE_EQ(Pij, Pji);
    const V avi = cs::viscous_acceleration(mj, Pij, gij), avj = cs::viscous_acceleration(mi, Pji, gji);
    EXPECT_LT((mi * avi + mj * avj).norm(), 1e-15 * (mi * avi).norm());
    const double av_work = mi * vi.dot(avi) + mj * vj.dot(avj);
    const double av_heat =
        mi * cs::viscous_heating(mj, Pij, V(vi - vj), gij) + mj * cs::viscous_heating(mi, Pji, V(vj - vi), gji);
    EXPECT_LT(av_work, 0.0);  // dissipative
    EXPECT_NEAR(av_work + av_heat, 0.0, 1e-14);
  }
  const double ui = 2.0, uj = 1.5;
  const double qcond_i = cs::conductivity_heating(mj, 1.0, Pi, Pj, rho_i, rho_j, ui, uj, gij.dW_mean());
  const double qcond_j = cs::conductivity_heating(mi, 1.0, Pj, Pi, rho_j, rho_i, uj, ui, gji.dW_mean());
  EXPECT_LT(qcond_i, 0.0);  // heat flows from the hotter particle
  EXPECT_NEAR(mi * qcond_i + mj * qcond_j, 0.0, 1e-15);
  // Receding pairs feel no artificial viscosity.
  cs::ArtificialViscosity av;
  EXPECT_EQ(av.Pi(1.0, ci, cj, rho_i, rho_j, 0.8, 1.1, V(vj - vi), gij), 0.0);
}

// The Newton-Raphson iteration for h on a uniform 1D lattice: rho h = m eta with rho = m / dx.
TEST(CompressibleIact, SmoothingLengthIterationOnALattice) {
  constexpr int D = 1;
  const double dx = 0.01, m = 0.01, eta = 1.2;
  const sph::Kernel<D> K0(sph::KernelType::CubicSpline, 1.0);
  double h = 2.0 * eta * dx;  // a poor first guess
  cs::HBracket bracket;
  int iterations = 0;
  for (; iterations < 30; ++iterations) {
    const sph::Kernel<D> K(sph::KernelType::CubicSpline, h);
    cs::DensitySums s;
    for (int k = -20; k <= 20; ++k) {
      const double r = std::abs(k) * dx, W = K.W(r);
      s.rho += m * W;
      s.drho_dh += m * cs::dW_dh(D, W, r, K.dWdr(r), h);
    }
    const double h_new = cs::newton_h_update(D, m, eta, h, s, bracket);
    if (std::abs(h_new - h) < 1e-12 * h) break;
    h = h_new;
  }
  EXPECT_LT(iterations, 10);
  // The cubic spline's lattice sum at h = 1.2 dx is within 0.2% of 1/dx (measured -0.18%).
  EXPECT_NEAR(h, eta * dx, 3e-3 * eta * dx);
}

// ------------------------------------------------------------------------------------------------
// End-to-end runs.

std::string opts(const std::string& name) { return std::string("-options_file ") + SPH_SOURCE_DIR + "/cases/" + name; }
double num(const nlohmann::json& j) { return j.get<double>(); }

// Sod at t = 0.2, cubic spline, h = 1.2 (m/rho), 1D, -nx = left particles per unit length. For scale, leaving the
// initial step in place scores l1_rho ~ 0.1, plateau errors ~50%; the exact shock runs 0.35 in t = 0.2. The bounds
// leave ~50% headroom over the measurements (docs/verification/compressible.md, "Design measurements").
TEST(Sod, ConvergesToExactRiemannSolution) {
  const auto coarse = run_sph("sod_400", opts("sod.opts") + " -nx 400 -output_interval 0");
  const auto fine = run_sph("sod_800", opts("sod.opts") + " -nx 800 -output_interval 0");
  ASSERT_EQ(coarse.exit_code, 0);
  ASSERT_EQ(fine.exit_code, 0);
  const auto& c = coarse.summary["errors"];
  const auto& f = fine.summary["errors"];
  EXPECT_EQ(fine.summary["status"], "completed");
  EXPECT_EQ(coarse.summary["n_particles"], 450);
  EXPECT_LT(num(c["l1_density"]), 0.012);
  EXPECT_LT(num(c["l1_velocity"]), 0.035);
  EXPECT_LT(num(c["l1_pressure"]), 0.012);
  EXPECT_LT(num(c["plateau_density_rel"]), 0.015);
  EXPECT_LT(num(c["plateau_pressure_rel"]), 0.01);
  EXPECT_LT(num(c["shock_position"]), 0.006);
  // Refinement: first-order-like convergence at a shock (ratios measured ~0.5).
  for (const char* e : {"l1_density", "l1_velocity", "l1_pressure", "shock_position"})
    EXPECT_LT(num(f[e]), 0.7 * num(c[e])) << e;
  EXPECT_LT(num(f["plateau_density_rel"]), 0.005);
  EXPECT_LT(num(f["plateau_pressure_rel"]), 0.005);
  // Pairwise antisymmetric forces: momentum to round-off (relative to sum |m v|); total energy to the
  // integrator's accuracy (measured 3e-6 .. 7e-6).
  for (const auto* r : {&coarse, &fine}) {
    EXPECT_LT(num(r->summary["conservation"]["momentum_drift"]), 1e-12);
    EXPECT_LT(num(r->summary["conservation"]["energy_drift_rel"]), 1e-4);
  }
}

TEST(Sod, SummaryListsActiveModels) {
  const auto r = run_sph("sod_models",
                         "-case sod -solver compressible -nx 80 -t_end 0.02 -av monaghan -balsara "
                         "-av_switch morris_monaghan -conductivity 0");
  ASSERT_EQ(r.exit_code, 0);
  const auto& m = r.summary["models"];
  EXPECT_EQ(m["artificial_viscosity"]["model"], "MonaghanAV");
  EXPECT_EQ(m["artificial_viscosity"]["beta"], 2.0);
  EXPECT_EQ(m["balsara"]["model"], "Balsara1995");
  EXPECT_EQ(m["viscosity_switch"]["model"], "MorrisMonaghan1997");
  EXPECT_FALSE(m.contains("conductivity"));
  EXPECT_EQ(m["equation_of_state"]["gamma"], 1.4);
  EXPECT_EQ(m["smoothing_length"]["model"], "GradH");
  EXPECT_EQ(m["smoothing_length"]["eta"], 1.3);  // Wendland C2, the program's default kernel
  for (const char* key :
       {"l1_density", "l1_velocity", "l1_pressure", "plateau_density_rel", "plateau_pressure_rel", "shock_position"})
    EXPECT_TRUE(r.summary["errors"].contains(key)) << key;
  const auto d = run_sph("sod_default_models", "-case sod -solver compressible -nx 80 -t_end 0.02");
  ASSERT_EQ(d.exit_code, 0);
  EXPECT_EQ(d.summary["models"]["artificial_viscosity"]["model"], "MonaghanSignalVelocity");
  EXPECT_EQ(d.summary["models"]["conductivity"]["model"], "Price2008");
  EXPECT_FALSE(d.summary["models"].contains("balsara"));
}

// A thin periodic 2D tube runs and conserves momentum (accuracy of lattice layouts: see the report).
TEST(Sod, TwoDimensionalTubeRuns) {
  const auto r = run_sph("sod_2d", "-case sod -solver compressible -dim 2 -nx 64 -ny 32 -eta 1.6 -t_end 0.1");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["dim"], 2);
  EXPECT_LT(num(r.summary["conservation"]["momentum_drift"]), 1e-12);
  EXPECT_LT(num(r.summary["errors"]["l1_density"]), 0.05);
}

TEST(Compressible, RefusesSceneWithoutGas) {
  const auto r = run_sph("compressible_tgv", "-case taylor_green -solver compressible -nx 16 -t_end 0.01");
  EXPECT_NE(r.exit_code, 0);
  std::ifstream log(r.output_dir + ".log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_NE(text.str().find("needs a gas scene"), std::string::npos) << text.str();
}

// Toy star after two breathing periods (t = 7.26), against the RK4 solution of the ODEs (quintic spline,
// Morris-Monaghan alpha from 0.1), against a central density of 1 and a velocity amplitude A0 R = 0.1; the errors
// at nx 200 are under 5e-4 (docs/verification/compressible.md, "Design measurements").
TEST(ToyStar, FollowsExactSolutionOverTwoPeriods) {
  const auto coarse = run_sph("toy_star_100", opts("toy_star.opts") + " -nx 100 -output_interval 0");
  const auto fine = run_sph("toy_star_200", opts("toy_star.opts") + " -nx 200 -output_interval 0");
  ASSERT_EQ(coarse.exit_code, 0);
  ASSERT_EQ(fine.exit_code, 0);
  const auto& f = fine.summary;
  EXPECT_NEAR(num(f["t_final"]), 4.0 * M_PI / std::sqrt(3.0), 1e-9);
  EXPECT_LT(num(f["errors"]["l1_density"]), 1e-3);
  EXPECT_LT(num(f["errors"]["l1_velocity"]), 1e-3);
  EXPECT_LT(num(f["errors"]["l1_density"]), 0.7 * num(coarse.summary["errors"]["l1_density"]));
  EXPECT_LT(num(f["errors"]["l1_velocity"]), 0.8 * num(coarse.summary["errors"]["l1_velocity"]));
  // Isentropic scheme with conservative AV heating: energy (with the external potential) is conserved to
  // the integrator's accuracy (measured 2e-10).
  EXPECT_LT(num(f["conservation"]["energy_drift_rel"]), 1e-8);
  EXPECT_EQ(f["models"]["energy_equation"]["model"], "Isentropic");
  EXPECT_TRUE(f["models"].contains("external_force"));
}

// Without dissipation the scheme is time-reversible leapfrog on a Hamiltonian system: the energy error
// falls as dt^2 (measured ratios 4.00 per halving).
TEST(ToyStar, EnergyErrorIsSecondOrderInTimeWithoutViscosity) {
  double drift[3];
  const char* dts[3] = {"0.002", "0.001", "0.0005"};
  for (int k = 0; k < 3; ++k) {
    const auto r = run_sph(std::string("toy_star_dt") + std::to_string(k),
                           opts("toy_star.opts") + " -nx 100 -av none -t_end 1 -output_interval 0 -dt " + dts[k]);
    ASSERT_EQ(r.exit_code, 0);
    EXPECT_FALSE(r.summary["models"].contains("artificial_viscosity"));
    drift[k] = num(r.summary["conservation"]["energy_drift_rel"]);
  }
  EXPECT_LT(drift[0], 1e-7);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(drift[k] / drift[k + 1], 3.0);
    EXPECT_LT(drift[k] / drift[k + 1], 5.5);
  }
}

// A run resumed from a checkpoint continues bit for bit: the thermal state, smoothing lengths (the
// Newton start), alphas, leapfrog rates and search radius travel with the checkpoint.
TEST(Compressible, RestartMatchesUninterruptedRunExactly) {
  const std::string common =
      "-case sod -solver compressible -nx 80 -t_end 0.04 -dt 0.001 -output_interval 0.01 "
      "-checkpoint_interval 0.02 -av_switch morris_monaghan -balsara";
  const auto a = run_sph("compressible_restart_a", common);
  const auto b = run_sph("compressible_restart_b", common + " -max_steps 20");
  ASSERT_EQ(a.exit_code, 0);
  ASSERT_EQ(b.exit_code, 0);
  const auto c = run_sph("compressible_restart_c", common + " -restart " + b.output_dir + "/checkpoint.bin");
  ASSERT_EQ(c.exit_code, 0);
  const std::string ca = sph::testing::checkpoint_state(a.output_dir + "/checkpoint.bin"),
                    cc = sph::testing::checkpoint_state(c.output_dir + "/checkpoint.bin");
  ASSERT_FALSE(ca.empty());
  EXPECT_TRUE(ca == cc) << "final checkpoints differ";
  EXPECT_EQ(c.summary["errors"], a.summary["errors"]);
  EXPECT_EQ(c.summary["conservation"], a.summary["conservation"]);
}

}  // namespace
