#pragma once
// Velocity at arbitrary points (probe lines such as the cavity's centrelines) from the fluid particles,
// reduced over all ranks. Brute force over particles: meant for a few hundred probe points.
//
// Two fits, chosen by name (-profile_interpolation):
//  - shepard: f(x) = sum_f f_f W_f / sum_f W_f, W_f = W(x - x_f). Exact for constants only: where the
//    support is cut by a wall, or the particles around x are not symmetric, it is biased by O(h grad f),
//    most of a coarse cavity's error (docs/verification/lid_driven_cavity.md, "How the profiles are read
//    off the particles").
//  - linear: moving least squares, f(y) ~ a + b.(y - x)/h fitted with the weights W_f; the value is a.
//    Exact for linear fields wherever the support holds D + 1 particles not on one hyperplane, next to
//    walls too, so its error is second order (h^2 f''), the order of the schemes it measures.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"

namespace sph {

enum class ProbeInterpolation { Shepard, Linear };
inline const char* const probe_interpolation_names[] = {"shepard", "linear"};

template <int D> std::vector<Vector<D>> probe_velocity(const Particles<D>& P, const Kernel<D>& K,
                                                       const std::vector<Vector<D>>& points, ProbeInterpolation fit) {
  constexpr int m = D + 1;  // basis 1, (y - x)/h
  using Moments = Eigen::Matrix<double, m, m>;
  using Sums = Eigen::Matrix<double, m, D>;
  constexpr int per_point = m * m + m * D;
  const std::size_t n = points.size();
  std::vector<double> buf(n * per_point, 0.0);  // per point: sum W p p^T, then sum W p u^T (column-major)
  const double rc2 = K.support_radius() * K.support_radius(), inv_h = 1.0 / K.h();
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Map<Moments> M(&buf[k * per_point]);
    Eigen::Map<Sums> B(&buf[k * per_point + m * m]);
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      const Vector<D> d = P.x[i] - points[k];
      const double r2 = d.squaredNorm();
      if (r2 >= rc2) continue;
      Eigen::Matrix<double, m, 1> p;
      p << 1.0, d * inv_h;
      const double w = K.W(std::sqrt(r2));
      M.noalias() += w * p * p.transpose();
      B.noalias() += w * p * P.v[i].transpose();
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<Vector<D>> u(n, Vector<D>::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Map<const Moments> M(&buf[k * per_point]);
    const Eigen::Map<const Sums> B(&buf[k * per_point + m * m]);
    if (!(M(0, 0) > 0.0)) continue;  // no fluid within reach: zero, as for a point outside the fluid
    u[k] = B.row(0).transpose() / M(0, 0);
    if (fit == ProbeInterpolation::Shepard) continue;
    // The moments are those of directions scaled by h, so a well-spread support gives a matrix of order
    // one; fewer than D + 1 particles, or all on one line, make it singular: keep Shepard's value there.
    const Eigen::LDLT<Moments> ldlt(M);
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-10)) continue;
    const Sums coefficients = ldlt.solve(Sums(B));
    u[k] = coefficients.row(0).transpose();
  }
  return u;
}

}  // namespace sph
