#pragma once
// The simulation box: bounds and, per axis, whether the box is periodic.
#include <array>

#include "src/core/types.hpp"

namespace sph {

template <int D> struct Domain {
  Vector<D> lo = Vector<D>::Zero();
  Vector<D> hi = Vector<D>::Ones();
  std::array<bool, D> periodic{};

  Vector<D> length() const { return hi - lo; }

  // Maps a point back into the box along periodic axes.
  Vector<D> wrap(Vector<D> x) const {
    for (int a = 0; a < D; ++a) {
      if (!periodic[a]) continue;
      const double L = hi[a] - lo[a];
      while (x[a] < lo[a]) x[a] += L;
      while (x[a] >= hi[a]) x[a] -= L;
    }
    return x;
  }
};

}  // namespace sph
