#pragma once
// The inverse of a small fixed-size matrix (the consistent Laplacian's 5 x 5 and 9 x 9 moment systems,
// one per particle and step) by Gauss-Jordan elimination with partial pivoting, on fixed-size Eigen
// rows that the compiler unrolls. Eigen's PartialPivLU<Matrix<double, 5, 5>>::inverse() runs its
// general kernels (a run-time-sized LU, then a triangular solve and GEMM packing for the identity's
// columns), a large share of a step for 250 flops (docs/performance.md, "Before it").
#include <Eigen/Dense>
#include <cmath>

namespace sph {

// inv = a^-1, the pivot in each column the entry of largest magnitude. Returns false, with inv
// undefined, when a pivot is zero or not a number (a singular matrix or one holding NaN); a nearly
// singular one passes, and its caller judges the condition number from the inverse.
template <int n> bool invert_partial_pivot(Eigen::Matrix<double, n, n, Eigen::RowMajor> a,
                                           Eigen::Matrix<double, n, n, Eigen::RowMajor>& inv) {
  inv.setIdentity();
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    double largest = std::abs(a(k, k));
    for (int r = k + 1; r < n; ++r)
      if (std::abs(a(r, k)) > largest) largest = std::abs(a(r, k)), pivot = r;
    if (!(largest > 0.0)) return false;
    if (pivot != k) a.row(pivot).swap(a.row(k)), inv.row(pivot).swap(inv.row(k));
    const double scale = 1.0 / a(k, k);
    // Columns left of k are zero in a's rows but k's, and a's column k is not read again.
    for (int c = k + 1; c < n; ++c) a(k, c) *= scale;
    inv.row(k) *= scale;
    for (int r = 0; r < n; ++r) {
      if (r == k) continue;
      const double factor = a(r, k);
      for (int c = k + 1; c < n; ++c) a(r, c) -= factor * a(k, c);
      inv.row(r) -= factor * inv.row(k);
    }
  }
  return true;
}

}  // namespace sph
