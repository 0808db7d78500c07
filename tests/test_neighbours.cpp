// Neighbour search against brute force: the k-d tree lists in open boxes (random points, lattices
// with distances exactly at and just under the radius, points in the solvers' curve order), and the
// periodic wrap of positions. Periodic images, the halo and the Verlet skin: test_neighbours_periodic.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "neighbour_particles.hpp"
#include "random_points.hpp"
#include "src/core/domain.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/neighbours/partition.hpp"
#include "src/particles/particles.hpp"

namespace {

using namespace sph;
using namespace sph::test;

// Brute force open-box lists: every j != i with |x_i - x_j| < radius, increasing j.
template <int D>
std::vector<std::vector<int>> brute_force(const std::vector<Vector<D>>& x, std::size_t n_query, double radius) {
  std::vector<std::vector<int>> nb(n_query);
  for (std::size_t i = 0; i < n_query; ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      if (j != i && (x[i] - x[j]).squaredNorm() < radius * radius) nb[i].push_back(static_cast<int>(j));
  return nb;
}

template <int D> std::vector<std::vector<int>> as_lists(const NeighbourList<D>& nl) {
  std::vector<std::vector<int>> nb(nl.size());
  for (std::size_t i = 0; i < nl.size(); ++i) nb[i].assign(nl.begin(i), nl.end(i));
  return nb;
}

// ---------------------------------------------------------------------------------------------
// Open boxes: NeighbourList against brute force.

template <int D> void random_points_match_brute_force() {
  SCOPED_TRACE("D = " + std::to_string(D));
  const Domain<D> dom = test_domain<D>({});
  const int n = D == 1 ? 300 : D == 2 ? 800 : 1200;
  const Particles<D> P = random_particles(dom, n, 11u + D);
  for (double radius : {0.013, 0.07, 0.19}) {
    NeighbourList<D> nl;
    nl.build(P.x, P.x.size(), radius);
    EXPECT_EQ(nl.size(), P.x.size());
    EXPECT_DOUBLE_EQ(nl.radius(), radius);
    const auto want = brute_force(P.x, P.x.size(), radius);
    std::size_t total = 0;
    for (const auto& w : want) total += w.size();
    EXPECT_EQ(nl.total(), total);
    EXPECT_EQ(as_lists(nl), want) << "radius " << radius;  // same sets, in increasing index order
    for (std::size_t i = 0; i < nl.size(); ++i) EXPECT_EQ(nl.count(i), want[i].size());
  }
  // Queries on a prefix only; candidates are still every point.
  NeighbourList<D> nl;
  nl.build(P.x, n / 3, 0.1);
  EXPECT_EQ(nl.size(), static_cast<std::size_t>(n / 3));
  EXPECT_EQ(as_lists(nl), brute_force(P.x, n / 3, 0.1));
}

template <int D> void lattice_matches_brute_force() {
  SCOPED_TRACE("D = " + std::to_string(D));
  const int n = D == 1 ? 50 : D == 2 ? 24 : 10;
  const Domain<D> dom = make_domain<D>(Vector<D>::Zero(), Vector<D>::Ones(), {});
  const Particles<D> P = lattice_particles(dom, n);
  const double dx = 1.0 / n;
  // Radii between lattice distances (r^2/dx^2 = 2.5^2 = 6.25, 1.7^2 = 2.89: no sum of squares of
  // integers), and radii just above a lattice distance (2 dx, sqrt(5) dx) so that points at distance
  // just under the radius must be found.
  for (double rq : {1.7, 2.5, 2.0 * (1.0 + 1e-9), std::sqrt(5.0) * (1.0 + 1e-9), 3.0 * (1.0 + 1e-9)}) {
    const double radius = rq * dx;
    NeighbourList<D> nl;
    nl.build(P.x, P.x.size(), radius);
    const auto got = as_lists(nl);
    EXPECT_EQ(got, brute_force(P.x, P.x.size(), radius)) << "radius/dx " << rq;
    // An interior particle sees exactly the lattice points inside the ball (counted directly).
    const int c = n / 2;
    std::size_t centre = 0;
    for (int a = 0, m = 1; a < D; ++a, m *= n) centre += static_cast<std::size_t>(c * m);
    const int reach = static_cast<int>(std::ceil(rq));
    int expected = 0, span = 2 * reach + 1, combos = 1;
    for (int a = 0; a < D; ++a) combos *= span;
    for (int k = 0; k < combos; ++k) {
      long s2 = 0;
      for (int a = 0, m = k; a < D; ++a, m /= span) s2 += (m % span - reach) * (m % span - reach);
      if (s2 > 0 && s2 < rq * rq) ++expected;
    }
    EXPECT_EQ(static_cast<int>(got[centre].size()), expected) << "radius/dx " << rq;
  }
}

// Points in the order the solvers keep them, along the Morton curve, so that the search takes runs of
// consecutive points together; every 37th point is moved far from its place in the order (a run must
// end there, not grow a box over the whole cloud), and queries stop part-way through a run.
template <int D> void curve_ordered_points_match_brute_force() {
  SCOPED_TRACE("D = " + std::to_string(D));
  const Domain<D> dom = test_domain<D>({});
  const int n = D == 2 ? 3000 : 4000;
  std::vector<Vector<D>> x = test::random_points(dom, n, 5u + D);
  std::vector<std::pair<std::uint64_t, int>> keyed(n);
  for (int i = 0; i < n; ++i) keyed[i] = {morton_key<D>(x[i], dom.lo, dom.hi), i};
  std::sort(keyed.begin(), keyed.end());
  std::vector<Vector<D>> sorted(n);
  for (int i = 0; i < n; ++i) sorted[i] = x[keyed[i].second];
  for (int i = 0; i < n; i += 37) std::swap(sorted[i], sorted[n - 1 - i]);
  for (double radius : {0.02, 0.06, 0.15})
    for (std::size_t n_query : {static_cast<std::size_t>(n), static_cast<std::size_t>(n / 2 + 5)}) {
      NeighbourList<D> nl;
      nl.build(sorted, n_query, radius);
      EXPECT_EQ(as_lists(nl), brute_force(sorted, n_query, radius)) << "radius " << radius << ", queries " << n_query;
    }
}

TEST(NeighbourList, CurveOrderedPointsMatchBruteForce) {
  curve_ordered_points_match_brute_force<2>();
  curve_ordered_points_match_brute_force<3>();
}

TEST(NeighbourList, OpenBoxMatchesBruteForce) {
  random_points_match_brute_force<1>();
  random_points_match_brute_force<2>();
  random_points_match_brute_force<3>();
  lattice_matches_brute_force<1>();
  lattice_matches_brute_force<2>();
  lattice_matches_brute_force<3>();
}

TEST(NeighbourList, DistancesJustUnderAndOverTheRadiusAndCoincidentPoints) {
  // A centre with points on a sphere of radius r(1 - 1e-9) (found) and r(1 + 1e-9) (not found), and
  // one exactly at r (not found: the support is open).
  const double r = 0.37;
  std::vector<Vector<3>> x{Vector<3>(0.1, -0.2, 0.3)};
  std::mt19937 gen(3);
  std::normal_distribution<double> g;
  std::vector<int> inside;
  for (int k = 0; k < 60; ++k) {
    Vector<3> d(g(gen), g(gen), g(gen));
    d.normalize();
    const double f = k % 2 ? 1.0 + 1e-9 : 1.0 - 1e-9;
    if (f < 1.0) inside.push_back(static_cast<int>(x.size()));
    x.push_back(x[0] + f * r * d);
  }
  x.push_back(x[0] + Vector<3>(r, 0.0, 0.0));
  ASSERT_EQ((x.back() - x[0]).squaredNorm(), r * r);
  NeighbourList<3> nl;
  nl.build(x, 1, r);
  EXPECT_EQ(std::vector<int>(nl.begin(0), nl.end(0)), inside);

  // Coincident points are neighbours of each other (distance 0 < radius); a point is never its own.
  std::vector<Vector<2>> y{Vector<2>(0, 0), Vector<2>(0, 0), Vector<2>(5, 5)};
  NeighbourList<2> nl2;
  nl2.build(y, 3, 1.0);
  EXPECT_EQ(std::vector<int>(nl2.begin(0), nl2.end(0)), std::vector<int>{1});
  EXPECT_EQ(std::vector<int>(nl2.begin(1), nl2.end(1)), std::vector<int>{0});
  EXPECT_EQ(nl2.count(2), 0u);
}

}  // namespace

// A periodic wrap maps any distance back in one step: a particle flung 1e300 away by a forced huge
// step once made the neighbour search loop for ever; a non-finite one stays non-finite for the
// blow-up check.
TEST(Domain, WrapMapsAnyDistanceBackInOneStep) {
  sph::Domain<2> box;
  box.lo = sph::Vector<2>(-1.0, 0.0);
  box.hi = sph::Vector<2>(1.0, 1.0);
  box.periodic = {true, false};
  EXPECT_DOUBLE_EQ(box.wrap(sph::Vector<2>(2.5, 0.5))[0], 0.5);
  EXPECT_DOUBLE_EQ(box.wrap(sph::Vector<2>(-3.25, 0.5))[0], 0.75);
  EXPECT_DOUBLE_EQ(box.wrap(sph::Vector<2>(1.0, 0.5))[0], -1.0);  // hi is outside, lo inside
  const sph::Vector<2> far = box.wrap(sph::Vector<2>(1e300, 7.0));
  EXPECT_GE(far[0], -1.0);
  EXPECT_LT(far[0], 1.0);
  EXPECT_EQ(far[1], 7.0);  // not a periodic axis
  EXPECT_FALSE(std::isfinite(box.wrap(sph::Vector<2>(INFINITY, 0.5))[0]));
  EXPECT_FALSE(std::isfinite(box.wrap(sph::Vector<2>(NAN, 0.5))[0]));
}
