// Operator properties that hold on any particle distribution, on a disordered open patch: exactness
// for constant and linear fields, momentum conservation, wall and fluid rows, the moment test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "operator_lattice.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/sph/consistent_laplacian.hpp"
#include "src/sph/laplacian_smoothing.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/vorticity.hpp"

namespace {

using namespace sph;
using namespace sph::test;

// The sheet-or-drop test: the smallest eigenvalue of the moment matrix's symmetric part against 0.2,
// on matrices whose eigenvalues are known ((a + c)/2 -+ sqrt(((a - c)/2)^2 + b^2) for [[a, b], [b, c]]).
TEST(OperatorDisordered, MomentsResolveByTheSmallestEigenvalue) {
  using T2 = Tensor<2>;
  EXPECT_TRUE(moments_resolve<2>(T2::Identity()));
  EXPECT_TRUE(moments_resolve<2>(0.5 * T2::Identity()));                      // a flat free surface
  EXPECT_FALSE(moments_resolve<2>((T2() << 1.0, 0.0, 0.0, 0.1).finished()));  // a sheet along x
  EXPECT_FALSE(moments_resolve<2>((T2() << 0.6, 0.5, 0.5, 0.6).finished()));  // 0.1 and 1.1
  EXPECT_TRUE(moments_resolve<2>((T2() << 0.5, 0.4, 0.4, 0.9).finished()));   // 0.253: past Gershgorin's 0.1
  // Its own eigenvalues are both 1; its symmetric part's are 0.1 and 1.9.
  EXPECT_FALSE(moments_resolve<2>((T2() << 1.0, 1.8, 0.0, 1.0).finished()));
  EXPECT_FALSE(moments_resolve<3>(Tensor<3>::Zero()));  // alone
  EXPECT_FALSE(moments_resolve<2>(T2::Constant(std::nan(""))));
}

TEST(OperatorDisordered, CorrectedGradientsExactForLinearFields) {
  const V2 a(3.0, -1.7);
  T2 A;  // u(x) = A x + b, so d u_b / d x_a = A(b, a)
  A << 0.5, -2.0, 1.25, 0.75;
  const V2 b(0.3, -0.1);
  for (const KernelCase& kc : kCases) {
    Patch S(16, kc);
    ASSERT_EQ(S.P.n_ghost, 0u);
    std::vector<double> f(S.P.size());
    std::vector<V2> u(S.P.size());
    for (std::size_t i = 0; i < S.P.size(); ++i) {
      f[i] = 2.0 + a.dot(S.P.x[i]);
      u[i] = A * S.P.x[i] + b;
    }
    const auto L = correction_matrices(S.P, S.nl(), S.K);
    const auto g = gradient_corrected(S.P, S.nl(), S.K, L, f);
    const auto G = vector_gradient_corrected(S.P, S.nl(), S.K, L, u);
    double eg = 0, eG = 0;
    for (std::size_t i = 0; i < S.P.n_owned; ++i) {  // every particle, boundary ones included
      eg = std::max(eg, (g[i] - a).norm() / a.norm());
      eG = std::max(eG, (G[i] - A.transpose()).norm() / A.norm());
    }
    std::printf("%-32s linear field: corrected gradient error %.2e, vector gradient error %.2e\n", label(kc).c_str(),
                eg, eG);
    EXPECT_LT(eg, 1e-10) << label(kc);
    EXPECT_LT(eG, 1e-10) << label(kc);
  }
}

// The output vorticity (-output_fields vorticity) is exact for a linear velocity field on any particle
// distribution, patch edges included, and ignores wall particles, whose velocities are the walls'
// (here deliberately wild) and not the fluid's.
TEST(OperatorDisordered, VorticityExactForLinearFieldsAndBlindToWalls) {
  T2 A;  // u(x) = A x + b: curl u = A(1, 0) - A(0, 1)
  A << 0.5, -2.0, 1.25, 0.75;
  for (const KernelCase& kc : kCases) {
    Patch S(16, kc);
    for (std::size_t i = 0; i < S.P.size(); ++i) {
      const bool wall = i % 7 == 3;
      S.P.kind[i] = wall ? kWall : kFluid;
      S.P.v[i] = wall ? V2(100.0, -50.0) : V2(A * S.P.x[i] + V2(0.3, -0.1));
    }
    const auto w = fluid_vorticity(S.P, S.nl(), S.K);
    ASSERT_EQ(w.size(), 1u);
    double err = 0.0;
    for (std::size_t i = 0; i < S.P.n_owned; ++i) {
      if (S.P.kind[i] == kWall) EXPECT_EQ(w[0][i], 0.0);
      else err = std::max(err, std::abs(w[0][i] - (A(1, 0) - A(0, 1))));
    }
    EXPECT_LT(err, 1e-10 * A.norm()) << label(kc);
  }
}

void difference_forms_vanish_for_constant_fields() {
  for (const KernelCase& kc : kCases) {
    Patch S(16, kc);
    const std::vector<double> c(S.P.size(), 4.2);
    const std::vector<V2> U(S.P.size(), V2(1.5, -0.5));
    const auto L = correction_matrices(S.P, S.nl(), S.K);
    const auto div = divergence(S.P, S.nl(), S.K, U);
    const auto gd = gradient_difference(S.P, S.nl(), S.K, c);
    const auto gc = gradient_corrected(S.P, S.nl(), S.K, L, c);
    const auto G = vector_gradient_corrected(S.P, S.nl(), S.K, L, U);
    const auto lap = laplacian_morris(S.P, S.nl(), S.K, c);
    const auto lapU = laplacian_morris(S.P, S.nl(), S.K, U);
    for (std::size_t i = 0; i < S.P.n_owned; ++i) {
      EXPECT_EQ(div[i], 0.0) << label(kc);
      EXPECT_EQ(gd[i].norm(), 0.0) << label(kc);
      EXPECT_EQ(gc[i].norm(), 0.0) << label(kc);
      EXPECT_EQ(G[i].norm(), 0.0) << label(kc);
      EXPECT_EQ(lap[i], 0.0) << label(kc);
      EXPECT_EQ(lapU[i].norm(), 0.0) << label(kc);
    }
  }
}

void singular_moment_matrix_falls_back_to_identity() {
  // An isolated particle (no neighbours) and a collinear row (rank-one moment matrix) get L = I.
  const Kernel<2> K(KernelType::WendlandC2, 0.1);
  Particles<2> P;
  for (const V2& x : {V2(0.5, 0.5), V2(0.1, 0.1), V2(0.15, 0.1), V2(0.2, 0.1)}) P.add(x, V2::Zero(), 1.0, 1.0);
  NeighbourList<2> nl;
  nl.build(P.x, P.n_owned, K.support_radius());
  const auto L = correction_matrices(P, nl, K);
  for (const T2& Li : L) EXPECT_EQ(Li, T2::Identity());
}

void symmetric_gradient_conserves_momentum() {
  // sum_i V_i (grad p)_i = sum_i sum_j m_i m_j (p_i/rho_i^2 + p_j/rho_j^2) grad_i W_ij = 0, since the
  // pair term is antisymmetric in i, j: the pressure force of a closed set sums to zero, on any
  // particle distribution (and although the gradient itself is not exact there).
  for (const KernelCase& kc : kCases) {
    Patch S(16, kc);
    std::vector<double> p(S.P.size());
    double scale = 0.0;
    for (std::size_t i = 0; i < S.P.size(); ++i) p[i] = 1e5 * (1.0 + f_s(S.P.x[i]));
    const auto g = gradient_symmetric(S.P, S.nl(), S.K, p);
    V2 total = V2::Zero();
    for (std::size_t i = 0; i < S.P.n_owned; ++i) {
      total += S.P.m[i] / S.P.rho[i] * g[i];
      scale += S.P.m[i] / S.P.rho[i] * g[i].norm();
    }
    EXPECT_LT(total.norm(), 1e-13 * scale) << label(kc);
  }
}

TEST(OperatorDisordered, ConstantFieldsMomentumAndSingularMoments) {
  difference_forms_vanish_for_constant_fields();
  symmetric_gradient_conserves_momentum();
  singular_moment_matrix_falls_back_to_identity();
}

// The corrected gradient that gathers its correction matrices in its own pair loop gives bitwise the
// result of the two separate loops.
TEST(OperatorDisordered, FusedCorrectedGradientEqualsTheSeparateLoops) {
  Patch S(16, kCases[0]);
  std::vector<double> f(S.P.size());
  for (std::size_t i = 0; i < S.P.size(); ++i) f[i] = f_s(S.P.x[i]);
  const std::vector<V2> fused = gradient_corrected(S.P, S.nl(), S.K, f);
  const std::vector<V2> separate = gradient_corrected(S.P, S.nl(), S.K, correction_matrices(S.P, S.nl(), S.K), f);
  ASSERT_EQ(fused.size(), separate.size());
  for (std::size_t i = 0; i < fused.size(); ++i) ASSERT_EQ(fused[i], separate[i]) << i;
}

// Rows::Fluid: the operators that ISPH evaluates at fluid particles only give, at every fluid
// particle, bitwise what the all-rows loop gives (walls still enter as neighbours), and leave the
// walls' entries at zero.
TEST(OperatorDisordered, FluidRowsEqualAllRowsAtTheFluid) {
  Patch S(16, kCases[0]);
  std::vector<double> f(S.P.size());
  std::vector<V2> u(S.P.size());
  for (std::size_t i = 0; i < S.P.size(); ++i) {
    S.P.kind[i] = i % 5 == 2 ? kWall : kFluid;
    f[i] = f_s(S.P.x[i]);
    u[i] = V2(f_s(S.P.x[i]), -0.5 * f_s(V2(S.P.x[i][1], S.P.x[i][0])));
  }
  const auto g_all = gradient_corrected(S.P, S.nl(), S.K, f),
             g_fluid = gradient_corrected(S.P, S.nl(), S.K, f, Rows::Fluid);
  const auto d_all = divergence_corrected(S.P, S.nl(), S.K, u),
             d_fluid = divergence_corrected(S.P, S.nl(), S.K, u, Rows::Fluid);
  const auto l_all = laplacian_consistent_one_pass(S.P, S.nl(), S.K, u);
  const auto l_fluid = laplacian_consistent_one_pass(S.P, S.nl(), S.K, u, Rows::Fluid);
  int walls = 0;
  for (std::size_t i = 0; i < S.P.n_owned; ++i) {
    if (S.P.kind[i] == kWall) {
      ++walls;
      EXPECT_EQ(g_fluid[i], V2::Zero()) << i;
      EXPECT_EQ(d_fluid[i], 0.0) << i;
      EXPECT_EQ(l_fluid[i], V2::Zero()) << i;
      continue;
    }
    ASSERT_EQ(g_fluid[i], g_all[i]) << i;
    ASSERT_EQ(d_fluid[i], d_all[i]) << i;
    ASSERT_EQ(l_fluid[i], l_all[i]) << i;
  }
  EXPECT_GT(walls, 0);
}

// Beside a wall the neighbours' Laplacians include walls, which carry none: those particles keep the
// consistent Laplacian, bitwise.
TEST(OperatorDisordered, SmoothingCorrectionLeavesParticlesBesideWallsAlone) {
  Patch S(16, kCases[0]);
  std::vector<V2> u(S.P.size());
  for (std::size_t i = 0; i < S.P.size(); ++i) {
    S.P.kind[i] = S.P.x[i][0] < 0.2 ? kWall : kFluid;
    u[i] = u_tg(S.P.x[i]);
  }
  std::vector<LaplacianCorrection<2>> factors;
  const std::vector<V2> lap = laplacian_consistent_one_pass(S.P, S.nl(), S.K, u, Rows::Fluid, &factors);
  std::vector<V2> corrected = lap;
  remove_laplacian_smoothing_error(S.P, *S.nh, S.K, factors, corrected);
  const double R2 = S.K.support_radius() * S.K.support_radius();
  int beside = 0, changed = 0;
  for (std::size_t i = 0; i < S.P.n_owned; ++i) {
    if (S.P.kind[i] != kFluid) continue;
    bool wall = false;
    for (std::size_t j = 0; j < S.P.size(); ++j)
      wall = wall || (S.P.kind[j] == kWall && (S.P.x[i] - S.P.x[j]).squaredNorm() < R2);
    if (wall) {
      ++beside;
      EXPECT_EQ(corrected[i], lap[i]) << i;
    } else {
      changed += corrected[i] != lap[i];
    }
  }
  EXPECT_GT(beside, 0);
  EXPECT_GT(changed, 0);
}

}  // namespace
