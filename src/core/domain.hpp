#pragma once
// The simulation box: bounds and, per axis, whether the box is periodic.
#include <array>
#include <cmath>
#include <memory>

#include "src/core/types.hpp"
#include "src/neighbours/screens.hpp"

namespace sph {

template <int D> struct Domain {
  Vector<D> lo = Vector<D>::Zero();
  Vector<D> hi = Vector<D>::Ones();
  std::array<bool, D> periodic{};
  // Thin plates that hide the particles on one side from those on the other (null: none); a moving
  // body moves its plates (MovingBodies::move_to), and every copy of the domain sees them there.
  std::shared_ptr<Screens<D>> screens;

  Vector<D> length() const { return hi - lo; }

  // Whether x lies beyond a side that is not periodic (through which nothing comes back).
  bool outside(const Vector<D>& x) const {
    for (int a = 0; a < D; ++a)
      if (!periodic[a] && (x[a] < lo[a] || x[a] > hi[a])) return true;
    return false;
  }

  // Maps a point back into the box along periodic axes, in one step whatever the distance (a point
  // flung far away must not loop for ever; a non-finite one stays non-finite for the blow-up check).
  Vector<D> wrap(Vector<D> x) const {
    for (int a = 0; a < D; ++a) {
      if (!periodic[a] || (x[a] >= lo[a] && x[a] < hi[a])) continue;
      const double L = hi[a] - lo[a];
      x[a] -= std::floor((x[a] - lo[a]) / L) * L;
      if (x[a] >= hi[a]) x[a] -= L;  // rounding
      if (x[a] < lo[a]) x[a] = lo[a];
    }
    return x;
  }
};

}  // namespace sph
