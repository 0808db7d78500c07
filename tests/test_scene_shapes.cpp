// YAML scenes (cases/scene/scene_yaml.hpp) and their shapes (cases/scene/shapes.hpp): signed distances
// against closed-form ones, lattice counts against whole numbers and areas, wall depth, the hydrostatic
// start, the refusals, and a mesh against the box it describes.
#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "cases/scene/scene_yaml.hpp"
#include "cases/scene/shapes.hpp"
#include "src/core/error.hpp"

namespace {

using sph::Point3;

const std::string& folder() {
  static const std::string dir = [] {
    const std::string d = std::string(SPH_BINARY_DIR) + "/test-output/scene_shapes";
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// Writes a YAML scene into the test folder; returns its path.
std::string scene(const std::string& name, const std::string& text) {
  const std::string path = folder() + "/" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

sph::YamlScene sample(const std::string& name, const std::string& text, double dx, int layers = 3) {
  return sph::read_yaml_scene(scene(name, text), dx, layers);
}

// The refusal's text ("" when the scene is accepted).
std::string refusal(const std::string& name, const std::string& text, double dx = 0.1) {
  try {
    sample(name, text, dx);
  } catch (const sph::Error& e) {
    return e.what();
  }
  return "";
}

long count(const sph::SceneFile& s, int kind) {
  long n = 0;
  for (int k : s.kind) n += k == kind;
  return n;
}

TEST(SceneShapes, BoxDistanceIsEuclidean) {
  const auto box = sph::make_box(Point3(0, 0, 0), Point3(2, 1, 0), 2);
  EXPECT_NEAR(box->distance(Point3(1, 0.5, 0)), -0.5, 1e-14);    // centre: half the short side
  EXPECT_NEAR(box->distance(Point3(1.9, 0.5, 0)), -0.1, 1e-14);  // near the right face
  EXPECT_NEAR(box->distance(Point3(3, 0.5, 0)), 1.0, 1e-14);     // beside a face
  EXPECT_NEAR(box->distance(Point3(5, 5, 0)), 5.0, 1e-14);       // beyond a corner: (3, 4, 5)
  const auto cube = sph::make_box(Point3(0, 0, 0), Point3(1, 1, 1), 3);
  EXPECT_NEAR(cube->distance(Point3(2, 2, 2)), std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(cube->distance(Point3(0.5, 0.5, 0.9)), -0.1, 1e-14);
}

TEST(SceneShapes, BallCylinderAndHalfSpaceDistances) {
  const auto circle = sph::make_ball(Point3(1, 2, 0), 0.5);
  EXPECT_NEAR(circle->distance(Point3(1, 2, 0)), -0.5, 1e-14);
  EXPECT_NEAR(circle->distance(Point3(4, 6, 0)), 4.5, 1e-14);
  const auto sphere = sph::make_ball(Point3(0, 0, 0), 1);
  EXPECT_NEAR(sphere->distance(Point3(1, 1, 1)), std::sqrt(3.0) - 1, 1e-14);
  // Capped cylinder along z from 0 to 2, radius 1.
  const auto cyl = sph::make_cylinder(Point3(0, 0, 0), Point3(0, 0, 2), 1);
  EXPECT_NEAR(cyl->distance(Point3(0, 0, 1)), -1.0, 1e-12);      // axis midpoint: to the side
  EXPECT_NEAR(cyl->distance(Point3(0.5, 0, 1.8)), -0.2, 1e-12);  // nearer the cap
  EXPECT_NEAR(cyl->distance(Point3(3, 0, 1)), 2.0, 1e-12);       // beside
  EXPECT_NEAR(cyl->distance(Point3(0, 0.5, 3)), 1.0, 1e-12);     // above the cap
  EXPECT_NEAR(cyl->distance(Point3(4, 0, 6)), 5.0, 1e-12);       // beyond the rim: (3, 4, 5)
  // A tilted cylinder: distance from its axis through the origin along (1, 1, 0).
  const auto tilted = sph::make_cylinder(Point3(-5, -5, 0), Point3(5, 5, 0), 0.5);
  EXPECT_NEAR(tilted->distance(Point3(1, -1, 0)), std::sqrt(2.0) - 0.5, 1e-12);
  // Solid below y = 1 (normal (0, 2): not a unit vector).
  const auto floor = sph::make_half_space(Point3(0, 1, 0), Point3(0, 2, 0));
  EXPECT_NEAR(floor->distance(Point3(7, 0.25, 0)), -0.75, 1e-14);
  EXPECT_NEAR(floor->distance(Point3(-3, 3, 0)), 2.0, 1e-14);
  const auto slope = sph::make_half_space(Point3(0, 0, 0), Point3(1, 1, 0));
  EXPECT_NEAR(slope->distance(Point3(1, 1, 0)), std::sqrt(2.0), 1e-14);
}

TEST(SceneShapes, PolygonDistanceAndInside) {
  // The right triangle (0,0), (4,0), (0,3): hypotenuse 3x + 4y = 12.
  const auto tri = sph::make_polygon({{0, 0}, {4, 0}, {0, 3}});
  EXPECT_NEAR(tri->distance(Point3(1, 1, 0)), -1.0, 1e-14);                     // the legs are nearest
  EXPECT_NEAR(tri->distance(Point3(4, 3, 0)), (12 + 12 - 12) / 5.0, 1e-14);     // beyond the hypotenuse
  EXPECT_NEAR(tri->distance(Point3(-3, -4, 0)), 5.0, 1e-14);                    // beyond the corner
  EXPECT_NEAR(tri->distance(Point3(2, 1.4, 0)), -(12 - 6 - 5.6) / 5.0, 1e-14);  // near the hypotenuse
  // A square as a polygon is the box, in either winding.
  const auto box = sph::make_box(Point3(0, 0, 0), Point3(1, 1, 0), 2);
  const auto ccw = sph::make_polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const auto cw = sph::make_polygon({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  for (const Point3& x : {Point3(0.3, 0.2, 0), Point3(1.5, 0.2, 0), Point3(-1, 2, 0), Point3(0.5, 0.99, 0)}) {
    EXPECT_NEAR(ccw->distance(x), box->distance(x), 1e-14);
    EXPECT_NEAR(cw->distance(x), box->distance(x), 1e-14);
  }
}

TEST(SceneShapes, CombinationsBoundTheDistanceWithTheRightSign) {
  const auto a = sph::make_box(Point3(0, 0, 0), Point3(2, 1, 0), 2);
  const auto b = sph::make_ball(Point3(2, 0.5, 0), 0.5);
  const auto u = sph::make_union({a, b}), i = sph::make_intersection({a, b}), d = sph::make_difference({a, b});
  // Each near its own parts' surfaces: the exact distance.
  EXPECT_NEAR(u->distance(Point3(2.6, 0.5, 0)), 0.1, 1e-14);   // beyond the ball's right
  EXPECT_NEAR(u->distance(Point3(-0.2, 0.5, 0)), 0.2, 1e-14);  // left of the box
  EXPECT_NEAR(i->distance(Point3(1.9, 0.5, 0)), -0.1, 1e-14);  // inside both, near the box's face
  EXPECT_GT(i->distance(Point3(2.2, 0.5, 0)), 0);              // in the ball only
  EXPECT_NEAR(d->distance(Point3(1.6, 0.5, 0)), 0.1, 1e-14);   // carved out by the ball
  EXPECT_NEAR(d->distance(Point3(1.4, 0.5, 0)), -0.1, 1e-14);  // left of the carved surface
  EXPECT_NEAR(d->distance(Point3(0.1, 0.5, 0)), -0.1, 1e-14);  // left part of the box
  EXPECT_GT(d->distance(Point3(2.2, 0.5, 0)), 0);
  // Tops along +y: the union's is its highest part's, the difference's its first part's.
  EXPECT_DOUBLE_EQ(u->highest(Point3(0, 1, 0)), 1.0);
  EXPECT_DOUBLE_EQ(sph::make_ball(Point3(0, 0, 0), 2)->highest(Point3(0, 1, 0)), 2.0);
}

// nx * width by nx * height, whatever the resolution: the lattice (i + 1/2) dx fills the box.
TEST(SceneShapes, BoxOfFluidHoldsWholeRowsAndColumns) {
  const std::string text = "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0.2, 1.7, -0.5, 0.5]}}\n";
  for (int nx : {10, 20, 40}) {
    const sph::YamlScene s = sample("box_fluid", text, 1.0 / nx);
    EXPECT_EQ(count(s.file, sph::kSceneFluid), static_cast<long>(1.5 * nx) * nx) << "nx " << nx;
    EXPECT_EQ(s.file.x.size(), s.file.kind.size());
    EXPECT_DOUBLE_EQ(s.file.field.at("dx")[0], 1.0 / nx);
  }
  const std::string cube = "dimension: 3\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 0.5, 0, 0.25]}}\n";
  EXPECT_EQ(count(sample("box_fluid3", cube, 0.05).file, sph::kSceneFluid), 20 * 10 * 5);
}

// The fluid area of a circle, count dx^2, tends to pi r^2: within a band of one dx around its rim at
// every resolution, and closer at the finest than at the coarsest.
TEST(SceneShapes, CircleAreaConvergesToPiRSquared) {
  const double r = 0.37, exact = M_PI * r * r;
  const std::string text =
      "dimension: 2\nregions:\n  - {role: fluid, shape: {circle: {centre: [0.013, -0.021], radius: 0.37}}}\n";
  std::vector<double> error;
  for (int nx : {10, 20, 40, 80, 160}) {
    const double dx = 1.0 / nx;
    const double area = count(sample("circle", text, dx).file, sph::kSceneFluid) * dx * dx;
    error.push_back(std::abs(area - exact));
    EXPECT_LT(error.back(), 2 * M_PI * r * dx) << "nx " << nx;
  }
  EXPECT_LT(error.back(), 0.1 * error.front());
}

// A floor many layers thick that runs past the box: only `layers` rows are sampled, under its top.
TEST(SceneShapes, WallsAreExactlyTheGivenLayersDeep) {
  const std::string text =
      "dimension: 2\nbox: [0, 1, -1, 0.5]\nregions:\n  - {role: wall, shape: {box: [-1, 2, -2, 0]}}\n"
      "  - {role: fluid, shape: {box: [0, 1, 0, 0.5]}}\n";
  for (int layers : {3, 4}) {
    for (int nx : {10, 25}) {
      const sph::YamlScene s = sample("slab", text, 1.0 / nx, layers);
      std::set<long> rows;
      for (std::size_t i = 0; i < s.file.x.size(); ++i)
        if (s.file.kind[i] == sph::kSceneFixedWall) rows.insert(std::lround(s.file.x[i][1] * nx - 0.5));
      EXPECT_EQ(rows.size(), static_cast<std::size_t>(layers)) << "nx " << nx;
      EXPECT_EQ(*rows.rbegin(), -1);  // the top row touches the surface
      EXPECT_EQ(count(s.file, sph::kSceneFixedWall), static_cast<long>(layers) * nx);
    }
  }
}

// p = rho0 |g| s, s the distance along up = -g / |g| at which the line from x leaves the water: the
// box's top or its left side under this tilted gravity.
TEST(SceneShapes, HydrostaticPressureIsRhoGDepth) {
  const std::string text =
      "dimension: 2\nphysics: {gravity: [0.6, -0.8], rho0: 3}\nregions:\n"
      "  - {role: fluid, shape: {box: [0, 1, 0, 0.4]}, pressure: hydrostatic}\n"
      "  - {role: fluid, shape: {box: [2, 3, 0, 1]}, velocity: [0.5, 0], pressure: 7}\n";
  const sph::YamlScene s = sample("hydrostatic", text, 0.05);
  long pool = 0, block = 0;
  for (std::size_t i = 0; i < s.file.x.size(); ++i) {
    const double x = s.file.x[i][0], y = s.file.x[i][1];
    if (x < 1.5) {
      const double depth = std::min((0.4 - y) / 0.8, x / 0.6);
      EXPECT_NEAR(s.file.p[i], 3.0 * 1.0 * depth, 1e-12) << x << ", " << y;
      EXPECT_EQ(s.file.v[i][0], 0.0);
      ++pool;
    } else {
      EXPECT_EQ(s.file.p[i], 7.0);
      EXPECT_EQ(s.file.v[i][0], 0.5);
      ++block;
    }
  }
  EXPECT_EQ(pool, 20 * 8);
  EXPECT_EQ(block, 20 * 20);
}

// A tilted surface (the sloshing tank's start) and bodies under water: each particle's pressure is
// rho0 g times its depth below the surface above it, which the bodies do not interrupt, nor the side of
// one cut out of the fluid's region whose face lies on a lattice column (at dx 0.05 the block's sides
// are columns of points at distance 0 from both the fluid's region and the block).
TEST(SceneShapes, HydrostaticPressureFollowsATiltedSurface) {
  const std::string text =
      "dimension: 2\nbox: [-0.2, 2.2, -0.2, 1.2]\nphysics: {gravity: [0, -9.81], rho0: 1000}\nregions:\n"
      "  - {role: wall, shape: {difference: [{box: [-0.2, 2.2, -0.2, 1.2]}, {box: [0, 2, 0, 1.2]}]}}\n"
      "  - {role: fluid, shape: {difference: [{polygon: [[0, 0], [2, 0], [2, 0.3], [0, 0.5]]}, "
      "{box: [1.425, 1.575, 0.1, 0.25]}]}, pressure: hydrostatic}\n"
      "  - {role: {body: stone}, shape: {circle: {centre: [1, 0.15], radius: 0.08}}}\n"
      "  - {role: {body: block}, shape: {box: [1.425, 1.575, 0.1, 0.25]}}\n";
  for (const double dx : {0.05, 0.0125}) {
    const sph::YamlScene s = sample("tilted", text, dx);
    long fluid = 0, under_stone = 0, beside_block = 0;
    for (std::size_t i = 0; i < s.file.x.size(); ++i) {
      if (s.file.kind[i] != sph::kSceneFluid) continue;
      const double x = s.file.x[i][0], y = s.file.x[i][1];
      const double surface = 0.5 - 0.1 * x;
      EXPECT_NEAR(s.file.p[i], 1000 * 9.81 * (surface - y), 1e-9) << x << ", " << y << " at dx " << dx;
      ++fluid;
      under_stone += std::abs(x - 1) < 0.05 && y < 0.07;
      beside_block += std::abs(x - 1.425) < 1e-9 && y < 0.1;
    }
    EXPECT_GT(fluid, 0);
    EXPECT_GT(under_stone, 0);
    if (dx == 0.05) {
      EXPECT_GT(beside_block, 0);
    }
  }
}

TEST(SceneShapes, BodiesAreFixedWallsThatKeepTheirNames) {
  const std::string text =
      "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}}\n"
      "  - {role: {body: wheel}, shape: {circle: {centre: [0.5, 0.5], radius: 0.2}}}\n"
      "  - {role: wall, shape: {box: [0, 1, -0.5, 0]}}\n"
      "  - {role: {body: wheel}, shape: {circle: {centre: [0.5, -0.6], radius: 0.05}}}\n";
  const sph::YamlScene s = sample("bodies", text, 0.05);
  ASSERT_EQ(s.bodies, std::vector<std::string>{"wheel"});
  ASSERT_EQ(s.body.size(), s.file.x.size());
  long wheel = 0;
  for (std::size_t i = 0; i < s.body.size(); ++i) {
    const double x = s.file.x[i][0] - 0.5, y = s.file.x[i][1];
    const bool in_wheel = x * x + (y - 0.5) * (y - 0.5) <= 0.04 || x * x + (y + 0.6) * (y + 0.6) <= 0.0025;
    EXPECT_EQ(s.body[i], in_wheel ? 0 : -1);
    if (in_wheel) {
      EXPECT_EQ(s.file.kind[i], sph::kSceneFixedWall);
    }
    wheel += s.body[i] == 0;
  }
  EXPECT_GT(wheel, 0);
  // The checksum is the file and the resolution.
  EXPECT_NE(s.file.checksum, sample("bodies", text, 0.025).file.checksum);
  EXPECT_EQ(s.file.checksum, sample("bodies", text, 0.05).file.checksum);
}

// The flat form (physics keys at the top, role: body with name:, shapes inline with their parameters
// beside them) samples the same particles as the nested one.
TEST(SceneShapes, InlineShapesAndTopLevelPhysicsMatchTheNestedForm) {
  const std::string flat =
      "dimension: 2\nbox: [-0.2, 2.2, -0.2, 1.6]\ngravity: [0, -1]\nnu: 0.01\nrho0: 1\nfree_surface: true\n"
      "regions:\n"
      "  - {role: wall, shape: difference, of: [{box: [-0.2, 2.2, -0.2, 1.4]}, {box: [0, 2, 0, 1.5]}]}\n"
      "  - {role: fluid, shape: difference, of: [{box: [0, 2, 0, 1]}, {circle: {centre: [1, 0.5], radius: 0.2}}], "
      "pressure: hydrostatic}\n"
      "  - {role: body, name: c, shape: circle, centre: [1, 0.5], radius: 0.2}\n"
      "  - {role: wall, shape: box, bounds: [1.8, 1.9, 0.1, 0.2]}\n";
  const std::string nested =
      "dimension: 2\nbox: [-0.2, 2.2, -0.2, 1.6]\n"
      "physics: {gravity: [0, -1], nu: 0.01, rho0: 1, free_surface: true}\nregions:\n"
      "  - {role: wall, shape: {difference: [{box: [-0.2, 2.2, -0.2, 1.4]}, {box: [0, 2, 0, 1.5]}]}}\n"
      "  - {role: fluid, shape: {difference: [{box: [0, 2, 0, 1]}, {circle: {centre: [1, 0.5], radius: 0.2}}]}, "
      "pressure: hydrostatic}\n"
      "  - {role: {body: c}, shape: {circle: {centre: [1, 0.5], radius: 0.2}}}\n"
      "  - {role: wall, shape: {box: [1.8, 1.9, 0.1, 0.2]}}\n";
  const sph::YamlScene a = sample("flat", flat, 0.05), b = sample("nested", nested, 0.05);
  EXPECT_EQ(a.file.x, b.file.x);
  EXPECT_EQ(a.file.kind, b.file.kind);
  EXPECT_EQ(a.file.p, b.file.p);
  EXPECT_EQ(a.body, b.body);
  EXPECT_EQ(a.bodies, std::vector<std::string>{"c"});
  EXPECT_EQ(a.file.field.at("gravity"), b.file.field.at("gravity"));
  EXPECT_EQ(a.file.field.at("nu"), b.file.field.at("nu"));
  EXPECT_EQ(a.file.field.at("free_surface"), b.file.field.at("free_surface"));
  EXPECT_GT(std::count(a.body.begin(), a.body.end(), 0), 0);
}

// Each {CSV text, message} pair: the text written to `file` beside the scene, sampling the scene fails
// with an error holding the message.
void expect_table_refusals(const std::string& name, const std::string& scene, const std::string& file,
                           const std::vector<std::pair<std::string, std::string>>& tables) {
  for (const auto& [csv, expected] : tables) {
    std::ofstream(folder() + "/" + file) << csv;
    std::string message;
    try {
      sample(name, scene, 0.1);
    } catch (const sph::Error& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

// An inlet's speed table: checked as a motion table is (one reader), and its factors may not be negative.
TEST(SceneShapes, InletSpeedTablesAreCheckedRowByRow) {
  const std::string scene =
      "dimension: 2\nbox: [0, 2, -0.3, 1.3]\nregions:\n  - {role: wall, shape: {box: [-1, 3, -1, 0]}}\n"
      "  - {role: wall, shape: {box: [-1, 3, 1, 2]}}\n  - {role: fluid, shape: {box: [0, 2, 0, 1]}}\n"
      "  - {role: inlet, side: x-, velocity: {parabolic: 1}, speed_table: s.csv}\n"
      "  - {role: outlet, side: x+}\n";
  const std::vector<std::pair<std::string, std::string>> tables = {
      {"t,speed\n0,1\n1,2\n", "has the header 't,speed'; give t,factor in the first line"},
      {"t,factor\n0,1\n0,2\n", "row 3: t = 0 does not increase"},
      {"t,factor\n0,1\n1\n", "row 3 has 1 values; give 2"},
      {"t,factor\n0,1\n", "holds fewer than two rows"},
      {"t,factor\n0,1\n1,-0.5\n", "row 3: factor -0.5 is negative"},
  };
  expect_table_refusals("inlet", scene, "s.csv", tables);
  std::ofstream(folder() + "/s.csv") << "t, factor\n0, 1\n0.5, 2\n";
  const sph::YamlScene ok = sample("inlet", scene, 0.1);
  ASSERT_EQ(ok.open.size(), 2u);
  EXPECT_EQ(ok.open[0].speed_t, (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(ok.open[0].speed_factor, (std::vector<double>{1.0, 2.0}));
}

// A motion table's file: its header, its rows and its times are checked, naming the row.
TEST(SceneShapes, MotionTablesAreCheckedRowByRow) {
  const std::string scene =
      "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}}\n"
      "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {type: table, file: m.csv}}\n";
  const std::vector<std::pair<std::string, std::string>> tables = {
      {"t,x\n0,0\n1,1\n", "has the header 't,x'; give t,x,y (and ,angle in degrees) in the first line"},
      {"t,x,y\n0,0,0\n0,1,0\n", "row 3: t = 0 does not increase"},
      {"t,x,y\n0,0,0\n1,one,0\n", "row 3: 'one' is not a finite number"},
      {"t,x,y\n0,0,0\n", "holds fewer than two rows"},
      {"t,x,y,angle\n0,0,0,0\n1,0,0,10\n", "turns the body (an angle column) but has no centre"},
  };
  expect_table_refusals("table", scene, "m.csv", tables);
  std::ofstream(folder() + "/m.csv") << "t, x, y\n0, 0, 0\n0.5, 0.1, 0\n1, 0.3, -0.1\n";
  const sph::YamlScene ok = sample("table", scene, 0.1);
  ASSERT_EQ(ok.motions.size(), 1u);
  EXPECT_EQ(ok.motions[0].type, "table");
  EXPECT_EQ(ok.motions[0].table_t, (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(ok.motions[0].table_x[1], (std::vector<double>{0, 0, -0.1}));
}

TEST(SceneShapes, RefusalsNameTheFileTheKeyAndTheFix) {
  struct Case {
    const char* name;
    std::string text, expected;
  };
  const std::string ok_region = "  - {role: fluid, shape: {box: [0, 1, 0, 1]}}\n";
  const std::vector<Case> cases = {
      {"syntax", "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}\n",
       "line 4, column 1: YAML syntax error (end of map flow not found); fix the syntax there"},
      {"unknown_key", "dimension: 2\ngravty: [0, -1]\nregions:\n" + ok_region,
       "line 2: unknown key 'gravty'; the keys at the top are dimension, dx, box"},
      {"unknown_region_key", "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}, velocty: [1, 0]}\n",
       "line 3, regions[0]: unknown key 'velocty'; the keys here are role, shape, velocity, pressure"},
      {"unknown_shape", "dimension: 2\nregions:\n  - {role: fluid, shape: {cube: [0, 1, 0, 1]}}\n",
       "regions[0].shape: unknown shape 'cube'; use one of box, circle, polygon"},
      {"coordinates", "dimension: 3\nregions:\n" + ok_region,
       "regions[0].shape.box: has 4 numbers; a 3D scene takes 6: [x0, x1, y0, y1, z0, z1]"},
      {"centre", "dimension: 2\nregions:\n  - {role: fluid, shape: {circle: {centre: [0, 0, 0], radius: 1}}}\n",
       "regions[0].shape.circle.centre: has 3 numbers; a 2D scene takes 2: [x, y]"},
      {"radius", "dimension: 2\nregions:\n  - {role: fluid, shape: {circle: {centre: [0, 0], radius: -0.1}}}\n",
       "regions[0].shape.circle.radius: is -0.1; a radius must be positive"},
      {"no_fluid", "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 0.04, 0, 1]}}\n",
       "regions: hold no fluid particle at dx = 0.1"},
      {"mesh", "dimension: 3\nregions:\n  - {role: wall, shape: {mesh: missing.stl}}\n" + std::string(ok_region),
       "regions[0].shape.mesh: cannot read '"},
      {"circle_3d", "dimension: 3\nregions:\n  - {role: fluid, shape: {circle: {centre: [0, 0], radius: 1}}}\n",
       "regions[0].shape.circle: is a 2D shape, this scene is 3D; use sphere"},
      {"no_dx", "dimension: 2\nregions:\n" + ok_region,
       "gives no particle spacing; pass -nx N (dx = 1/N) or -scene_dx, or add dx: to the file"},
      {"wall_velocity", "dimension: 2\nregions:\n  - {role: wall, shape: {box: [0, 1, 0, 1]}, velocity: [1, 0]}\n",
       "regions[0].velocity: is given for a wall"},
      {"hydrostatic", "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}, pressure: hydrostatic}\n",
       "is hydrostatic but the scene has no gravity"},
      {"half_space",
       "dimension: 2\nregions:\n  - {role: fluid, shape: {half_space: {point: [0, 0], normal: [1, 1]}}}\n",
       "regions: reach to infinity along x (a half_space); give a box"},
      {"periodic", "dimension: 2\nbox: [0, 1.05, 0, 1]\nperiodic: [x]\nregions:\n" + ok_region,
       "box: is 1.05 long along periodic x, not a whole number of dx = 0.1"},
      {"body_name", "dimension: 2\nregions:\n" + ok_region + "  - {role: body, shape: {box: [0, 1, -1, 0]}}\n",
       "regions[1]: is a body without a name; add name: NAME"},
      {"walls_body",
       "dimension: 2\nregions:\n" + ok_region + "  - {role: {body: walls}, shape: {box: [0, 1, -1, 0]}}\n",
       "names a body 'walls', the name of the walls' own force columns; rename it"},
      {"inline_missing", "dimension: 2\nregions:\n  - {role: fluid, shape: difference}\n",
       "regions[0]: has shape: difference but no of; add of: ... beside it"},
      {"inline_mixed", "dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}, radius: 1}\n",
       "regions[0]: gives radius beside a nested shape; write shape: NAME for the inline form"},
      {"physics_twice", "dimension: 2\nnu: 1\nphysics: {nu: 2}\nregions:\n" + ok_region,
       "line 2, nu: is given at the top and under physics; keep one"},
      {"wall_motion",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: wall, shape: {box: [0, 1, -1, 0]}, motion: {type: constant, velocity: [1, 0]}}\n",
       "regions[1].motion: is given for a region that is no body; only role: body moves"},
      {"motion_type",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {type: spin}}\n",
       "regions[1].motion.type: is 'spin'; give fixed, constant, sinusoidal or table"},
      {"motion_period",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {type: sinusoidal, amplitude: [1, 0], period: "
           "0}}\n",
       "regions[1].motion.period: is 0; give a positive period"},
      {"rotation_centre",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {rotation: {type: constant, rate: 10}}}\n",
       "regions[1].motion.rotation: has no centre; give the point the axis goes through"},
      {"rotation_axis_2d",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {rotation: {type: constant, rate: 10, centre: "
           "[0, 0], axis: [0, 0]}}}\n",
       "regions[1].motion.rotation.axis: is given in a 2D scene, where bodies turn about z; remove it"},
      {"table_missing",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {type: table, file: nowhere.csv}}\n",
       "regions[1].motion.file: cannot be opened"},
      {"motion_twice",
       "dimension: 2\nregions:\n" + ok_region +
           "  - {role: {body: b}, shape: {box: [0, 1, -1, 0]}, motion: {type: constant, velocity: [1, 0]}}\n"
           "  - {role: {body: b}, shape: {box: [2, 3, -1, 0]}, motion: {type: constant, velocity: [1, 0]}}\n",
       "regions[2].motion: moves body 'b' a second time; give its motion on one region"},
      {"probes_map", "dimension: 2\nregions:\n" + ok_region + "probes: {name: P1, at: [0.5, 0.5]}\n",
       "probes: is not a list; write probes: [{name: P1, at: [x, y]}]"},
      {"probe_name", "dimension: 2\nregions:\n" + ok_region + "probes:\n  - {name: P-1, at: [0.5, 0.5]}\n",
       "probes[0].name: is 'P-1'; give letters, digits and _ only"},
      {"probe_twice",
       "dimension: 2\nregions:\n" + ok_region +
           "probes:\n  - {name: P, at: [0.5, 0.5]}\n  - {name: P, at: [0.2, 0.5]}\n",
       "probes[1].name: repeats the probe name 'P'"},
      {"probe_outside",
       "dimension: 2\nbox: [0, 1, 0, 1]\nregions:\n" + ok_region + "probes:\n  - {name: P, at: [0.5, 1.2]}\n",
       "probes[0].at: lies outside the box along y; move it inside"},
      {"probe_point", "dimension: 2\nregions:\n" + ok_region + "probes:\n  - {name: P}\n",
       "probes[0]: needs a name and a point; write {name: P1, at: [x, y]}"},
      {"probe_3d", "dimension: 2\nregions:\n" + ok_region + "probes:\n  - {name: P, at: [0.5, 0.5, 0.5]}\n",
       "probes[0].at: has 3 numbers; a 2D scene takes 2: [x, y]"},
  };
  for (const Case& c : cases) {
    const std::string path = folder() + "/" + c.name + ".yaml";
    std::ofstream(path) << c.text;
    const double dx = std::string(c.name) == "no_dx" ? 0.0 : 0.1;
    EXPECT_THROW(sph::read_yaml_scene(path, dx, 3), sph::Error) << c.name;
    const std::string message = refusal(c.name, c.text, dx);
    EXPECT_EQ(message.rfind("scene file '" + path + "': ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// The box lo-hi as an STL surface of triangles: all six faces, or the first `faces` of them.
bool write_cube_stl(const std::string& path, const Point3& lo, const Point3& hi, int faces = 6, bool binary = false) {
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 8; ++k)
    points->InsertNextPoint(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  // Corners of each face, numbered by the bits x = 1, y = 2, z = 4; the windings are left mixed.
  const vtkIdType quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  vtkNew<vtkCellArray> triangles;
  for (int f = 0; f < faces; ++f) {
    const vtkIdType a[3] = {quads[f][0], quads[f][1], quads[f][2]}, b[3] = {quads[f][0], quads[f][2], quads[f][3]};
    triangles->InsertNextCell(3, a), triangles->InsertNextCell(3, b);
  }
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(points);
  surface->SetPolys(triangles);
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputData(surface);
  writer->SetFileName(path.c_str());
  if (binary) writer->SetFileTypeToBinary();
  return writer->Write() == 1;
}

// A cube written as an STL surface samples to the particles of the box it bounds, as fluid and as a
// wall (the signed distance decides the wall's depth too), whatever the file's winding.
TEST(SceneShapes, MeshCubeSamplesAsTheEquivalentBox) {
  ASSERT_TRUE(write_cube_stl(folder() + "/cube.stl", Point3(0.2, 0.1, 0.3), Point3(0.8, 0.7, 0.9)));
  auto positions = [](const sph::YamlScene& s, int kind) {
    std::set<std::array<long, 3>> p;
    for (std::size_t i = 0; i < s.file.x.size(); ++i)
      if (s.file.kind[i] == kind)
        p.insert(
            {std::lround(s.file.x[i][0] * 1e6), std::lround(s.file.x[i][1] * 1e6), std::lround(s.file.x[i][2] * 1e6)});
    return p;
  };
  const std::string head = "dimension: 3\nregions:\n";
  const std::string box = "{box: [0.2, 0.8, 0.1, 0.7, 0.3, 0.9]}";
  const std::string pool = "  - {role: fluid, shape: {box: [0, 1, 0, 1, 0, 1]}}\n";
  for (double dx : {0.1, 0.05}) {
    const auto fluid_mesh = sample("mesh_fluid", head + "  - {role: fluid, shape: {mesh: cube.stl}}\n", dx);
    const auto fluid_box = sample("box_fluid3d", head + "  - {role: fluid, shape: " + box + "}\n", dx);
    EXPECT_EQ(positions(fluid_mesh, sph::kSceneFluid), positions(fluid_box, sph::kSceneFluid)) << "dx " << dx;
    const std::size_t side = std::lround(0.6 / dx);
    EXPECT_EQ(positions(fluid_box, sph::kSceneFluid).size(), side * side * side);
    const auto wall_mesh = sample("mesh_wall", head + pool + "  - {role: wall, shape: {mesh: cube.stl}}\n", dx);
    const auto wall_box = sample("box_wall", head + pool + "  - {role: wall, shape: " + box + "}\n", dx);
    EXPECT_EQ(positions(wall_mesh, sph::kSceneFixedWall), positions(wall_box, sph::kSceneFixedWall)) << "dx " << dx;
    EXPECT_EQ(positions(wall_mesh, sph::kSceneFluid), positions(wall_box, sph::kSceneFluid)) << "dx " << dx;
  }
  // As a body, the mesh is its own surface (not a contour of its distance, which cuts the edges):
  // closed, refined to faces no wider than the spacing, pointing out, enclosing the cube exactly.
  const auto body = sample("mesh_body", head + pool + "  - {role: body, name: cube, shape: {mesh: cube.stl}}\n", 0.1);
  ASSERT_EQ(body.surfaces.size(), 1u);
  const sph::SurfaceMesh& mesh = body.surfaces[0];
  EXPECT_TRUE(mesh.closed);
  EXPECT_GT(mesh.cells.size(), 12u);
  double volume = 0.0;  // (1/3) sum x . n a over the faces (divergence theorem)
  for (const auto& cell : mesh.cells) {
    const Eigen::Vector3d x = sph::face_centre(mesh, cell), n = sph::face_area_normal(mesh, cell);
    EXPECT_GT((x - Eigen::Vector3d(0.5, 0.4, 0.6)).dot(n), 0.0);
    volume += x.dot(n) / 3.0;
  }
  EXPECT_NEAR(volume, 0.6 * 0.6 * 0.6, 1e-6);  // an STL holds single-precision coordinates
  // An open surface (a cube without its last face) has no inside: refused.
  ASSERT_TRUE(write_cube_stl(folder() + "/open.stl", Point3(0.2, 0.1, 0.3), Point3(0.8, 0.7, 0.9), 5));
  EXPECT_NE(refusal("open", head + pool + "  - {role: wall, shape: {mesh: open.stl}}\n").find("not a closed surface"),
            std::string::npos);
}

// STL comes as text or binary (its header may start "solid" as well); both read alike. A file that is
// neither (an archive named .stl, here 3 GB of zeros, sparse on disk) is refused from its size and
// first bytes, not read whole.
TEST(SceneShapes, MeshStlIsTextOrBinaryAndNothingElse) {
  const Point3 lo(0.2, 0.1, 0.3), hi(0.8, 0.7, 0.9);
  ASSERT_TRUE(write_cube_stl(folder() + "/text.stl", lo, hi));
  ASSERT_TRUE(write_cube_stl(folder() + "/binary.stl", lo, hi, 6, true));
  const std::string head = "dimension: 3\nregions:\n";
  const auto text = sample("stl_text", head + "  - {role: fluid, shape: {mesh: text.stl}}\n", 0.1);
  const auto binary = sample("stl_binary", head + "  - {role: fluid, shape: {mesh: binary.stl}}\n", 0.1);
  EXPECT_EQ(text.file.x.size(), 216u);
  EXPECT_EQ(binary.file.x.size(), text.file.x.size());
  {
    std::ofstream junk(folder() + "/junk.stl", std::ios::binary);
    junk.seekp((std::streamoff(3) << 30) - 1);
    junk.put('\0');
  }
  EXPECT_NE(refusal("stl_junk", head + "  - {role: fluid, shape: {mesh: junk.stl}}\n")
                .find("is not an STL file: neither text starting 'solid ... facet' nor binary"),
            std::string::npos);
  std::filesystem::remove(folder() + "/junk.stl");
}

}  // namespace
