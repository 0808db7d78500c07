#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "src/core/small_inverse.hpp"

namespace {

using namespace sph;

// The consistent Laplacian's small inverse against Eigen's LU: a times its inverse is the identity to
// round-off, including matrices that need row exchanges (a zero leading diagonal); a singular matrix
// or one holding NaN is refused.
template <int n> void check_small_inverse(std::uint32_t seed) {
  using Mat = Eigen::Matrix<double, n, n, Eigen::RowMajor>;
  std::srand(seed);
  for (int trial = 0; trial < 20; ++trial) {
    Mat a = Mat::Random();
    if (trial % 2) a(0, 0) = 0.0;  // the first pivot must come from another row
    Mat inv;
    ASSERT_TRUE(invert_partial_pivot<n>(a, inv));
    const Mat lu_inverse = Eigen::PartialPivLU<Mat>(a).inverse();
    const double scale = a.norm() * inv.norm();
    EXPECT_LT((a * inv - Mat::Identity()).norm(), 1e-13 * scale) << "n " << n << " trial " << trial;
    EXPECT_LT((inv - lu_inverse).norm(), 1e-12 * inv.norm() * scale) << "n " << n << " trial " << trial;
  }
  Mat singular = Mat::Random(), inv;
  singular.row(n - 1) = 2.0 * singular.row(0);
  singular.col(n - 1).setZero();
  EXPECT_FALSE(invert_partial_pivot<n>(singular, inv));
  Mat with_nan = Mat::Identity();
  with_nan(1, 1) = std::nan("");
  EXPECT_FALSE(invert_partial_pivot<n>(with_nan, inv));
}

TEST(SmallInverse, MatchesEigensLuAndRefusesSingularMatrices) {
  check_small_inverse<5>(3);
  check_small_inverse<9>(7);
}

}  // namespace
