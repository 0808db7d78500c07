// The YAML scene reader's shared parts: the regions as read and the Reader that checks every key. Internal
// to cases/scene/: scene_yaml.cpp reads a scene with them (scene_yaml.hpp is the public face); the
// Reader's members are defined in scene_reader.cpp (keys, numbers, shapes, regions), scene_motions.cpp
// (motions) and scene_plates.cpp (plates).
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cases/scene/scene_yaml.hpp"
#include "cases/scene/shapes.hpp"

namespace sph::scene_detail {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Lattice points within this share of dx of a surface or a box face count as on it (inside).
constexpr double kOnSurface = 1e-6;

inline std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

enum class Role { Fluid, Wall, Body };

// A region's keys that hold an inline shape's parameters (Reader::inline_shape).
inline const std::set<std::string> kInlineParameters = {"of",     "bounds", "vertices", "file",  "centre",
                                                        "center", "radius", "ends",     "point", "normal",
                                                        "from",   "to",     "thickness"};

// A thin plate (2D): its mid-line from a to b and its thickness, which may be below the kernel
// support (src/neighbours/screens.hpp).
struct PlateSpec {
  Point3 a = Point3::Zero(), b = Point3::Zero();
  double thickness = 0.0;
};

struct Region {
  Role role = Role::Fluid;
  int body = -1;
  ShapePtr shape;
  Point3 velocity = Point3::Zero();
  double pressure = 0.0;
  bool hydrostatic = false;
  double top = 0.0;  // hydrostatic: the region's highest point along -g
  MotionSpec motion;
  bool free_slip = false;  // walls and bodies: slip: free
  signed char wall_pressure =
      -1;                 // walls and bodies: wall_pressure: adami | continued (a WallPressure; -1: the option's)
  bool is_plate = false;  // shape: plate (then `shape` is its outline, for the bounds)
  PlateSpec plate;
  std::string key;  // regions[k], for the messages
  YAML::Node at;
};

// Parses one scene file; every refusal names the file, the line and the key. A key that is absent gives a
// node on which only IsDefined() may be asked (yaml-cpp throws on the others).
// A table read from a CSV file (Reader::csv_table).
struct CsvTable {
  std::string where, header_line;  // where: the key and the file, for errors
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path), dir_(std::filesystem::path(path).parent_path()) {}

