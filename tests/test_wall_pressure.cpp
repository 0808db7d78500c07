// The walls' pressure extrapolated from the fluid with -wall_pressure continued
// (AdamiWall::extrapolate_pressure, the relation ISPH's wall rows hold too) in a tank's corner: a
// floor four layers deep and a side wall cut to three, whose middle layer has no face normal of its
// own. Still water's hydrostatic field is continued into every wall particle exactly, near its free
// surface too; a lone particle on the side wall gives every wall particle its own pressure, where
// Adami's relation as published (the default) adds a column of water along the wall that is not there
// (docs/verification/free_surface.md, "Walls that continue the fluid's own pressure").
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "src/boundary/adami_wall.hpp"
#include "src/boundary/adami_wall_model.hpp"
#include "src/core/domain.hpp"
#include "src/kernels/kernel.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/particles/particles.hpp"

namespace {

using namespace sph;
using V2 = Vector<2>;

constexpr double kDx = 1.0 / 40, kRho = 1000.0, kG = 9.81;
constexpr int kFloorLayers = 4, kSideLayers = 3, kColumns = 24, kRows = 16;
const V2 kGravity(0.0, -kG);

V2 site(int i, int j) { return V2((i + 0.5) * kDx, (j + 0.5) * kDx); }

struct Corner {
  Domain<2> domain;
  Kernel<2> K;
  Particles<2> P;
  std::unique_ptr<Neighbourhood<2>> nh;

