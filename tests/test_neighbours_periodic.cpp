// Periodic images (Halo + NeighbourList, through Neighbourhood) against an O(N^2) search over every
// periodic image, in 2D and 3D, fully and partially periodic. Also the ghost layer itself (positions
// are source + a multiple of the box length, field refreshes copy the source values) and the Verlet
// skin (no rebuild while particles moved less than skin/2, and the stale lists still hold every pair
// within the support).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "neighbour_particles.hpp"
#include "src/core/domain.hpp"
#include "src/core/error.hpp"
#include "src/neighbours/halo.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/particles/particles.hpp"

namespace {

using namespace sph;
using namespace sph::test;

// A pair (i, source k, periodic shift in box lengths): the neighbour is x_k + shift * L.
using Pair = std::tuple<int, long, std::array<int, 3>>;

// Integer multiple of the box length separating a ghost from its source (checked to be integral).
template <int D> std::array<int, 3> shift_of(const Domain<D>& dom, const Vector<D>& ghost, const Vector<D>& src) {
  std::array<int, 3> s{0, 0, 0};
  const Vector<D> L = dom.length();
  for (int a = 0; a < D; ++a) {
    const double q = (ghost[a] - src[a]) / L[a];
    s[a] = static_cast<int>(std::lround(q));
    EXPECT_NEAR(q, s[a], 1e-12) << "ghost not at a periodic image of its source, axis " << a;
    if (!dom.periodic[a]) {
      EXPECT_EQ(s[a], 0) << "image across non-periodic axis " << a;
    }
  }
  return s;
}

// Pairs within `radius` of owned particle i, from the neighbour list at the current positions.
template <int D> std::vector<Pair> pairs_from_list(const Particles<D>& P, const NeighbourList<D>& nl,
                                                   const Domain<D>& dom, double radius) {
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    for (const int* it = nl.begin(i); it != nl.end(i); ++it) {
      const int j = *it;
      if ((P.x[i] - P.x[j]).squaredNorm() >= radius * radius) continue;
      const long k = static_cast<long>(P.gid[j]);
      pairs.emplace_back(static_cast<int>(i), k, shift_of<D>(dom, P.x[j], P.x[k]));
    }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Brute force over every owned source k and every periodic image x_k + s L (s integer along periodic
// axes, unbounded: per axis, every s whose image could lie within the radius is tried; no assumption
// about which images the halo should make).
template <int D> std::vector<Pair> pairs_brute_force(const Particles<D>& P, const Domain<D>& dom, double radius) {
  std::vector<Pair> pairs;
  const Vector<D> L = dom.length();
  for (std::size_t i = 0; i < P.n_owned; ++i)
    for (std::size_t k = 0; k < P.n_owned; ++k) {
      std::array<int, 3> lo{0, 0, 0}, n{1, 1, 1};  // per axis: first shift tried, number of shifts
      bool any = true;
      for (int a = 0; a < D && any; ++a) {
        const double d = P.x[i][a] - P.x[k][a];
        if (!dom.periodic[a]) {
          any = std::abs(d) < radius;
          continue;
        }
        // |d - s L| < radius needs (d - radius)/L < s < (d + radius)/L; the closed range is tried.
        lo[a] = static_cast<int>(std::floor((d - radius) / L[a]));
        n[a] = static_cast<int>(std::ceil((d + radius) / L[a])) - lo[a] + 1;
      }
      if (!any) continue;
      for (int c = 0; c < n[0] * n[1] * n[2]; ++c) {
        std::array<int, 3> s{0, 0, 0};
        for (int a = 0, m = c; a < D; m /= n[a], ++a) s[a] = lo[a] + m % n[a];
        Vector<D> xk = P.x[k];
        for (int a = 0; a < D; ++a) xk[a] += s[a] * L[a];
        const double r2 = (P.x[i] - xk).squaredNorm();
        if ((k == i && s == std::array<int, 3>{0, 0, 0}) || r2 >= radius * radius) continue;
        pairs.emplace_back(static_cast<int>(i), static_cast<long>(k), s);
      }
    }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Ghost layer invariants: gids point at owned sources, positions are periodic images of them.
template <int D> void check_ghosts(const Particles<D>& P, const Domain<D>& dom) {
  for (std::size_t g = P.n_owned; g < P.size(); ++g) {
    const long k = static_cast<long>(P.gid[g]);
    ASSERT_GE(k, 0);
    ASSERT_LT(k, static_cast<long>(P.n_owned));
    const std::array<int, 3> s = shift_of<D>(dom, P.x[g], P.x[k]);
    EXPECT_TRUE(s[0] != 0 || s[1] != 0 || s[2] != 0) << "ghost " << g << " sits on its source";
    EXPECT_EQ(P.m[g], P.m[k]);
    EXPECT_EQ(P.rho[g], P.rho[k]);
    EXPECT_EQ(P.p[g], P.p[k]);
    EXPECT_EQ(P.kind[g], P.kind[k]);
    EXPECT_EQ(P.v[g], P.v[k]);
  }
}

template <int D> void expect_same_pairs(const std::vector<Pair>& got, const std::vector<Pair>& want) {
  EXPECT_EQ(got.size(), want.size());
  std::vector<Pair> missing, extra;
  std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(missing));
  std::set_difference(got.begin(), got.end(), want.begin(), want.end(), std::back_inserter(extra));
  EXPECT_TRUE(missing.empty()) << missing.size() << " pairs missing, first: i=" << std::get<0>(missing[0])
                               << " k=" << std::get<1>(missing[0]);
  EXPECT_TRUE(extra.empty()) << extra.size() << " extra pairs, first: i=" << std::get<0>(extra[0])
                             << " k=" << std::get<1>(extra[0]);
}

// Builds ghosts and lists through Neighbourhood and compares with brute force over all images.
template <int D> void check_periodic(Particles<D> P, const Domain<D>& dom, double radius) {
  Neighbourhood<D> nh(dom, radius, 0.0);
  EXPECT_TRUE(nh.update(P, true));
  EXPECT_EQ(nh.halo().n_owned(), P.n_owned);
  EXPECT_EQ(nh.halo().n_ghost(), P.n_ghost);
  EXPECT_EQ(nh.list().size(), P.n_owned);
  check_ghosts(P, dom);
  const std::vector<Pair> want = pairs_brute_force(P, dom, radius);
  ASSERT_FALSE(want.empty());
  expect_same_pairs<D>(pairs_from_list(P, nh.list(), dom, radius), want);
  // The list holds nothing beyond the radius either.
  std::size_t beyond = 0;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    for (const int* it = nh.list().begin(i); it != nh.list().end(i); ++it)
      if ((P.x[i] - P.x[*it]).squaredNorm() >= radius * radius) ++beyond;
  EXPECT_EQ(beyond, 0u);
}

// ---------------------------------------------------------------------------------------------
// Periodic boxes: Neighbourhood (Halo + NeighbourList) against brute force over all images.

TEST(NeighbourPeriodic, RandomPointsMatchBruteForceOverImages) {
  {
    SCOPED_TRACE("2D fully periodic");
    const Domain<2> dom = test_domain<2>({true, true});
    for (double radius : {0.05, 0.21, 0.4}) check_periodic(random_particles(dom, 700, 21u), dom, radius);
  }
  for (std::array<bool, 2> per : {std::array<bool, 2>{true, false}, std::array<bool, 2>{false, true}}) {
    SCOPED_TRACE("2D periodic in " + std::string(per[0] ? "x" : "y"));
    const Domain<2> dom = test_domain<2>(per);
    for (double radius : {0.07, 0.3}) check_periodic(random_particles(dom, 600, 22u), dom, radius);
  }
  for (std::array<bool, 3> per : {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, false, true},
                                  std::array<bool, 3>{false, false, true}}) {
    SCOPED_TRACE("3D periodic " + std::to_string(per[0]) + std::to_string(per[1]) + std::to_string(per[2]));
    const Domain<3> dom = test_domain<3>(per);
    for (double radius : {0.12, 0.3}) check_periodic(random_particles(dom, 700, 23u), dom, radius);
  }
}

TEST(NeighbourPeriodic, LatticeMatchesBruteForceOverImages) {
  // Radii between lattice distances, and just above 3 dx / 2 dx so that points at distance just
  // under the radius (across the periodic faces too) must be found.
  const double dx2 = 1.0 / 20;
  for (double rq : {1.7, 2.5, 3.0 * (1.0 + 1e-9)}) {
    SCOPED_TRACE("2D, radius/dx " + std::to_string(rq));
    const Domain<2> dom = make_domain<2>(Vector<2>::Zero(), Vector<2>::Ones(), {true, true});
    check_periodic(lattice_particles(dom, 20), dom, rq * dx2);
    const Domain<2> half = make_domain<2>(Vector<2>::Zero(), Vector<2>::Ones(), {false, true});
    check_periodic(lattice_particles(half, 20), half, rq * dx2);
  }
  const double dx3 = 1.0 / 10;
  for (std::array<bool, 3> per : {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{false, true, false}}) {
    const Domain<3> dom = make_domain<3>(Vector<3>::Zero(), Vector<3>::Ones(), per);
    for (double rq : {1.5, 2.0 * (1.0 + 1e-9), 2.5}) {
      SCOPED_TRACE("3D, radius/dx " + std::to_string(rq));
      check_periodic(lattice_particles(dom, 10), dom, rq * dx3);
    }
  }
}

TEST(NeighbourPeriodic, WrapsOwnedParticlesAndRejectsTooSmallBoxes) {
  const Domain<2> dom = test_domain<2>({true, false});
  Particles<2> P = random_particles(dom, 200, 5u);
  const Vector<2> L = dom.length();
  // Push some particles outside along the periodic axis (by up to 1.5 box lengths).
  for (std::size_t i = 0; i < P.n_owned; i += 3) P.x[i][0] += (i % 2 ? 1.5 : -1.2) * L[0];
  const std::vector<Vector<2>> before(P.x.begin(), P.x.end());
  Neighbourhood<2> nh(dom, 0.15, 0.0);
  nh.update(P, true);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    EXPECT_GE(P.x[i][0], dom.lo[0]);
    EXPECT_LT(P.x[i][0], dom.hi[0]);
    EXPECT_EQ(P.x[i][1], before[i][1]);
    const double q = (before[i][0] - P.x[i][0]) / L[0];
    EXPECT_NEAR(q, std::round(q), 1e-12);
  }
  check_ghosts(P, dom);
  expect_same_pairs<2>(pairs_from_list(P, nh.list(), dom, 0.15), pairs_brute_force(P, dom, 0.15));

  // A periodic box must be longer than twice the search radius (one image per neighbour).
  const Domain<2> unit = make_domain<2>(Vector<2>::Zero(), Vector<2>::Ones(), {true, false});
  Particles<2> Q = random_particles(unit, 50, 1u);
  Neighbourhood<2> too_wide(unit, 0.5, 0.0);  // needs L > 2 * 0.5
  EXPECT_THROW(too_wide.update(Q, true), sph::Error);
}

// ---------------------------------------------------------------------------------------------
// The halo: field refreshes copy owned values into the ghost slots.

TEST(NeighbourHalo, UpdateCopiesOwnedValuesIntoGhosts) {
  const Domain<3> dom = test_domain<3>({true, true, false});
  Particles<3> P = random_particles(dom, 400, 9u);
  Halo<3> halo;
  halo.build(P, dom, 0.2);
  ASSERT_GT(halo.n_ghost(), 0u);
  EXPECT_EQ(halo.n_owned(), P.n_owned);
  EXPECT_EQ(P.size(), P.n_owned + halo.n_ghost());
  for (std::size_t g = 0; g < halo.n_ghost(); ++g) EXPECT_EQ(halo.owner_rank(g), 0);
  check_ghosts(P, dom);
  // A particle has an image for each periodic shift that lands within 0.2 of the particles' bounding
  // box (so within reach of particles across the face), and no other.
  std::vector<int> images(P.n_owned, 0);
  for (std::size_t g = P.n_owned; g < P.size(); ++g) ++images[P.gid[g]];
  Vector<3> lo = P.x[0], hi = P.x[0];
  for (std::size_t i = 0; i < P.n_owned; ++i) lo = lo.cwiseMin(P.x[i]), hi = hi.cwiseMax(P.x[i]);
  const Vector<3> L = dom.length();
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    int expected = 0;
    for (int sx = -1; sx <= 1; ++sx)
      for (int sy = -1; sy <= 1; ++sy) {
        if (sx == 0 && sy == 0) continue;
        const Vector<3> y = P.x[i] + Vector<3>(sx * L[0], sy * L[1], 0.0);
        if (((y.array() >= lo.array() - 0.2) && (y.array() <= hi.array() + 0.2)).all()) ++expected;
      }
    EXPECT_EQ(images[i], expected) << "particle " << i;
  }

