#pragma once
// Geometric checks of a scene read from a file, made once on the whole scene before the run: does the
// fluid have a free surface, and how thick are the walls. Lattice counts within 2 dx: 13 neighbours
// (self included) in 2D and 33 in 3D inside a filled region; a particle on a flat face of the filled
// region has 9 (2D) or 23 (3D), about 0.7 of them.
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

#include "src/core/domain.hpp"
#include "src/particles/particles.hpp"

namespace sph {

// Particles binned in cells of about `cell` (periodic axes: an exact divisor of the box length), for
// searches within a radius up to a few cells; distances across periodic sides use the nearest image.
template <int D> class PointGrid {
 public:
  PointGrid(const std::vector<Vector<D>>& x, const Domain<D>& box, double cell) : x_(x), box_(box) {
    for (int a = 0; a < D; ++a) {
      const double L = box.hi[a] - box.lo[a];
      n_[a] = box.periodic[a] ? std::max(1L, static_cast<long>(std::floor(L / cell))) : 0;
      cell_[a] = box.periodic[a] ? L / n_[a] : cell;
    }
    for (std::size_t i = 0; i < x.size(); ++i) cells_[key(index(x[i]))].push_back(static_cast<int>(i));
  }

  // Calls f(j, x_j - x) for every particle j within r of x (x itself included when it is a particle).
  template <class F> void for_each_within(const Vector<D>& x, double r, F&& f) const {
    const std::array<long, D> c = index(x);
    std::array<long, D> reach{};
    for (int a = 0; a < D; ++a) reach[a] = static_cast<long>(std::ceil(r / cell_[a]));
    std::array<long, D> o{};
    for (int a = 0; a < D; ++a) o[a] = -reach[a];
    while (true) {
      std::array<long, D> k{};
      bool repeat = false;  // a periodic axis shorter than the search: visit each cell once
      for (int a = 0; a < D; ++a) {
        k[a] = c[a] + o[a];
        if (box_.periodic[a]) {
          repeat |= o[a] - (-reach[a]) >= n_[a];
          k[a] = ((k[a] % n_[a]) + n_[a]) % n_[a];
        }
      }
      const auto it = repeat ? cells_.end() : cells_.find(key(k));
      if (it != cells_.end())
        for (int j : it->second) {
          const Vector<D> d = separation(x, x_[j]);
          if (d.squaredNorm() <= r * r) f(j, d);
        }
      int a = 0;
      while (a < D && ++o[a] > reach[a]) o[a] = -reach[a], ++a;
      if (a == D) break;
    }
  }

  // x_j - x across periodic sides by the nearest image.
  Vector<D> separation(const Vector<D>& x, const Vector<D>& xj) const {
    Vector<D> d = xj - x;
    for (int a = 0; a < D; ++a)
      if (box_.periodic[a]) {
        const double L = box_.hi[a] - box_.lo[a];
        d[a] -= L * std::round(d[a] / L);
      }
    return d;
  }

 private:
  std::array<long, D> index(const Vector<D>& x) const {
    std::array<long, D> c{};
    const Vector<D> w = box_.wrap(x);
    for (int a = 0; a < D; ++a) {
      c[a] = static_cast<long>(std::floor((w[a] - box_.lo[a]) / cell_[a]));
      if (box_.periodic[a]) c[a] = std::min(std::max(c[a], 0L), n_[a] - 1);
    }
    return c;
  }
  static long long key(const std::array<long, D>& c) {
    long long k = 0;
    for (int a = 0; a < D; ++a) k = k * 2000003LL + (c[a] + 1000000LL);
    return k;
  }

  const std::vector<Vector<D>>& x_;
  const Domain<D>& box_;
  std::array<long, D> n_{};
  std::array<double, D> cell_{};
  std::unordered_map<long long, std::vector<int>> cells_;
};

// A region's face: fewer than this share of the fullest particle's count within 2 dx.
constexpr double kFaceShare = 0.75;

// Neighbour counts within 2 dx (all kinds, self included).
template <int D>
std::vector<int> neighbour_counts(const PointGrid<D>& grid, const std::vector<Vector<D>>& x, double dx) {
  std::vector<int> count(x.size(), 0);
  for (std::size_t i = 0; i < x.size(); ++i)
    grid.for_each_within(x[i], 2.0 * dx * (1 + 1e-9), [&](int, const Vector<D>&) { ++count[i]; });
  return count;
}

// True when some fluid particle lies on a face of the filled region: an open side, a free surface.
template <int D> bool has_open_fluid_face(const std::vector<int>& count, const std::vector<int>& kind) {
  const int full = *std::max_element(count.begin(), count.end());
  for (std::size_t i = 0; i < count.size(); ++i)
    if (kind[i] == kFluid && count[i] < kFaceShare * full) return true;
  return false;
}

struct WallThickness {
  double thickness = 0.0;    // 0: no walls
  std::size_t particle = 0;  // where the thinnest wall was measured
};

// Wall thickness, measured from every wall particle on a face of a wall (one that touches fluid, or
// one on a face towards empty space, which fluid may reach later): walking into the wall in steps of
// dx, along the face's normal and along the lattice axis nearest to it (the larger of the two, so that
// a walk which leaves a thick wall sideways near a corner does not count), the wall is (1 + the
// consecutive steps that land within half a cell diagonal of a wall particle) dx thick. Walls of L
// lattice layers measure L dx. Capped at 16 dx.
template <int D> WallThickness measure_wall_thickness(const PointGrid<D>& grid, const std::vector<Vector<D>>& x,
                                                      const std::vector<int>& kind, const std::vector<int>& count,
                                                      double dx) {
  const int full = *std::max_element(count.begin(), count.end());
  const double near = 0.5 * std::sqrt(double(D)) * dx * 1.05, reach = 2.0 * dx * (1 + 1e-9);
  const int cap = 16;
  auto walk = [&](const Vector<D>& from, const Vector<D>& dir) {
    int k = 1;
    for (; k < cap; ++k) {
      bool wall = false;
      grid.for_each_within(from + k * dx * dir, near, [&](int j, const Vector<D>&) { wall |= kind[j] != kFluid; });
      if (!wall) break;
    }
    return k;
  };
  WallThickness w;
  int thinnest = cap + 1;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (kind[i] == kFluid) continue;
    // Into the wall: away from the fluid next to it, else away from the empty side.
    Vector<D> from_fluid = Vector<D>::Zero(), into_mass = Vector<D>::Zero();
    bool touches_fluid = false;
    grid.for_each_within(x[i], reach, [&](int j, const Vector<D>& d) {
      if (d.squaredNorm() == 0.0) return;
      into_mass += d / d.norm();
      if (kind[j] != kFluid) return;
      from_fluid -= d / d.norm();
      // Fluid a lattice step away: the wall's first layer. A deeper particle that sees fluid only
      // diagonally, where a wall curves, would measure the layers below it alone.
      touches_fluid |= d.norm() < 1.05 * dx;
    });
    const bool face = count[i] < kFaceShare * full;
    if (!touches_fluid && !face) continue;
    const Vector<D> n = touches_fluid ? from_fluid : into_mass;
    if (n.norm() < 1e-9) {  // fluid on every side: a wall one particle thick
      if (1 < thinnest) thinnest = 1, w.particle = i;
      continue;
    }
    const Vector<D> dir = n / n.norm();
    int axis = 0;
    for (int a = 1; a < D; ++a)
      if (std::abs(dir[a]) > std::abs(dir[axis])) axis = a;
    Vector<D> along = Vector<D>::Zero();
    along[axis] = dir[axis] > 0 ? 1.0 : -1.0;
    const int layers = std::max(walk(x[i], dir), walk(x[i], along));
    if (layers < thinnest) thinnest = layers, w.particle = i;
  }
  if (thinnest <= cap) w.thickness = thinnest * dx;
  return w;
}

}  // namespace sph
