#pragma once
// Points drawn uniformly in a domain's box: the same sequence for a given seed on every rank, so
// tests can build one global cloud and split it as they need.
#include <random>
#include <vector>

#include "src/core/domain.hpp"

namespace sph::test {

template <int D> std::vector<Vector<D>> random_points(const Domain<D>& dom, int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vector<D>> points(n);
  for (Vector<D>& x : points)
    for (int a = 0; a < D; ++a) x[a] = dom.lo[a] + u(gen) * (dom.hi[a] - dom.lo[a]);
  return points;
}

}  // namespace sph::test
