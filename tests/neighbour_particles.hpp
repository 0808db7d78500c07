#pragma once
// Particle sets for the neighbour-search tests: boxes away from the origin, random clouds and
// lattices, with per-particle fields that differ so ghosts can be traced to their sources.
#include <array>
#include <vector>

#include "random_points.hpp"
#include "src/core/domain.hpp"
#include "src/particles/particles.hpp"

namespace sph::test {

template <int D> Domain<D> make_domain(const Vector<D>& lo, const Vector<D>& hi, std::array<bool, D> periodic) {
  Domain<D> d;
  d.lo = lo;
  d.hi = hi;
  d.periodic = periodic;
  return d;
}

// A box that is neither the unit box nor anchored at the origin.
template <int D> Domain<D> test_domain(std::array<bool, D> periodic) {
  Vector<D> lo, hi;
  for (int a = 0; a < D; ++a) {
    lo[a] = -0.3 + 0.1 * a;
    hi[a] = lo[a] + 1.0 + 0.2 * a;
  }
  return make_domain<D>(lo, hi, periodic);
}

template <int D> void add_particle(Particles<D>& P, const Vector<D>& x) {
  const std::size_t i = P.n_owned;
  Vector<D> v;
  for (int a = 0; a < D; ++a) v[a] = 0.1 * (a + 1) + 0.001 * i;
  P.add(x, v, 1.0 + 0.01 * i, 1000.0 + i, -5.0 * i, static_cast<int>(i % 2));
  P.gid.back() = static_cast<GlobalIndex>(i);
  P.n_global = static_cast<GlobalIndex>(P.n_owned);
}

template <int D> Particles<D> random_particles(const Domain<D>& dom, int n, unsigned seed) {
  Particles<D> P;
  for (const Vector<D>& x : test::random_points(dom, n, seed)) add_particle(P, x);
  return P;
}

// n points per axis at cell centres (k + 0.5) * L / n: spacing L/n along each axis.
template <int D> Particles<D> lattice_particles(const Domain<D>& dom, int n) {
  Particles<D> P;
  int total = 1;
  for (int a = 0; a < D; ++a) total *= n;
  for (int k = 0; k < total; ++k) {
    Vector<D> x;
    for (int a = 0, c = k; a < D; ++a, c /= n) x[a] = dom.lo[a] + (c % n + 0.5) * (dom.hi[a] - dom.lo[a]) / n;
    add_particle(P, x);
  }
  return P;
}

}  // namespace sph::test