  // Walls: the floor (j < 0) and the side wall (i < 0) up to kRows + 6; fluid where `fluid(i, j)`.
  template <class Fluid> Corner(KernelType kernel, double h_over_dx, Fluid&& fluid) : K(kernel, h_over_dx * kDx) {
    domain.lo = V2(-1.0, -1.0), domain.hi = V2(2.0, 2.0);
    for (int j = -kFloorLayers; j < kRows + 6; ++j)
      for (int i = -kSideLayers; i < kColumns; ++i) {
        const bool wall = i < 0 || j < 0;
        if (!wall && !fluid(i, j)) continue;
        P.add(site(i, j), V2::Zero(), kDx * kDx * kRho, kRho, 0.0, wall ? kWall : kFluid);
        P.gid.back() = P.id.back() = static_cast<long>(P.n_owned) - 1;
      }
    P.n_global = static_cast<long>(P.n_owned);
    nh = std::make_unique<Neighbourhood<2>>(domain, K.support_radius(), 0.0);
    nh->update(P, true);
  }
  // Wall particles that see fluid.
  std::vector<std::size_t> wetted_walls() const {
    const auto s = AdamiWall<2>::stencil(P, nh->list(), K);
    std::vector<std::size_t> out;
    for (std::size_t w = 0; w < P.n_owned; ++w)
      if (P.kind[w] == kWall && s.offset[w + 1] > s.offset[w]) out.push_back(w);
    return out;
  }
};

class WallPressure : public ::testing::TestWithParam<std::pair<KernelType, double>> {};

// Water kRows deep at rest: p = rho g (H - y) in the fluid, and the same field in every wall particle
// that sees fluid, beside the free surface and in the corner included.
TEST_P(WallPressure, ContinuesStillWatersHydrostaticFieldIntoTheWalls) {
  Corner c(GetParam().first, GetParam().second, [](int, int j) { return j < kRows; });
  const double H = kRows * kDx;
  for (std::size_t i = 0; i < c.P.n_owned; ++i)
    if (c.P.kind[i] == kFluid) c.P.p[i] = kRho * kG * (H - c.P.x[i].y());
  AdamiWall<2>::extrapolate_pressure(c.P, *c.nh, c.K, kGravity, nullptr, sph::WallPressure::Continued);
  const std::vector<std::size_t> walls = c.wetted_walls();
  ASSERT_GT(walls.size(), 50u);
  double worst = 0.0;
  for (std::size_t w : walls) {
    const double e = std::abs(c.P.p[w] - kRho * kG * (H - c.P.x[w].y()));
    worst = std::max(worst, e);
  }
  // Against rho g dx = 245 Pa: the fit's damping of the slope where the fluid's spread along the wall is
  // small is all that is left.
  EXPECT_LT(worst, 1e-3 * kRho * kG * kDx) << "largest error " << worst;
}

// One fluid particle on the side wall at half the depth, its pressure 7 Pa: every wall particle that
// sees it takes 7 Pa, the side wall's cut middle layer too; Adami's relation as published gives them
// 7 + rho g (y_f - y_w), a hydrostatic column along the wall.
TEST_P(WallPressure, GivesALoneParticlesPressureToTheWallsAroundIt) {
  Corner c(GetParam().first, GetParam().second, [](int i, int j) { return i == 0 && j == kRows / 2; });
  std::size_t f = 0;
  for (std::size_t i = 0; i < c.P.n_owned; ++i)
    if (c.P.kind[i] == kFluid) f = i, c.P.p[i] = 7.0;
  AdamiWall<2>::extrapolate_pressure(c.P, *c.nh, c.K, kGravity, nullptr, sph::WallPressure::Continued);
  const std::vector<std::size_t> walls = c.wetted_walls();
  ASSERT_GE(walls.size(), 8u);
  int off_level = 0;  // walls above or below the particle, where the published relation adds a head
  for (std::size_t w : walls) {
    EXPECT_NEAR(c.P.p[w], 7.0, 1e-9) << "wall at " << c.P.x[w].transpose();
    off_level += std::abs(c.P.x[w].y() - c.P.x[f].y()) > 0.5 * kDx;
  }
  EXPECT_GT(off_level, 4);
  AdamiWall<2>::extrapolate_pressure(c.P, *c.nh, c.K, kGravity);  // -wall_pressure adami, the default
  for (std::size_t w : walls)
    EXPECT_NEAR(c.P.p[w], 7.0 + kRho * kG * (c.P.x[f].y() - c.P.x[w].y()), 1e-9) << "wall at " << c.P.x[w].transpose();
}

// Each wall group continues the pressure in the form it chose (a scene's wall_pressure:), the others
// in the option's: through the wall model, the side wall below the lone particle chooses continued and
// takes its 7 Pa, the walls above keep Adami's column; and the other way round.
TEST_P(WallPressure, TakesEachWallGroupsOwnForm) {
  Corner c(GetParam().first, GetParam().second, [](int i, int j) { return i == 0 && j == kRows / 2; });
  std::size_t f = 0;
  for (std::size_t i = 0; i < c.P.n_owned; ++i)
    if (c.P.kind[i] == kFluid) f = i, c.P.p[i] = 7.0;
  auto below = [&](std::size_t w) { return c.P.x[w].y() < c.P.x[f].y(); };
  const std::vector<std::size_t> walls = c.wetted_walls();
  for (const sph::WallPressure form : {sph::WallPressure::Adami, sph::WallPressure::Continued}) {
    const auto other = form == sph::WallPressure::Adami ? sph::WallPressure::Continued : sph::WallPressure::Adami;
    std::vector<signed char> chosen(c.P.n_owned, -1);
    for (std::size_t w = 0; w < c.P.n_owned; ++w)
      if (c.P.kind[w] == kWall && below(w)) chosen[w] = static_cast<signed char>(other);
    const MovingBodies<2> groups({}, {}, 0.0, {}, {}, chosen);
    make_wall_model<2>(form, groups)->extrapolate_pressure(c.P, *c.nh, c.K, kGravity);
    int each[2] = {0, 0};
    for (std::size_t w : walls) {
      const bool continued = (below(w) ? other : form) == sph::WallPressure::Continued;
      const double column = continued ? 0.0 : kRho * kG * (c.P.x[f].y() - c.P.x[w].y());
      EXPECT_NEAR(c.P.p[w], 7.0 + column, 1e-9) << "wall at " << c.P.x[w].transpose();
      ++each[continued];
    }
    EXPECT_GE(std::min(each[0], each[1]), 3) << "walls in each form";
  }
}

// A tank accelerating at a_w: the normal head is (g - a_w) . n, the head along the wall the fluid's
// own (here hydrostatic in g - a_w, as in a tank accelerated for a long time).
TEST_P(WallPressure, TakesTheWallsAccelerationAcrossTheWall) {
  Corner c(GetParam().first, GetParam().second, [](int, int j) { return j < kRows; });
  const V2 a_w(-2.0, 1.5), effective = kGravity - a_w;
  const V2 origin(0.0, kRows * kDx);
  for (std::size_t i = 0; i < c.P.n_owned; ++i)
    if (c.P.kind[i] == kFluid) c.P.p[i] = kRho * effective.dot(c.P.x[i] - origin);
  const std::vector<V2> acceleration(c.P.n_owned, a_w);
  AdamiWall<2>::extrapolate_pressure(c.P, *c.nh, c.K, kGravity, &acceleration, sph::WallPressure::Continued);
  double worst = 0.0;
  for (std::size_t w : c.wetted_walls())
    worst = std::max(worst, std::abs(c.P.p[w] - kRho * effective.dot(c.P.x[w] - origin)));
  EXPECT_LT(worst, 1e-3 * kRho * effective.norm() * kDx) << "largest error " << worst;
}

INSTANTIATE_TEST_SUITE_P(Kernels, WallPressure,
                         ::testing::Values(std::make_pair(KernelType::WendlandC2, 1.5),
                                           std::make_pair(KernelType::QuinticSpline, 0.93)));

}  // namespace
