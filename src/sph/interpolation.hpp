#pragma once
// Fluid fields at arbitrary points from the fluid particles, reduced over all ranks: the velocity on
// probe lines such as the cavity's centrelines, the pressure on a body's surface.
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
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"

namespace sph {

enum class ProbeInterpolation { Shepard, Linear };
inline const char* const probe_interpolation_names[] = {"shepard", "linear"};

namespace detail {
// The owned fluid particles within reach of any of a set of points, binned in cells one support wide,
// so that a point visits the 3^D cells around it rather than every particle (a body's surface has
// thousands of points in 3D).
template <int D> class FluidCells {
 public:
  FluidCells(const Particles<D>& P, const std::vector<Vector<D>>& points, double reach) : reach_(reach) {
    if (points.empty()) return;
    lo_ = hi_ = points[0];
    for (const Vector<D>& x : points) lo_ = lo_.cwiseMin(x), hi_ = hi_.cwiseMax(x);
    lo_.array() -= reach, hi_.array() += reach;
    for (int a = 0; a < D; ++a) n_[a] = static_cast<long>((hi_[a] - lo_[a]) / reach) + 1;
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      const Vector<D>& x = P.x[i];
      if (((x - lo_).array() < 0.0).any() || ((x - hi_).array() > 0.0).any()) continue;
      cells_[key(cell_of(x))].push_back(static_cast<int>(i));
    }
  }
  // The candidates for point x, in increasing index: each sum then runs in the particles' order, as
  // a pass over every particle would.
  void candidates(const Vector<D>& x, std::vector<int>& out) const {
    out.clear();
    const Eigen::Matrix<long, D, 1> c = cell_of(x);
    Eigen::Matrix<long, D, 1> d = Eigen::Matrix<long, D, 1>::Constant(-1);
    for (;;) {
      const Eigen::Matrix<long, D, 1> k = c + d;
      if ((k.array() >= 0).all() && (k.array() < n_.array()).all()) {
        const auto it = cells_.find(key(k));
        if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
      }
      int a = 0;
      while (a < D && d[a] == 1) d[a++] = -1;
      if (a == D) break;
      ++d[a];
    }
    std::sort(out.begin(), out.end());
  }

 private:
  Eigen::Matrix<long, D, 1> cell_of(const Vector<D>& x) const {
    Eigen::Matrix<long, D, 1> c;
    for (int a = 0; a < D; ++a) c[a] = std::clamp(static_cast<long>((x[a] - lo_[a]) / reach_), 0L, n_[a] - 1);
    return c;
  }
  long key(const Eigen::Matrix<long, D, 1>& c) const {
    long k = 0;
    for (int a = D - 1; a >= 0; --a) k = k * n_[a] + c[a];
    return k;
  }
  double reach_;
  Vector<D> lo_ = Vector<D>::Zero(), hi_ = Vector<D>::Zero();
  Eigen::Matrix<long, D, 1> n_ = Eigen::Matrix<long, D, 1>::Ones();
  std::unordered_map<long, std::vector<int>> cells_;
};

// A field's value (double or Vector<D>) as a row of C numbers, and back.
template <int C, class T> Eigen::Matrix<double, 1, C> as_row(const T& v) {
  if constexpr (std::is_same_v<T, double>) return Eigen::Matrix<double, 1, 1>::Constant(v);
  else return v.transpose();
}
template <class T, int C> T from_row(const Eigen::Matrix<double, 1, C>& r) {
  if constexpr (std::is_same_v<T, double>) return r(0);
  else return r.transpose();
}
// probe_fluid's default: point k sees every fluid particle within reach.
struct SeesEveryParticle {
  bool operator()(std::size_t, int) const { return true; }
};
}  // namespace detail

// A fluid field (double or Vector<D>, one value per particle) at arbitrary points, by the chosen fit,
// reduced over all ranks: every rank gets every point's value. For a scalar field and the linear fit,
// `gradient` (if given) gets the fitted gradient at each point (zero where the fit fell back to
// Shepard's value), so that a + b.(y - x) serves around x; `linear` (if given) gets 1 where the linear
// fit was made, 0 where it fell back. sees(k, i): whether point k may take particle i into its fit (a
// plate's face fits its own side's fluid only).
template <int D, class T, class Sees = detail::SeesEveryParticle>
std::vector<T> probe_fluid(const Particles<D>& P, const Kernel<D>& K, const std::vector<Vector<D>>& points,
                           ProbeInterpolation fit, const std::vector<T>& field,
                           std::vector<Vector<D>>* gradient = nullptr, const Sees& sees = Sees{},
                           std::vector<char>* linear = nullptr) {
  constexpr int m = D + 1;  // basis 1, (y - x)/h
  constexpr int C = std::is_same_v<T, double> ? 1 : D;
  using Moments = Eigen::Matrix<double, m, m>;
  using Sums = Eigen::Matrix<double, m, C>;
  constexpr int per_point = m * m + m * C;
  const std::size_t n = points.size();
  std::vector<double> buf(n * per_point, 0.0);  // per point: sum W p p^T, then sum W p f^T (column-major)
  const double rc2 = K.support_radius() * K.support_radius(), inv_h = 1.0 / K.h();
  const detail::FluidCells<D> cells(P, points, K.support_radius());
  std::vector<int> near;
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Map<Moments> M(&buf[k * per_point]);
    Eigen::Map<Sums> B(&buf[k * per_point + m * m]);
    cells.candidates(points[k], near);
    for (const int i : near) {
      const Vector<D> d = P.x[i] - points[k];
      const double r2 = d.squaredNorm();
      if (r2 >= rc2 || !sees(k, i)) continue;
      Eigen::Matrix<double, m, 1> p;
      p << 1.0, d * inv_h;
      const double w = K.W(std::sqrt(r2));
      M.noalias() += w * p * p.transpose();
      B.noalias() += w * p * detail::as_row<C>(field[static_cast<std::size_t>(i)]);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<T> u(n, detail::from_row<T, C>(Eigen::Matrix<double, 1, C>::Zero()));
  if (gradient) gradient->assign(n, Vector<D>::Zero());
  if (linear) linear->assign(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Map<const Moments> M(&buf[k * per_point]);
    const Eigen::Map<const Sums> B(&buf[k * per_point + m * m]);
    if (!(M(0, 0) > 0.0)) continue;  // no fluid within reach: zero, as for a point outside the fluid
    u[k] = detail::from_row<T, C>(Eigen::Matrix<double, 1, C>(B.row(0) / M(0, 0)));
    if (fit == ProbeInterpolation::Shepard) continue;
    // The moments are those of directions scaled by h, so a well-spread support gives a matrix of order
    // one; fewer than D + 1 particles, or all on one line, make it singular: keep Shepard's value there.
    const Eigen::LDLT<Moments> ldlt(M);
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-10)) continue;
    const Sums coefficients = ldlt.solve(Sums(B));
    if (linear) (*linear)[k] = 1;
    u[k] = detail::from_row<T, C>(Eigen::Matrix<double, 1, C>(coefficients.row(0)));
    if constexpr (std::is_same_v<T, double>)
      if (gradient) (*gradient)[k] = coefficients.template bottomRows<D>().col(0) * inv_h;
  }
  return u;
}

template <int D> std::vector<Vector<D>> probe_velocity(const Particles<D>& P, const Kernel<D>& K,
                                                       const std::vector<Vector<D>>& points, ProbeInterpolation fit) {
  return probe_fluid(P, K, points, fit, P.v);
}

}  // namespace sph
