// The pressure force from a body's surface (src/sph/surface_force.hpp) on disordered fluid particles:
// exact zero for a uniform pressure (a closed surface's area normals sum to zero), exactly the weight
// of the enclosed water for a hydrostatic (linear) pressure, in 2D and 3D; a thin plate's two faces
// each fitted from their own side, and no pressure on faces above a free surface; and the surfaces YAML
// scenes give their bodies (cases/scene/body_surface.cpp) are closed with their normals pointing out;
// the wall particles' viscous forces spread onto the faces (src/sph/surface_shear.hpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "cases/scene/body_surface.hpp"
#include "cases/scene/shapes.hpp"
#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"
#include "src/sph/surface_force.hpp"
#include "src/sph/surface_shear.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

// Fluid particles on a lattice of spacing dx filling [0, 1]^D less the points within `hole` of the
// centre, each moved by up to 20 % of dx, with pressure p(x).
template <int D, class Field> sph::Particles<D> fluid_around(double dx, double hole, Field p) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  sph::Particles<D> P;
  const int n = static_cast<int>(std::lround(1.0 / dx));
  const sph::Vector<D> centre = sph::Vector<D>::Constant(0.5);
  int idx[3] = {0, 0, 0};
  for (;;) {
    sph::Vector<D> x;
    for (int a = 0; a < D; ++a) x[a] = (idx[a] + 0.5) * dx;
    if ((x - centre).norm() > hole) {
      for (int a = 0; a < D; ++a) x[a] += dx * jitter(gen);
      P.add(x, sph::Vector<D>::Zero(), std::pow(dx, D), 1.0, p(x), sph::kFluid);
    }
    int a = 0;
    while (a < D && idx[a] == n - 1) idx[a++] = 0;
    if (a == D) break;
    ++idx[a];
  }
  return P;
}

struct Faces2 {
  std::vector<sph::Vector<2>> centre, area_normal;
  double area = 0.0;  // enclosed
};

// A regular polygon of m sides inscribed in the circle of radius R about (0.5, 0.5), normals outwards.
Faces2 polygon(int m, double R) {
  Faces2 f;
  const sph::Vector<2> c(0.5, 0.5);
  for (int k = 0; k < m; ++k) {
    const double a0 = 2 * kPi * k / m, a1 = 2 * kPi * (k + 1) / m;
    const sph::Vector<2> p0 = c + R * sph::Vector<2>(std::cos(a0), std::sin(a0)),
                         p1 = c + R * sph::Vector<2>(std::cos(a1), std::sin(a1)), d = p1 - p0;
    f.centre.push_back(0.5 * (p0 + p1)), f.area_normal.emplace_back(d[1], -d[0]);
  }
  f.area = 0.5 * m * R * R * std::sin(2 * kPi / m);
  return f;
}

TEST(SurfaceForce, UniformPressureGivesNoForceOnDisorderedParticles) {
  const double dx = 1.0 / 40, p0 = 3.7;
  const sph::Particles<2> P = fluid_around<2>(dx, 0.2, [&](const sph::Vector<2>&) { return p0; });
  const sph::Kernel<2> K(sph::KernelType::WendlandC2, 1.5 * dx);
  const Faces2 f = polygon(100, 0.2);
  const auto S = sph::surface_pressure_force(P, K, f.centre, f.area_normal, P.p, sph::Vector<2>(0.5, 0.5));
  const double scale = p0 * 2 * kPi * 0.2;  // the pressure times the perimeter
  EXPECT_LT(S.force.norm(), 1e-13 * scale);
  EXPECT_LT(std::abs(S.moment[2]), 1e-13 * scale);
}

TEST(SurfaceForce, HydrostaticPressureGivesTheEnclosedWatersWeight) {
  const double dx = 1.0 / 40, rho_g = 1.3;
  const auto p = [&](const sph::Vector<2>& x) { return 2.0 + rho_g * (1.0 - x[1]); };
  const sph::Particles<2> P = fluid_around<2>(dx, 0.2, p);
  const sph::Kernel<2> K(sph::KernelType::WendlandC2, 1.5 * dx);
  const Faces2 f = polygon(100, 0.2);
  const auto S = sph::surface_pressure_force(P, K, f.centre, f.area_normal, P.p, sph::Vector<2>(0.5, 0.5));
  EXPECT_NEAR(S.force[1] / (rho_g * f.area), 1.0, 1e-12);
  EXPECT_NEAR(S.force[0], 0.0, 1e-12 * rho_g * f.area);
}