  // Reading and checking (scene_reader.cpp).
  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& what) const;
  YAML::Node load(const std::string& text) const;
  // yaml-cpp keeps a key given twice in one mapping and answers the first: the second (dimension: 2,
  // then 3) would be silently ignored.
  void refuse_repeated_keys(const YAML::Node& n) const;
  YAML::Node parse();
  void only_keys(const YAML::Node& map, const std::string& key, std::initializer_list<const char*> allowed) const;
  double number(const YAML::Node& n, const std::string& key) const;
  std::vector<double> numbers(const YAML::Node& n, const std::string& key, std::size_t count,
                              const std::string& form) const;
  Point3 point(const YAML::Node& n, const std::string& key) const;
  double radius(const YAML::Node& map, const std::string& key) const;
  // The lower and upper corners of a box [x0, x1, y0, y1(, z0, z1)], each pair increasing.
  std::pair<Point3, Point3> box(const YAML::Node& n, const std::string& key) const;
  ShapePtr shape(const YAML::Node& n, const std::string& key);
  ShapePtr polygon(const YAML::Node& v, const std::string& k) const;
  ShapePtr mesh(const YAML::Node& v, const std::string& k);
  // A shape written inline, `shape: NAME` with its parameters beside it in the region (`shape: circle,
  // centre: [..], radius: R`; `shape: difference, of: [..]`; box: bounds, polygon: vertices, mesh: file),
  // as the nested form {NAME: value}.
  YAML::Node inline_shape(const YAML::Node& n, const std::string& key) const;
  // Whether region n is an inlet or an outlet (role: inlet / outlet).
  static bool is_open_boundary(const YAML::Node& n);
  // {role: inlet, side: x-, velocity: [u, v] or {parabolic: U_max}, ramp: T, speed_table: FILE} or
  // {role: outlet, side: x+, pressure: p, level: H}: the side and the condition; the buffer's place and
  // section come with the lattice.
  // Where it lies: on a side of the box (the box given, the axis not periodic, the side free), with a
  // buffer `depth` deep.
  OpenBoundarySpec open_boundary(const YAML::Node& n, const std::string& key, bool has_box, const Point3& box_lo,
                                 const Point3& box_hi, const std::vector<double>& periodic,
                                 const std::vector<OpenBoundarySpec>& others, double depth);
  OpenBoundarySpec open_boundary_condition(const YAML::Node& n, const std::string& key);
  // One region of regions:, its keys checked; a body's name added to `bodies`; g: the scene's gravity,
  // for a hydrostatic start.
  void read_role(const YAML::Node& n, const std::string& key, Region& r, std::vector<std::string>& bodies) const;
  Region region(const YAML::Node& n, const std::string& key, std::vector<std::string>& bodies, const Point3& g);
  void wall_conditions(const YAML::Node& n, const std::string& key, Region& r) const;

  // A CSV table in the file that file_key names (relative to the scene file; `what` names it in the
  // error for a folder): its header, then rows of finite numbers as many as the header's cells, the
  // first (t) increasing, two rows at least, each error naming the row (scene_tables.cpp). check_header
  // sees the header before any row is read, and fails on a wrong one. The bytes join the checksum.
  CsvTable csv_table(const YAML::Node& file_key, const std::string& key, const std::string& what,
                     const std::function<void(const CsvTable&)>& check_header);
  // An inlet's speed_table: FILE, a CSV with the header t,factor, factors >= 0.
  void inlet_speed_table(const YAML::Node& file_key, const std::string& key, OpenBoundarySpec& b);
  void inlet_expressions(const YAML::Node& n, const std::string& key, OpenBoundarySpec& b) const;

  // Motions (scene_motions.cpp).
  // {type: fixed}, {type: constant, velocity: [..]} or {type: sinusoidal, amplitude: [..], period: T,
  // phase: degrees (optional)}.
  MotionSpec motion(const YAML::Node& m, const std::string& key);
  // A free body's density: or mass: (one of them, positive), keys of its region beside its motion.
  void body_mass(const YAML::Node& n, const std::string& key, MotionSpec& motion) const;
  // {type: free, velocity: [..], rate: deg/s ([..] in 3D), fixed: [x, y, z, rotation, rx, ry, rz],
  // hinge: [..](, axis: [..] in 3D)}: a body the fluid moves (src/boundary/free_body.hpp); its density
  // or mass is a key of the region.
  MotionSpec free_motion(const YAML::Node& m, const std::string& key) const;
  // {type: table, file: motion.csv(, centre: [..], axis: [..])}: a CSV with the header t,x,y(,z)(,angle)
  // (angle in degrees, about the axis through centre), t increasing; the path relative to the scene file.
  void table_motion(const YAML::Node& m, const std::string& key, MotionSpec& spec);
  // An axis's direction, made unit.
  std::array<double, 3> unit_axis(const YAML::Node& n, const std::string& key) const;
  // The centre the rotation's axis goes through and, in 3D, its direction (none in 2D: about z).
  void rotation_axis(const YAML::Node& r, const std::string& key, MotionSpec& spec, const std::string& no_centre) const;
  // {type: constant, rate: deg/s, centre: [..](, axis: [..] in 3D)} or {type: sinusoidal, amplitude:
  // degrees, period: T, phase: degrees (optional), centre, axis}.
  void rotation(const YAML::Node& r, const std::string& key, MotionSpec& spec) const;

  // Plates (scene_plates.cpp).
  // {from: [x, y], to: [x, y], thickness: T (default 0)}: a plate's mid-line and thickness; its outline,
  // a rectangle, is the region's shape for the bounds and the body's surface.
  void read_plate(const YAML::Node& v, const std::string& k, Region& r);

  std::uint64_t checksum = kFnv1aBasis;
  int dim = 2;
  struct MeshRead {
    YAML::Node at;
    std::string key, file;
    Bounds bounds;
  };
  std::vector<MeshRead> meshes;  // every mesh the regions read, for the check of their units

 private:
  std::string path_;
  std::filesystem::path dir_;
};

// Axis flags from `none`, `x` or [x, y].
std::vector<double> periodic_axes(const Reader& r, const YAML::Node& n);

// prefix: where the keys stand, "physics." or "" (at the top), for the messages.
void read_physics(Reader& r, const YAML::Node& n, SceneFile& s, const std::string& prefix);

// A mesh drawn in other units than the scene (millimetres in a scene of metres) is far larger or
// smaller than the scene's box: refused naming the likely unit, before its surface is sampled at the
// scene's spacing (a 400-wide cube refined to dx/4 exhausts any memory).
void check_mesh_units(const Reader& r, const Point3& box_lo, const Point3& box_hi);

}  // namespace sph::scene_detail
