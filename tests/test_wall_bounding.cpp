// The wall bounding (src/boundary/wall_bounding.hpp) against the geometry of a tank's corner with a
// step on its floor: square wall lattices whose faces lie dx/2 beyond their outer particles, so where a
// fluid particle is behind a face, and where that face is, are known. Fluid at rest on its lattice is
// left alone (concave and convex corners included); particles behind a face, one where the fluid that
// seeped through a wall sat (the centre of a wall cell), are put back on the face with their velocity
// into the wall removed; for the default kernel and for the quintic spline whose flat kernel sum let the
// fluid through.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "src/boundary/wall_bounding.hpp"
#include "src/core/domain.hpp"
#include "src/kernels/kernel.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/particles/particles.hpp"

namespace {

using namespace sph;
using V2 = Vector<2>;

constexpr int kLayers = 4, kFluidRows = 12, kFluidColumns = 28, kStepFrom = 12, kStepColumns = 9, kStepRows = 3;
constexpr double kDx = 1.0 / 40;

// Lattice point (i + 1/2, j + 1/2) dx: the floor's face is y = 0, the left wall's x = 0. A step of
// kStepColumns x kStepRows wall particles stands on the floor from x = 12 dx: its top face is y = 3 dx,
// its left face x = 12 dx, and they meet at a convex corner. The cases below lie where the walls'
// normals are exact by symmetry (more than a support from other walls), except the convex corner's.
V2 site(double i, double j) { return V2((i + 0.5) * kDx, (j + 0.5) * kDx); }
bool in_step(int i, int j) { return i >= kStepFrom && i < kStepFrom + kStepColumns && j >= 0 && j < kStepRows; }

struct CornerWithStep {
  Domain<2> domain;
  Kernel<2> K;
  Particles<2> P;
  std::unique_ptr<Neighbourhood<2>> nh;

  explicit CornerWithStep(KernelType kernel, double h_over_dx) : K(kernel, h_over_dx * kDx) {
    domain.lo = V2(-1.0, -1.0), domain.hi = V2(2.0, 2.0);
    for (int j = -kLayers; j < kFluidRows; ++j)
      for (int i = -kLayers; i < kFluidColumns; ++i) {
        const bool wall = i < 0 || j < 0 || in_step(i, j);
        P.add(site(i, j), V2::Zero(), kDx * kDx, 1.0, 0.0, wall ? kWall : kFluid);
        P.gid.back() = static_cast<long>(P.n_owned) - 1;
      }
    P.n_global = static_cast<long>(P.n_owned);
  }
  // Adds a fluid particle at x moving at v and returns its index.
  std::size_t add(const V2& x, const V2& v) {
    P.add(x, v, kDx * kDx, 1.0, 0.0, kFluid);
    P.gid.back() = static_cast<long>(P.n_owned) - 1;
    P.n_global = static_cast<long>(P.n_owned);
    return P.n_owned - 1;
  }
  long bound() {
    nh = std::make_unique<Neighbourhood<2>>(domain, K.support_radius(), 0.0);
    nh->update(P, true);
    return WallBounding<2>().apply(P, *nh, K, kDx, 1.0, false);
  }
};

class WallBounding : public ::testing::TestWithParam<std::pair<KernelType, double>> {};

TEST_P(WallBounding, LeavesFluidAtRestOnItsLatticeAlone) {
  CornerWithStep s(GetParam().first, GetParam().second);
  const std::vector<V2> before(s.P.x.begin(), s.P.x.end());
  EXPECT_EQ(s.bound(), 0);
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_EQ(s.P.x[i], before[i]) << i;
}

// Fluid pressed against a face, in front of it (0.1 dx, 0.02 dx beside the convex corner): not behind
// it, so not moved; beside the corner the corner particle's diagonal normal alone would put it behind.
TEST_P(WallBounding, LeavesFluidInFrontOfAFaceAlone) {
  CornerWithStep s(GetParam().first, GetParam().second);
  const std::vector<V2> in_front = {V2(12.4 * kDx, 3.02 * kDx), V2(11.9 * kDx, 2.5 * kDx), V2(6.5 * kDx, 0.1 * kDx),
                                    V2(0.1 * kDx, 6.5 * kDx)};
  std::vector<std::size_t> added;
  for (const V2& x : in_front) added.push_back(s.add(x, V2(-1, -1)));
  EXPECT_EQ(s.bound(), 0);
  for (std::size_t k = 0; k < added.size(); ++k) EXPECT_EQ(s.P.x[added[k]], in_front[k]) << in_front[k].transpose();
}

// Behind the floor's face by 0.3 dx, behind the left wall's by 0.2 dx, behind the step's top face, and
// at the centre of a cell one layer into the floor (where the seeping fluid sat): each goes back onto its
// face, the velocity into the wall removed and the velocity along it kept.
TEST_P(WallBounding, PutsFluidBehindAFaceBackOnIt) {
  CornerWithStep s(GetParam().first, GetParam().second);
  struct Case {
    V2 x, v, on_face, v_after;
  };
  const std::vector<Case> cases = {
      {V2(6.5 * kDx, -0.3 * kDx), V2(0.5, -1.0), V2(6.5 * kDx, 0.0), V2(0.5, 0.0)},
      {V2(-0.2 * kDx, 6.5 * kDx), V2(-1.0, 0.25), V2(0.0, 6.5 * kDx), V2(0.0, 0.25)},
      {V2(16.5 * kDx, 2.8 * kDx), V2(0.0, -2.0), V2(16.5 * kDx, 3.0 * kDx), V2(0.0, 0.0)},
      {V2(6.0 * kDx, -1.0 * kDx), V2(0.0, 0.0), V2(6.0 * kDx, 0.0), V2(0.0, 0.0)},
  };
  for (const Case& c : cases) {
    CornerWithStep t(GetParam().first, GetParam().second);
    const std::size_t i = t.add(c.x, c.v);
    EXPECT_EQ(t.bound(), 1) << c.x.transpose();
    EXPECT_NEAR((t.P.x[i] - c.on_face).norm(), 0.0, 1e-12) << c.x.transpose() << " -> " << t.P.x[i].transpose();
    EXPECT_NEAR((t.P.v[i] - c.v_after).norm(), 0.0, 1e-12) << c.x.transpose() << " -> " << t.P.v[i].transpose();
  }
}

// Inside the convex corner's cell, nearer than dx/2 to the corner particle, where the walls hold less
// than half of the kernel sum: moved out along the corner's normal to dx/2 from that particle.
TEST_P(WallBounding, PutsFluidOutOfAConvexCornersCell) {
  CornerWithStep s(GetParam().first, GetParam().second);
  const V2 corner = site(kStepFrom, kStepRows - 1);
  const std::size_t i = s.add(corner + V2(-0.3 * kDx, 0.3 * kDx), V2(1.0, -1.0));
  EXPECT_EQ(s.bound(), 1);
  EXPECT_NEAR((s.P.x[i] - corner).norm(), 0.5 * kDx, 0.05 * kDx);
  EXPECT_LT(s.P.v[i].norm(), 0.1);  // it moved straight at the corner: nearly all of it into the wall
}

INSTANTIATE_TEST_SUITE_P(Kernels, WallBounding,
                         ::testing::Values(std::make_pair(KernelType::WendlandC2, 1.5),
                                           std::make_pair(KernelType::QuinticSpline, 0.93)));

}  // namespace
