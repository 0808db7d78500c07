// -box_exit auto (src/run/box_exit.hpp) tells fluid thrown over an open side from fluid that went
// through a wall, from where each crossed the box's side: a tank's left wall, 4 layers of a square
// lattice cut by the box at x = -4 dx (as a scene's box cuts its walls), its top face at y = 8 dx, the box
// open above it.
#include <gtest/gtest.h>

#include "src/core/domain.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/particles/particles.hpp"
#include "src/run/box_exit.hpp"

namespace {

using namespace sph;
using V2 = Vector<2>;

constexpr double kDx = 0.05;

struct CutWall {
  Domain<2> domain;
  Particles<2> P;

  CutWall() {
    domain.lo = V2(-4 * kDx, 0.0), domain.hi = V2(1.0, 1.0);
    for (int j = 0; j < 8; ++j)
      for (int i = -4; i < 0; ++i) add(V2((i + 0.5) * kDx, (j + 0.5) * kDx), kWall);
  }
  std::size_t add(const V2& x, int kind) {
    P.add(x, V2::Zero(), kDx * kDx, 1.0, 0.0, kind);
    P.gid.back() = static_cast<long>(P.n_owned) - 1;
    P.n_global = static_cast<long>(P.n_owned);
    return P.n_owned - 1;
  }
  bool through_wall(std::size_t i) {
    Neighbourhood<2> nh(domain, 3 * kDx, 0.0);
    nh.update(P, true);
    return left_through_wall(P, nh.list(), domain, i, kDx);
  }
};

TEST(BoxExit, FluidThatCrossedTheBoxSideInsideAWallWentThroughIt) {
  for (double y : {0.5, 3.0, 7.4}) {  // beside the layers' particles and between them
    CutWall w;
    const std::size_t i = w.add(V2(-4.2 * kDx, y * kDx), kFluid);
    EXPECT_TRUE(w.domain.outside(w.P.x[i]));
    EXPECT_TRUE(w.through_wall(i)) << y;
  }
}

TEST(BoxExit, FluidThrownOverTheWallsTopLeftThroughAnOpenSide) {
  // Sliding over the top face (the fluid's gap to the top layer is a spacing), and flying above it.
  for (double y : {8.5, 9.0, 12.0}) {
    CutWall w;
    const std::size_t i = w.add(V2(-4.2 * kDx, y * kDx), kFluid);
    EXPECT_TRUE(w.domain.outside(w.P.x[i]));
    EXPECT_FALSE(w.through_wall(i)) << y;
  }
  // Up the wall's face to the box's top (a box whose top cuts the wall at 8 dx): beside the face, over an
  // open side; a little inside it, through the wall.
  for (const double x : {0.04, -0.04}) {
    CutWall w;
    w.domain.hi[1] = 8 * kDx;
    const std::size_t i = w.add(V2(x * kDx, 8.3 * kDx), kFluid);
    EXPECT_TRUE(w.domain.outside(w.P.x[i]));
    EXPECT_EQ(w.through_wall(i), x < 0) << x;
  }
  // Out through the box's floor, away from any wall.
  CutWall w;
  const std::size_t i = w.add(V2(0.5, -0.3 * kDx), kFluid);
  EXPECT_FALSE(w.through_wall(i));
}

TEST(BoxExit, AutoRemovesOnlyWhatLeftThroughAnOpenSide) {
  CutWall w;
  const std::size_t inside = w.add(V2(0.5, 0.5), kFluid);
  w.add(V2(-4.2 * kDx, 3.0 * kDx), kFluid);   // through the wall
  w.add(V2(-4.2 * kDx, 12.0 * kDx), kFluid);  // over its top
  const double mass = w.P.m[inside];
  Neighbourhood<2> nh(w.domain, 3 * kDx, 0.0);
  nh.update(w.P, true);
  const RemovedFluid gone = remove_fluid_outside(w.P, nh.list(), w.domain, kDx, false);
  EXPECT_EQ(gone.count, 1);
  EXPECT_DOUBLE_EQ(gone.mass, mass);
  EXPECT_TRUE(fluid_outside(w.P, w.domain));  // the one through the wall stays, for the health check
}

}  // namespace
