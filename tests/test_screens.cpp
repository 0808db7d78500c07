// Thin plates in the neighbour lists (src/neighbours/screens.hpp) against the rule computed by hand:
// visibility is symmetric, a face's layers are seen from its own side only, particles alongside the plate on opposite
// sides never see each other, and beyond the plate's ends both sides meet; a plate moved keeps its rule where it is
// now; through Neighbourhood, in a periodic box that the plate crosses, the lists are brute force less exactly those
// pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "src/core/domain.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/neighbours/screens.hpp"
#include "src/particles/global_indices.hpp"
#include "src/particles/particles.hpp"

namespace {

using namespace sph;
using V = Vector<2>;

// A vertical plate from (0.5, 0.2) to (0.5, 1): its normal (-1, 0), so face +1 looks to x < 0.5.
// Particles 0-3 are plain; 4 is a layer of face +1 (it lies at x > 0.5, behind the face), 5 of face -1.
Screens<2> vertical_plate() { return Screens<2>({{V(0.5, 0.2), V(0.5, 1.0)}}, {0, 0, 0, 0, 1, -1}); }

TEST(Screens, LayersAreSeenFromTheirOwnSideOnly) {
  const Screens<2> s = vertical_plate();
  const V left(0.45, 0.5), right(0.55, 0.5), layer_plus(0.525, 0.5), layer_minus(0.475, 0.5);
  EXPECT_TRUE(s.see(left, 0, layer_plus, 4));    // face +1 stands for the solid to the left fluid's right
  EXPECT_FALSE(s.see(right, 1, layer_plus, 4));  // though it lies among the right fluid
  EXPECT_TRUE(s.see(right, 1, layer_minus, 5));
  EXPECT_FALSE(s.see(left, 0, layer_minus, 5));
  EXPECT_FALSE(s.see(layer_plus, 4, layer_minus, 5));  // the two faces' layers
  // Below the lower end, a layer is still seen from its own side only.
  EXPECT_TRUE(s.see(V(0.45, 0.15), 2, layer_plus, 4));
  EXPECT_FALSE(s.see(V(0.55, 0.15), 3, layer_plus, 4));
}

TEST(Screens, OppositeSidesMeetOnlyBeyondTheEnds) {
  const Screens<2> s = vertical_plate();
  EXPECT_FALSE(s.see(V(0.45, 0.5), 0, V(0.55, 0.5), 1));    // both alongside
  EXPECT_FALSE(s.see(V(0.49, 0.21), 0, V(0.51, 0.21), 1));  // just above the end
  EXPECT_TRUE(s.see(V(0.49, 0.19), 0, V(0.51, 0.19), 1));   // just below it
  EXPECT_TRUE(s.see(V(0.49, 0.21), 0, V(0.51, 0.19), 1));   // one of them beyond
  EXPECT_TRUE(s.see(V(0.4, 0.5), 0, V(0.45, 0.6), 1));      // the same side
}

// A body's motion moves its plate (MovingBodies::move_to): the rule follows the plate where it is.
TEST(Screens, AMovedPlateScreensWhereItIs) {
  Screens<2> s = vertical_plate();
  EXPECT_FALSE(s.see(V(0.45, 0.5), 0, V(0.55, 0.5), 1));
  s.move(0, V(0.7, 0.2), V(0.7, 1.0));  // moved 0.2 to the right
  EXPECT_TRUE(s.see(V(0.45, 0.5), 0, V(0.55, 0.5), 1));
  EXPECT_FALSE(s.see(V(0.65, 0.5), 0, V(0.75, 0.5), 1));
  EXPECT_TRUE(s.see(V(0.65, 0.5), 0, V(0.725, 0.5), 4));  // face +1's layer, now behind the moved face
  EXPECT_TRUE(s.start()[0].a.isApprox(V(0.5, 0.2)));      // where the scene laid it
  s.move(0, V(0.7, 0.2), V(0.7 + 0.8 * std::sin(0.1), 0.2 + 0.8 * std::cos(0.1)));  // and turned
  EXPECT_NEAR(s.normal(0).dot(V(std::sin(0.1), std::cos(0.1))), 0.0, 1e-15);
}

TEST(Screens, VisibilityIsSymmetric) {
  const Screens<2> s = vertical_plate();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.3, 0.7), v(0.0, 1.1);
  std::uniform_int_distribution<int> label(0, 5);
  for (int k = 0; k < 20000; ++k) {
    const V a(u(rng), v(rng)), b(u(rng), v(rng));
    const int ia = label(rng), ib = label(rng);
    ASSERT_EQ(s.see(a, ia, b, ib), s.see(b, ib, a, ia)) << a.transpose() << " / " << b.transpose();
  }
}

// A periodic strip 1 x 1 cut along y = 0.5 by a plate that runs past the box (so that it parts the
// images too): the lists are the brute-force pairs less those with one particle on each side.
TEST(Screens, NeighbourListsDropThePairsThePlateParts) {
  Domain<2> dom;
  dom.lo = V(0.0, 0.0), dom.hi = V(1.0, 1.0), dom.periodic = {true, false};
  Particles<2> P;
  const int n = 20;
  const double dx = 1.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) P.add(V((i + 0.5) * dx, (j + 0.5) * dx), V::Zero(), dx * dx, 1.0);
  assign_global_indices(P);
  dom.screens = std::make_shared<Screens<2>>(std::vector<Screens<2>::Plate>{{V(-0.3, 0.5), V(1.3, 0.5)}},
                                             std::vector<std::int8_t>{});
  const double radius = 2.9 * dx;  // no lattice distance at the radius itself
  Neighbourhood<2> nh(dom, radius, 0.0);
  nh.update(P, true);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    std::set<GlobalIndex> listed;
    for (const int* j = nh.list().begin(i); j != nh.list().end(i); ++j) {
      EXPECT_EQ(P.x[i][1] < 0.5, P.x[*j][1] < 0.5) << "a pair across the plate";
      listed.insert(P.id[*j]);
    }
    // Brute force over the periodic images, same side only.
    std::set<GlobalIndex> expected;
    for (std::size_t k = 0; k < P.n_owned; ++k) {
      if (k == i || (P.x[i][1] < 0.5) != (P.x[k][1] < 0.5)) continue;
      for (double shift : {-1.0, 0.0, 1.0})
        if ((P.x[i] - P.x[k] - V(shift, 0.0)).norm() < radius) expected.insert(P.id[k]);
    }
    EXPECT_EQ(listed, expected) << "particle " << i;
    pairs += listed.size();
  }
  EXPECT_GT(pairs, 0u);
}

}  // namespace