// A cube of side 2a about (0.5, 0.5, 0.5), two triangles a face, normals outwards.
TEST(SurfaceForce, HydrostaticPressureOnATriangulatedCubeIn3D) {
  const double dx = 1.0 / 20, a = 0.15, rho_g = 0.8;
  const auto p = [&](const sph::Vector<3>& x) { return 1.0 + rho_g * (1.0 - x[2]); };
  sph::Particles<3> P = fluid_around<3>(dx, 0.0, p);
  // Keep the fluid outside the cube (fluid_around leaves a ball out; here the cube).
  sph::Particles<3> outside;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (((P.x[i].array() - 0.5).abs() > a).any()) outside.add(P.x[i], P.v[i], P.m[i], P.rho[i], P.p[i], sph::kFluid);
  const sph::Kernel<3> K(sph::KernelType::WendlandC2, 1.5 * dx);
  std::vector<sph::Vector<3>> centre, area_normal;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      sph::Vector<3> corner[4];
      for (int k = 0; k < 4; ++k) {
        corner[k] = sph::Vector<3>::Constant(0.5);
        corner[k][axis] += side * a;
        corner[k][u] += (k == 1 || k == 2 ? a : -a), corner[k][v] += (k >= 2 ? a : -a);
      }
      for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
        const sph::Vector<3> c = (corner[tri[0]] + corner[tri[1]] + corner[tri[2]]) / 3.0;
        sph::Vector<3> n = 0.5 * (corner[tri[1]] - corner[tri[0]]).cross(corner[tri[2]] - corner[tri[0]]);
        if (n[axis] * side < 0) n = -n;
        centre.push_back(c), area_normal.push_back(n);
      }
    }
  const auto S = sph::surface_pressure_force(outside, K, centre, area_normal, outside.p,
                                             sph::Vector<3>(sph::Vector<3>::Constant(0.5)));
  const double volume = 8 * a * a * a;
  EXPECT_NEAR(S.force[2] / (rho_g * volume), 1.0, 1e-11);
  EXPECT_LT(std::hypot(S.force[0], S.force[1]), 1e-11 * rho_g * volume);
}

// A zero-thickness plate at x = 0.5 across the whole fluid, a different linear pressure on each side
// (fluid_around's lattice leaves dx/2 either side of it): its two faces lie on one line, and each must
// be fitted from its own side's fluid only, so the force is the integral of p_left - p_right exactly.
struct PlateFaces {
  std::vector<sph::Vector<2>> centre, area_normal;
};
PlateFaces plate_faces(double x0, double y0, double y1, int pieces) {
  PlateFaces f;
  const double a = (y1 - y0) / pieces;
  for (int k = 0; k < pieces; ++k) {
    const double y = y0 + (k + 0.5) * a;
    f.centre.emplace_back(x0, y), f.area_normal.emplace_back(-a, 0.0);  // the left face, looking left
    f.centre.emplace_back(x0, y), f.area_normal.emplace_back(a, 0.0);   // the right face
  }
  return f;
}