  const std::size_t n = P.n_owned, ng = halo.n_ghost();
  std::vector<double> fd(n);
  std::vector<int> fi(n);
  std::vector<GlobalIndex> fg(n);
  std::vector<Vector<3>> fv(n);
  std::vector<Eigen::Matrix<double, 3, 3>> ft(n);
  for (std::size_t i = 0; i < n; ++i) {
    fd[i] = std::sin(1.0 + i);
    fi[i] = static_cast<int>(7 * i) - 100;
    fg[i] = static_cast<GlobalIndex>(1000 + i);
    fv[i] = Vector<3>(i, -2.0 * i, std::cos(1.0 * i));
    for (int a = 0; a < 9; ++a) ft[i](a) = i + 0.1 * a;
  }
  halo.update(fd), halo.update(fi), halo.update(fg), halo.update(fv), halo.update(ft);
  ASSERT_EQ(fd.size(), n + ng);
  ASSERT_EQ(fi.size(), n + ng);
  ASSERT_EQ(fg.size(), n + ng);
  ASSERT_EQ(fv.size(), n + ng);
  ASSERT_EQ(ft.size(), n + ng);
  for (std::size_t g = n; g < n + ng; ++g) {
    const std::size_t k = static_cast<std::size_t>(P.gid[g]);
    EXPECT_EQ(fd[g], fd[k]);
    EXPECT_EQ(fi[g], fi[k]);
    EXPECT_EQ(fg[g], fg[k]);
    EXPECT_EQ(fv[g], fv[k]);
    EXPECT_EQ(ft[g], ft[k]);
  }

