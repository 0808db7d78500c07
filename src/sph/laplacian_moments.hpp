#pragma once
// The sums over one particle's pairs that the consistent Laplacian (consistent_laplacian.hpp) needs,
// taken along the pairs in SIMD lanes.
//
// Its moment system sum_j g_j psi_j phi_j^T has 25 entries in 2D (81 in 3D), more than the registers
// hold: summed pair by pair, every entry was loaded and stored at every pair. But each entry is
// g s^t times a monomial of the pair's direction e of degree 2 to 4, and only 16 of them differ in 2D
// (41 in 3D). So a particle's pairs are recorded first, one array per quantity (LaplacianPairs), and
// the distinct moments are summed after its pair loop, kLanes pairs at a time, each partial sum in a
// register where they fit (in 2D most do; splitting the sums over two passes to keep them all there
// made a 3D step slower, the monomials computed twice). The lanes are added in a fixed order at the
// end: the sums differ from pair-by-pair ones in round-off only, and are the same on any thread count.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "src/core/types.hpp"

namespace sph {

namespace detail {

// Pairs summed at a time: two doubles fill the default build's SSE2 registers.
constexpr int kLanes = 2;

// Number of monomials of degree k in d variables, C(d + k - 1, k).
constexpr int monomial_count(int d, int k) {
  int c = 1;
  for (int i = 1; i <= k; ++i) c = c * (d + i - 1) / i;  // exact: c is C(d + i - 1, i) at every i
  return c;
}

// The monomials of degree K of a D-vector e: one per sorted axis tuple a_1 <= ... <= a_K, in
// lexicographic order (degree 2: the order of the Laplacian's unknowns A_ab, a <= b). Monomial i is
// the monomial of degree K - 1 at prefix[i] (in that degree's table) times e_{last[i]}.
template <int D, int K> struct Monomials {
  static constexpr int count = monomial_count(D, K);
  std::array<std::array<int, K>, count> axes{};
  std::array<int, count> prefix{}, last{};

  constexpr Monomials() {
    std::array<int, K> t{};  // the first tuple: all axes 0
    for (int i = 0; i < count; ++i) {
      axes[i] = t;
      int pos = K - 1;  // the next tuple: raise the rightmost axis that can rise, and copy it rightwards
      while (pos >= 0 && t[pos] == D - 1) --pos;
      if (pos < 0) break;
      ++t[pos];
      for (int r = pos + 1; r < K; ++r) t[r] = t[pos];
    }
    if constexpr (K > 0) {
      const Monomials<D, K - 1> lower;
      for (int i = 0; i < count; ++i) {
        std::array<int, K - 1> head{};
        for (int r = 0; r + 1 < K; ++r) head[r] = axes[i][r];
        prefix[i] = lower.index(head), last[i] = axes[i][K - 1];
      }
    }
  }
  // The index of a sorted axis tuple.
  constexpr int index(const std::array<int, K>& t) const {
    for (int i = 0; i < count; ++i) {
      bool same = true;
      for (int r = 0; r < K; ++r) same = same && axes[i][r] == t[r];
      if (same) return i;
    }
    return -1;
  }
  // The index of the monomial e_{a_1} ... e_{a_K}, its axes in any order.
  constexpr int index_unsorted(std::array<int, K> t) const {
    for (int i = 1; i < K; ++i)  // insertion sort: K <= 4
      for (int j = i; j > 0 && t[j - 1] > t[j]; --j) {
        const int x = t[j];
        t[j] = t[j - 1], t[j - 1] = x;
      }
    return index(t);
  }
};

}  // namespace detail

// One particle's pairs as the consistent Laplacian reads them, one array per quantity: the direction
// e_j = (x_j - x_i) / |x_j - x_i|, s_j = |x_j - x_i| / R, the weight g_j > 0 and, for the Laplacian of a
// field f, 2 g_j (f_j - f_i). One buffer per thread (laplacian_pair_buffer), so a particle's pairs
// allocate nothing once it has grown.
template <int D> struct LaplacianPairs {
  std::array<std::vector<double>, D> e, wdf;
  std::vector<double> s, g;
  std::size_t size = 0;

  void add(const Vector<D>& ej, double sj, double gj) {
    if (size == s.size()) grow();
    for (int a = 0; a < D; ++a) e[a][size] = ej(a);
    s[size] = sj, g[size] = gj;
    ++size;
  }
  void add(const Vector<D>& ej, double sj, double gj, const Vector<D>& wdfj) {
    if (size == s.size()) grow();
    for (int a = 0; a < D; ++a) e[a][size] = ej(a), wdf[a][size] = wdfj(a);
    s[size] = sj, g[size] = gj;
    ++size;
  }
  Vector<D> direction(std::size_t k) const {
    Vector<D> v;
    for (int a = 0; a < D; ++a) v(a) = e[a][k];
    return v;
  }
  // The pairs rounded up to whole lanes, the extra ones zero (weight 0: they add nothing).
  std::size_t padded() {
    std::size_t n = (size + detail::kLanes - 1) / detail::kLanes * detail::kLanes;
    while (s.size() < n) grow();
    for (std::size_t k = size; k < n; ++k) {
      for (int a = 0; a < D; ++a) e[a][k] = 0.0, wdf[a][k] = 0.0;
      s[k] = 0.0, g[k] = 0.0;
    }
    return n;
  }

 private:
  void grow() {
    const std::size_t n = s.empty() ? 64 : 2 * s.size();
    for (int a = 0; a < D; ++a) e[a].resize(n), wdf[a].resize(n);
    s.resize(n), g.resize(n);
  }
};

// The thread's pair buffer, emptied.
template <int D> LaplacianPairs<D>& laplacian_pair_buffer() {
  thread_local LaplacianPairs<D> buffer;
  buffer.size = 0;
  return buffer;
}

namespace detail {

// The distinct moments of a particle's pairs: sum_j g s^t e^alpha for the weights g s (degree 2 and 3
// monomials) and g s^2 (degree 3 and 4).
template <int D> struct LaplacianMoments {
  static constexpr int n2 = monomial_count(D, 2), n3 = monomial_count(D, 3), n4 = monomial_count(D, 4);
  std::array<double, n2> gs2{};
  std::array<double, n3> gs3{}, gss3{};
  std::array<double, n4> gss4{};
};

using Lanes = Eigen::Array<double, kLanes, 1>;

inline Lanes lanes_at(const std::vector<double>& v, std::size_t k) { return Eigen::Map<const Lanes>(v.data() + k); }

// The moments of the pairs [0, padded) of p.
template <int D> LaplacianMoments<D> sum_laplacian_moments(const LaplacianPairs<D>& p, std::size_t padded) {
  using L = Lanes;
  using M = LaplacianMoments<D>;
  constexpr Monomials<D, 2> m2;
  constexpr Monomials<D, 3> m3;
  constexpr Monomials<D, 4> m4;
  std::array<L, M::n2> gs2;
  std::array<L, M::n3> gs3, gss3;
  std::array<L, M::n4> gss4;
  for (auto& v : gs2) v.setZero();
  for (auto& v : gs3) v.setZero();
  for (auto& v : gss3) v.setZero();
  for (auto& v : gss4) v.setZero();
  for (std::size_t k = 0; k < padded; k += kLanes) {
    std::array<L, D> e;
    for (int a = 0; a < D; ++a) e[a] = lanes_at(p.e[a], k);
    const L gs = lanes_at(p.g, k) * lanes_at(p.s, k);
    const L gss = gs * lanes_at(p.s, k);
    std::array<L, M::n2> e2;
    std::array<L, M::n3> e3;
    for (int i = 0; i < M::n2; ++i) e2[i] = e[m2.axes[i][0]] * e[m2.axes[i][1]], gs2[i] += gs * e2[i];
    for (int i = 0; i < M::n3; ++i)
      e3[i] = e2[m3.prefix[i]] * e[m3.last[i]], gs3[i] += gs * e3[i], gss3[i] += gss * e3[i];
    for (int i = 0; i < M::n4; ++i) gss4[i] += gss * (e3[m4.prefix[i]] * e[m4.last[i]]);
  }
  M out;
  for (int i = 0; i < M::n2; ++i) out.gs2[i] = gs2[i].sum();
  for (int i = 0; i < M::n3; ++i) out.gs3[i] = gs3[i].sum(), out.gss3[i] = gss3[i].sum();
  for (int i = 0; i < M::n4; ++i) out.gss4[i] = gss4[i].sum();
  return out;
}

// The field moments of the pairs [0, padded) of p: second[q](c) = sum_j e^{alpha_q} 2 g_j (f_j - f_i)_c
// for the degree-2 monomials q, first(a, c) = sum_j e_a 2 g_j (f_j - f_i)_c.
template <int D> struct LaplacianFieldMoments {
  std::array<Vector<D>, monomial_count(D, 2)> second;
  Tensor<D> first;
};

template <int D> LaplacianFieldMoments<D> sum_laplacian_field_moments(const LaplacianPairs<D>& p, std::size_t padded) {
  using L = Lanes;
  constexpr int n2 = monomial_count(D, 2);
  constexpr Monomials<D, 2> m2;
  std::array<std::array<L, D>, n2> second;
  std::array<std::array<L, D>, D> first;
  for (auto& row : second)
    for (auto& v : row) v.setZero();
  for (auto& row : first)
    for (auto& v : row) v.setZero();
  for (std::size_t k = 0; k < padded; k += kLanes) {
    std::array<L, D> e, w;
    for (int a = 0; a < D; ++a) e[a] = lanes_at(p.e[a], k), w[a] = lanes_at(p.wdf[a], k);
    for (int i = 0; i < n2; ++i) {
      const L ee = e[m2.axes[i][0]] * e[m2.axes[i][1]];
      for (int c = 0; c < D; ++c) second[i][c] += ee * w[c];
    }
    for (int a = 0; a < D; ++a)
      for (int c = 0; c < D; ++c) first[a][c] += e[a] * w[c];
  }
  LaplacianFieldMoments<D> out;
  for (int i = 0; i < n2; ++i)
    for (int c = 0; c < D; ++c) out.second[i](c) = second[i][c].sum();
  for (int a = 0; a < D; ++a)
    for (int c = 0; c < D; ++c) out.first(a, c) = first[a][c].sum();
  return out;
}

}  // namespace detail

}  // namespace sph