TEST(SurfaceForce, PlateFacesTakeTheirOwnSidesPressure) {
  const double dx = 1.0 / 40;
  const auto p = [](const sph::Vector<2>& x) {
    return x[0] < 0.5 ? 5.0 + 2.0 * (1.0 - x[1]) : 1.0 + 3.0 * (1.0 - x[1]);
  };
  const sph::Particles<2> P = fluid_around<2>(dx, 0.0, p);
  const sph::Kernel<2> K(sph::KernelType::WendlandC2, 1.5 * dx);
  const sph::Screens<2> screens({{sph::Vector<2>(0.5, -0.2), sph::Vector<2>(0.5, 1.2)}}, {});
  const PlateFaces f = plate_faces(0.5, 0.0, 1.0, 160);
  const sph::Vector<2> about(0.5, 0.0);
  const auto S = sph::surface_pressure_force(P, K, f.centre, f.area_normal, P.p, about, &screens);
  // The integral over y in [0, 1] of (5 + 2 (1 - y)) - (1 + 3 (1 - y)) = 3 + y (exact face by face for
  // a linear integrand), and its moment about (0.5, 0), -y (3 + y) in the z direction, summed at the
  // faces' centres as the force is applied there.
  EXPECT_NEAR(S.force[0], 3.5, 1e-11);
  EXPECT_NEAR(S.force[1], 0.0, 1e-11);
  double moment = 0.0;
  for (std::size_t q = 0; q < f.centre.size(); q += 2) moment -= f.centre[q][1] * (3.0 + f.centre[q][1]) / 160;
  EXPECT_NEAR(S.moment[2], moment, 1e-11);
  EXPECT_NEAR(moment, -(1.5 + 1.0 / 3.0), 1e-5);  // the integral, to the midpoint rule's error
  // Without the screens each fit mixes the two sides' fluid.
  const auto mixed = sph::surface_pressure_force(P, K, f.centre, f.area_normal, P.p, about);
  EXPECT_GT(std::abs(mixed.force[0] - 3.5), 0.5);
}

// With a free surface, the plate's faces above the water carry no pressure: still water 0.6 deep on
// the left and 0.3 on the right of a plate 1 tall, each hydrostatic (p = 0 at the level, dx/2 above
// the top particles): the force is rho g (0.6^2 - 0.3^2) / 2, however far the fits reach into the air.
TEST(SurfaceForce, DryFacesAboveAFreeSurfaceCarryNoPressure) {
  const double dx = 1.0 / 40, rho_g = 9810.0;
  sph::Particles<2> P;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const sph::Vector<2> x((i + 0.5) * dx, (j + 0.5) * dx);
      const double level = x[0] < 0.5 ? 0.6 : 0.3;
      if (x[1] < level) P.add(x, sph::Vector<2>::Zero(), dx * dx, 1000.0, rho_g * (level - x[1]), sph::kFluid);
    }
  const sph::Kernel<2> K(sph::KernelType::WendlandC2, 1.5 * dx);
  const sph::Screens<2> screens({{sph::Vector<2>(0.5, -0.2), sph::Vector<2>(0.5, 1.2)}}, {});
  const PlateFaces f = plate_faces(0.5, 0.0, 1.0, 160);
  const auto S =
      sph::surface_pressure_force(P, K, f.centre, f.area_normal, P.p, sph::Vector<2>(0.5, 0.0), &screens, true);
  EXPECT_NEAR(S.force[0] / (rho_g * (0.36 - 0.09) / 2), 1.0, 1e-12);
}

// The wall particles' viscous forces spread onto a body's faces (src/sph/surface_shear.hpp): the faces'
// forces sum to the particles' exactly, each force stays on the faces that look at its fluid (a thin
// plate's two faces), and the rotation's part exerts no force and the torque -2 mu V w.
TEST(SurfaceShear, SpreadForcesSumToTheParticlesForces) {
  const double dx = 1.0 / 40;
  const sph::Kernel<2> K(sph::KernelType::WendlandC2, 1.5 * dx);
  const Faces2 f = polygon(100, 0.2);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<sph::WallParticleShear<2>> forces;
  sph::Vector<2> total = sph::Vector<2>::Zero();
  for (int k = 0; k < 300; ++k) {
    const double angle = kPi * (u(gen) + 1.0), r = 0.2 + 0.5 * dx * u(gen);
    const sph::Vector<2> radial(std::cos(angle), std::sin(angle));
    forces.push_back({0, sph::Vector<2>(u(gen), u(gen)), sph::Vector<2>(0.5, 0.5) + r * radial, radial});
    total += forces.back().force;
  }
  forces.push_back({0, sph::Vector<2>(2.0, -1.0), sph::Vector<2>(3.0, 3.0), sph::Vector<2>(1.0, 1.0)});  // far off
  total += forces.back().force;
  const auto shear = sph::spread_shear(forces, K, f.centre, f.area_normal);
  sph::Vector<2> sum = sph::Vector<2>::Zero();
  for (std::size_t q = 0; q < shear.size(); ++q) sum += shear[q] * f.area_normal[q].norm();
  EXPECT_LT((sum - total).norm(), 1e-12 * total.norm());
}