  // Owned values changed later: the next refresh carries them, and positions keep their shifts.
  std::vector<Vector<3>> shift(ng);
  for (std::size_t g = 0; g < ng; ++g) shift[g] = P.x[n + g] - P.x[P.gid[n + g]];
  for (std::size_t i = 0; i < n; ++i) {
    fd[i] = -3.0 * i;
    P.x[i] += Vector<3>(0.01, -0.02, 0.005);
  }
  halo.update(fd);
  halo.update_positions(P.x);
  for (std::size_t g = n; g < n + ng; ++g) {
    const std::size_t k = static_cast<std::size_t>(P.gid[g]);
    EXPECT_EQ(fd[g], fd[k]);
    EXPECT_LT((P.x[g] - P.x[k] - shift[g - n]).norm(), 1e-14);
  }
}

// ---------------------------------------------------------------------------------------------
// The Verlet skin.

template <int D> void check_skin(const Domain<D>& dom, int n, unsigned seed) {
  const double support = 0.12, skin = 0.04;
  Particles<D> P = random_particles(dom, n, seed);
  Neighbourhood<D> nh(dom, support, skin);
  ASSERT_TRUE(nh.update(P, true));
  EXPECT_EQ(nh.rebuilds(), 1);
  EXPECT_FALSE(nh.update(P));  // nothing moved
  std::mt19937 gen(seed + 1);
  std::normal_distribution<double> g;
  // Several small moves, each taking particles up to 0.49 skin from where the lists were built.
  const std::vector<Vector<D>> x0(P.x.begin(), P.x.begin() + P.n_owned);
  for (int step = 0; step < 3; ++step) {
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      Vector<D> d;
      for (int a = 0; a < D; ++a) d[a] = g(gen);
      P.x[i] = x0[i] + (0.49 * skin * (step + 1) / 3.0) * d.normalized();
    }
    EXPECT_FALSE(nh.update(P)) << "rebuilt although no particle moved skin/2";
    EXPECT_EQ(nh.rebuilds(), 1);
    // Ghost positions and velocities follow their sources.
    for (std::size_t gi = P.n_owned; gi < P.size(); ++gi) shift_of<D>(dom, P.x[gi], P.x[P.gid[gi]]);
    expect_same_pairs<D>(pairs_from_list(P, nh.list(), dom, support), pairs_brute_force(P, dom, support));
  }
  // One particle moving skin/2 or more forces a rebuild.
  P.x[0] = x0[0];
  P.x[0][0] += 0.51 * skin;
  EXPECT_TRUE(nh.update(P));
  EXPECT_EQ(nh.rebuilds(), 2);
  check_ghosts(P, dom);
  expect_same_pairs<D>(pairs_from_list(P, nh.list(), dom, support), pairs_brute_force(P, dom, support));
}

TEST(NeighbourSkin, NoRebuildAndStaleListsStayExact) {
  check_skin<2>(test_domain<2>({true, true}), 900, 31u);
  check_skin<2>(test_domain<2>({false, true}), 600, 32u);
  check_skin<3>(test_domain<3>({true, true, true}), 900, 33u);
  check_skin<3>(test_domain<3>({true, false, true}), 700, 34u);
}

}  // namespace
