// The consistent Laplacian and the corrected divergence (src/sph/consistent_laplacian.hpp) against
// analytic derivatives on disordered particles, where the Morris Laplacian and the plain divergence
// stop converging: exactness for quadratic / linear fields, and the convergence order on a jittered
// periodic lattice at nx = 20, 40, 80 (fixed h/dx and jitter fraction).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "src/core/domain.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/consistent_laplacian.hpp"

namespace {

using namespace sph;
using V2 = Vector<2>;
constexpr double k2pi = 2.0 * M_PI;

// nx^2 particles on the unit square, each moved from its cell centre by up to `jitter` dx in each
// direction; periodic (with ghosts) or open.
struct Cloud {
  Domain<2> domain;
  Kernel<2> K;
  Particles<2> P;
  std::unique_ptr<Neighbourhood<2>> nh;

  Cloud(int nx, double jitter, bool periodic) : K(KernelType::WendlandC2, 1.5 / nx) {
    const double dx = 1.0 / nx;
    domain.periodic = {periodic, periodic};
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> u(-jitter, jitter);
    for (int k = 0; k < nx * nx; ++k) {
      const double x = (k % nx + 0.5 + u(gen)) * dx, y = (k / nx + 0.5 + u(gen)) * dx;
      P.add(V2(x, y), V2::Zero(), dx * dx, 1.0);
      P.gid.back() = k;
    }
    P.n_global = nx * nx;
    nh = std::make_unique<Neighbourhood<2>>(domain, K.support_radius(), 0.0);
    nh->update(P, true);
  }
  template <class T, class F> std::vector<T> sample(F g) const {
    std::vector<T> v(P.n_owned);
    for (std::size_t i = 0; i < P.n_owned; ++i) v[i] = g(P.x[i]);
    nh->halo().update(v);
    return v;
  }
  // Whether x is at least one support radius inside the open square.
  bool interior(const V2& x) const {
    const double r = K.support_radius();
    return x.minCoeff() > r && x.maxCoeff() < 1.0 - r;
  }
};

double f_s(const V2& x) { return std::sin(k2pi * x[0]) * std::sin(k2pi * x[1]); }
V2 w_ns(const V2& x) { return V2(std::sin(k2pi * x[0]), std::sin(k2pi * x[1])); }
double div_w_ns(const V2& x) { return k2pi * (std::cos(k2pi * x[0]) + std::cos(k2pi * x[1])); }

// max |num - exact| / max |exact| over owned particles.
template <class F> double rel_error(const Cloud& C, const std::vector<double>& num, F exact) {
  double e = 0.0, s = 0.0;
  for (std::size_t i = 0; i < C.P.n_owned; ++i) {
    e = std::max(e, std::abs(num[i] - exact(C.P.x[i])));
    s = std::max(s, std::abs(exact(C.P.x[i])));
  }
  return e / s;
}

TEST(ConsistentLaplacian, ExactForLinearAndNearlyExactForQuadraticFieldsOnDisorderedParticles) {
  Cloud C(24, 0.25, false);
  const auto corr = laplacian_corrections(C.P, C.nh->list(), C.K);
  // f = 1.5 x^2 - 0.7 x y + 0.4 y^2 + linear: lap f = 3 + 0.8.
  auto quad = [](const V2& x) { return 1.5 * x[0] * x[0] - 0.7 * x[0] * x[1] + 0.4 * x[1] * x[1] + 2 * x[0] - x[1]; };
  auto lin = [](const V2& x) { return 2.0 * x[0] - 3.0 * x[1] + 1.0; };
  const auto lq = laplacian_consistent(C.P, C.nh->list(), C.K, corr, C.sample<double>(quad));
  const auto ll = laplacian_consistent(C.P, C.nh->list(), C.K, corr, C.sample<double>(lin));
  const auto lm = laplacian_morris(C.P, C.nh->list(), C.K, C.sample<double>(quad));
  double eq = 0, el = 0, em = 0;
  for (std::size_t i = 0; i < C.P.n_owned; ++i) {
    if (!C.interior(C.P.x[i])) continue;
    eq = std::max(eq, std::abs(lq[i] - 3.8) / 3.8);
    em = std::max(em, std::abs(lm[i] - 3.8) / 3.8);
    el = std::max(el, std::abs(ll[i]));
  }
  std::printf("quadratic field, jitter 0.25 dx: consistent %.2e, Morris %.2e; linear field: %.2e\n", eq, em, el);
  EXPECT_LT(el, 1e-8);  // exact: the corrected gradient is exact for linear f
  EXPECT_LT(eq, 0.02);  // only the gradient's O(disorder^2) error is left
  EXPECT_GT(em, 0.1);   // the Morris form is O(1) wrong here: the reason for the consistent one
}

// The one-pass form (factors gathered beside the moments, used by WCSPH's rates and both of ISPH's
// kicks) is the two-pass operator rearranged: the same values to round-off on every particle of a
// disordered open cloud, edge particles (where the factors fall back to Morris') included, and exact
// for a quadratic vector field in the interior. The factors it hands out (ISPH's PPE reads them) are
// laplacian_corrections' bitwise.
TEST(ConsistentLaplacian, OnePassFormEqualsTheTwoPassOperator) {
  Cloud C(20, 0.25, false);
  auto quad = [](const V2& x) {
    return V2(1.5 * x[0] * x[0] - 0.7 * x[0] * x[1] + 0.4 * x[1] * x[1], -0.3 * x[0] * x[0] + 2.0 * x[1] * x[1] + x[0]);
  };
  const auto u = C.sample<V2>(quad);
  const auto factors = laplacian_corrections(C.P, C.nh->list(), C.K);
  const auto two_pass = laplacian_consistent(C.P, C.nh->list(), C.K, factors, u);
  std::vector<LaplacianCorrection<2>> one_pass_factors;
  const auto one_pass = laplacian_consistent_one_pass(C.P, C.nh->list(), C.K, u, Rows::All, &one_pass_factors);
  ASSERT_EQ(one_pass_factors.size(), factors.size());
  for (std::size_t i = 0; i < factors.size(); ++i) {
    EXPECT_EQ(one_pass_factors[i].A, factors[i].A);
    EXPECT_EQ(one_pass_factors[i].c, factors[i].c);
  }
  double scale = 0.0, diff = 0.0, err = 0.0;
  for (std::size_t i = 0; i < C.P.n_owned; ++i) scale = std::max(scale, two_pass[i].norm());
  for (std::size_t i = 0; i < C.P.n_owned; ++i) {
    diff = std::max(diff, (one_pass[i] - two_pass[i]).norm());
    if (C.interior(C.P.x[i])) err = std::max(err, (one_pass[i] - V2(3.8, 3.4)).norm() / 3.8);
  }
  std::printf("one pass against two: %.2e of the largest value; quadratic field error %.2e\n", diff / scale, err);
  EXPECT_LT(diff, 1e-11 * scale);
  EXPECT_LT(err, 1e-10);  // the moment conditions make it exact for quadratic fields
}

TEST(ConsistentLaplacian, CorrectedDivergenceExactForLinearFields) {
  Cloud C(16, 0.25, false);
  const auto corr = laplacian_corrections(C.P, C.nh->list(), C.K);
  const auto u = C.sample<V2>([](const V2& x) { return V2(2.0 * x[0] - x[1] + 0.3, 0.5 * x[0] + 1.5 * x[1]); });
  const auto div = divergence_corrected(C.P, C.nh->list(), C.K, u);
  for (std::size_t i = 0; i < C.P.n_owned; ++i) EXPECT_NEAR(div[i], 3.5, 1e-10);
  // Two fields in one pass: each exact for its linear field, and bitwise the pass of its own.
  const auto w = C.sample<V2>([](const V2& x) { return V2(-x[0] + 0.2 * x[1], 0.7 * x[0] - 0.4 * x[1] + 1.0); });
  const auto both = divergences_corrected(C.P, C.nh->list(), C.K, {&u, &w});
  const auto div_w = divergence_corrected(C.P, C.nh->list(), C.K, w);
  ASSERT_EQ(both.size(), 2u);
  for (std::size_t i = 0; i < C.P.n_owned; ++i) {
    EXPECT_EQ(both[0][i], div[i]);
    EXPECT_EQ(both[1][i], div_w[i]);
    EXPECT_NEAR(div_w[i], -1.4, 1e-10);
  }
}

// On a periodic lattice the consistent Laplacian converges at second order (the smoothing error).
TEST(ConsistentLaplacian, SecondOrderOnALattice) {
  double e[3];
  const int nxs[] = {32, 64, 128};
  for (int k = 0; k < 3; ++k) {
    Cloud C(nxs[k], 0.0, true);
    const auto corr = laplacian_corrections(C.P, C.nh->list(), C.K);
    e[k] = rel_error(C, laplacian_consistent(C.P, C.nh->list(), C.K, corr, C.sample<double>(f_s)),
                     [](const V2& x) { return -2.0 * k2pi * k2pi * f_s(x); });
  }
  std::printf("lattice: consistent Laplacian %.3e %.3e %.3e (nx 32, 64, 128)\n", e[0], e[1], e[2]);
  EXPECT_GE(std::log2(e[0] / e[1]), 1.9);
  EXPECT_GE(std::log2(e[1] / e[2]), 1.9);
}

// On a jittered periodic lattice (jitter 0.15 dx at every resolution) the consistent operators
// converge at first order (their error is the third moments of a disordered neighbourhood, O(h));
// the Morris Laplacian and the plain divergence do not converge at all: their error is set by the
// jitter, not by h (the Morris error even grows, as 1/h).
TEST(ConsistentLaplacian, ConvergesOnJitteredLatticeWhereMorrisStalls) {
  const int nxs[] = {20, 40, 80};
  double lap_c[3], lap_m[3], div_c[3], div_p[3];
  for (int k = 0; k < 3; ++k) {
    Cloud C(nxs[k], 0.15, true);
    const auto corr = laplacian_corrections(C.P, C.nh->list(), C.K);
    const auto f = C.sample<double>(f_s);
    const auto w = C.sample<V2>(w_ns);
    auto lap_exact = [](const V2& x) { return -2.0 * k2pi * k2pi * f_s(x); };
    lap_c[k] = rel_error(C, laplacian_consistent(C.P, C.nh->list(), C.K, corr, f), lap_exact);
    lap_m[k] = rel_error(C, laplacian_morris(C.P, C.nh->list(), C.K, f), lap_exact);
    div_c[k] = rel_error(C, divergence_corrected(C.P, C.nh->list(), C.K, w), div_w_ns);
    div_p[k] = rel_error(C, divergence(C.P, C.nh->list(), C.K, w), div_w_ns);
  }
  auto order = [](const double* e, int k) { return std::log2(e[k] / e[k + 1]); };
  std::printf("jitter 0.15 dx        nx=20      nx=40      nx=80   orders\n");
  const char* names[] = {"lap consistent", "lap Morris", "div corrected", "div plain"};
  const double* errs[] = {lap_c, lap_m, div_c, div_p};
  for (int r = 0; r < 4; ++r)
    std::printf("  %-15s %9.3e  %9.3e  %9.3e   %5.2f %5.2f\n", names[r], errs[r][0], errs[r][1], errs[r][2],
                order(errs[r], 0), order(errs[r], 1));
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(order(lap_c, k), 1.0);  // measured 1.28, 1.26
    EXPECT_GE(order(div_c, k), 0.9);  // measured 1.45, 1.00
    EXPECT_LT(order(lap_m, k), 0.5);
    EXPECT_LT(order(div_p, k), 0.5);
  }
  EXPECT_LT(lap_c[2], 0.01 * lap_m[2]);
}