TEST(SurfaceShear, APlatesFacesTakeTheirOwnSidesForces) {
  const double dx = 1.0 / 40;
  const sph::Kernel<2> K(sph::KernelType::WendlandC2, 1.5 * dx);
  const PlateFaces f = plate_faces(0.5, 0.0, 1.0, 160);
  std::vector<sph::WallParticleShear<2>> forces;
  for (int k = 0; k < 40; ++k) {
    const double y = (k + 0.5) * dx;
    // Face +1's layer lies right of the plate and is pulled by the left fluid along +y; face -1's
    // lies left and is pulled along -y twice as hard.
    forces.push_back({0, sph::Vector<2>(0.0, 1.0), sph::Vector<2>(0.5 + 0.5 * dx, y), sph::Vector<2>(-1.0, 0.0)});
    forces.push_back({0, sph::Vector<2>(0.0, -2.0), sph::Vector<2>(0.5 - 0.5 * dx, y), sph::Vector<2>(1.0, 0.0)});
  }
  const auto shear = sph::spread_shear(forces, K, f.centre, f.area_normal);
  double left = 0.0, right = 0.0;
  for (std::size_t q = 0; q < shear.size(); ++q)
    (f.area_normal[q][0] < 0.0 ? left : right) += shear[q][1] * f.area_normal[q].norm();
  EXPECT_NEAR(left, 40.0, 1e-11);
  EXPECT_NEAR(right, -80.0, 1e-11);
}

TEST(SurfaceShear, TheRotationsPartHasNoForceAndItsTorque) {
  const double mu = 0.3, w = 1.7;
  const Faces2 f = polygon(200, 0.2);
  std::vector<sph::Vector<2>> shear(f.centre.size(), sph::Vector<2>::Zero());
  sph::add_rotation_shear(shear, f.area_normal, Eigen::Vector3d(0.0, 0.0, w), mu);
  sph::Vector<2> force = sph::Vector<2>::Zero();
  double torque = 0.0;
  for (std::size_t q = 0; q < shear.size(); ++q) {
    const double a = f.area_normal[q].norm();
    const sph::Vector<2> r = f.centre[q] - sph::Vector<2>(0.5, 0.5);
    force += a * shear[q], torque += a * (r[0] * shear[q][1] - r[1] * shear[q][0]);
  }
  EXPECT_LT(force.norm(), 1e-14);
  // -2 mu V w with V the polygon's area: each face's arm is the apothem, its length sums to the perimeter.
  EXPECT_NEAR(torque, -2.0 * mu * f.area * w, 1e-12);
}

// The surface a YAML scene gives a circular body: closed, each face's normal pointing away from the
// centre, its enclosed area that of the circle to the contour's resolution.
TEST(SurfaceForce, SceneBodySurfacesAreClosedAndPointOutwards) {
  const sph::Point3 c(0.5, 0.5, 0.0);
  const sph::ShapePtr ball = sph::make_ball(c, 0.2);
  const sph::SurfaceMesh mesh =
      sph::body_surface({ball.get()}, 2, sph::Point3(0.2, 0.2, 0.0), sph::Point3(0.8, 0.8, 0.0), 0.01);
  EXPECT_TRUE(mesh.closed);
  double area = 0.0;  // (1/2) sum x . n over the faces: the enclosed area (divergence theorem)
  for (const auto& cell : mesh.cells) {
    const Eigen::Vector3d x = sph::face_centre(mesh, cell), n = sph::face_area_normal(mesh, cell);
    if (n.norm() > 0.0) {  // the contour may repeat a point: a face of no area
      EXPECT_GT((x - c).dot(n), 0.0);
    }
    area += 0.5 * (x - c).dot(n);
  }
  EXPECT_NEAR(area / (kPi * 0.04), 1.0, 1e-3);
}

}  // namespace