// The moment system and the field moments, summed along the pairs in lanes from their distinct
// moments (laplacian_moments.hpp), against the definitions summed pair by pair: S = sum_j g psi phi^T,
// second_q = sum_j e^{alpha_q} w_j, first = sum_j e w_j^T, on random pairs (an odd count, so the
// lanes are padded) in 1D, 2D and 3D.
template <int D> void check_moments_against_pairwise_sums() {
  constexpr int m = D * (D + 1) / 2, n = m + D;
  std::mt19937 gen(11 + D);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.05, 1.0);
  for (int count : {1, 7, 30}) {
    LaplacianPairs<D>& pairs = laplacian_pair_buffer<D>();
    Eigen::Matrix<double, n, n> S = Eigen::Matrix<double, n, n>::Zero();
    std::array<Vector<D>, m> second;
    for (auto& v : second) v.setZero();
    Tensor<D> first = Tensor<D>::Zero(), moment = Tensor<D>::Zero();
    for (int k = 0; k < count; ++k) {
      Vector<D> e;
      for (int a = 0; a < D; ++a) e(a) = u(gen);
      e.normalize();
      Vector<D> w;
      for (int a = 0; a < D; ++a) w(a) = u(gen);
      const double s = pos(gen), g = pos(gen);
      pairs.add(e, s, g, w);
      Eigen::Matrix<double, n, 1> phi, psi;
      int q = 0;
      for (int a = 0; a < D; ++a)
        for (int b = a; b < D; ++b, ++q) {
          phi(q) = (a == b ? 1.0 : 2.0) * e(a) * e(b), psi(q) = s * s * e(a) * e(b);
          second[q] += e(a) * e(b) * w;
        }
      for (int a = 0; a < D; ++a) phi(m + a) = e(a), psi(m + a) = s * e(a);
      S += g * psi * phi.transpose();
      first += e * w.transpose();
      moment += (g * s * s) * e * e.transpose();  // sum_j g r r^T over R^2, r = s R e
    }
    const std::size_t padded = pairs.padded();
    EXPECT_EQ(padded % detail::kLanes, 0u);
    const detail::LaplacianMoments<D> moments = detail::sum_laplacian_moments(pairs, padded);
    const detail::LaplacianSystem<D> system(moments);
    EXPECT_LT((detail::moment_matrix_over_R2(moments) - moment).cwiseAbs().maxCoeff(), 1e-13 * count) << "D " << D;
    const double scale = S.cwiseAbs().maxCoeff();
    EXPECT_LT((system.S - S).cwiseAbs().maxCoeff(), 1e-13 * scale) << "D " << D << ", " << count << " pairs";
    const detail::LaplacianFieldMoments<D> fields = detail::sum_laplacian_field_moments(pairs, padded);
    for (int q = 0; q < m; ++q) EXPECT_LT((fields.second[q] - second[q]).cwiseAbs().maxCoeff(), 1e-13 * count);
    EXPECT_LT((fields.first - first).cwiseAbs().maxCoeff(), 1e-13 * count);
  }
}

TEST(ConsistentLaplacian, MomentsInLanesEqualThePairwiseSums) {
  check_moments_against_pairwise_sums<1>();
  check_moments_against_pairwise_sums<2>();
  check_moments_against_pairwise_sums<3>();
}

}  // namespace
