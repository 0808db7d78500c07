#include "cases/scene/scene_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "cases/scene/body_surface.hpp"
#include "cases/scene/shapes.hpp"
#include "src/core/error.hpp"
#include "src/particles/particle_budget.hpp"

namespace sph {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Lattice points within this share of dx of a surface or a box face count as on it (inside).
constexpr double kOnSurface = 1e-6;

// How far x lies below the free surface above it: the distance along `up` to the first point that
// `occupied` (a signed distance: negative inside the scene's fluid regions or solids) leaves empty, so
// that a tilted or curved surface starts in hydrostatic balance column by column and a submerged body
// does not cut the column. Marched in steps of dx (an overhang is found) and refined by bisection to
// round-off; `top` (the box's highest point along up) ends the march.
template <class Occupied>
double depth_below_surface(const Occupied& occupied, const Point3& x, const Point3& up, double top, double dx) {
  const double reach = top - up.dot(x);
  if (reach <= 0.0 || occupied(x) >= 0.0) return 0.0;
  double inside = 0.0, outside = reach;
  for (double s = dx; s < reach; s += dx) {
    if (occupied(x + s * up) >= 0.0) {
      outside = s;
      break;
    }
    inside = s;
  }
  for (int k = 0; k < 60 && outside - inside > 1e-12 * dx; ++k) {
    const double mid = 0.5 * (inside + outside);
    (occupied(x + mid * up) < 0.0 ? inside : outside) = mid;
  }
  return 0.5 * (inside + outside);
}

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

enum class Role { Fluid, Wall, Body };

// A region's keys that hold an inline shape's parameters (Reader::inline_shape).
const std::set<std::string> kInlineParameters = {"of",   "bounds", "vertices", "file", "centre", "center",   "radius",
                                                 "ends", "point",  "normal",   "from", "to",     "thickness"};

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
  bool is_plate = false;   // shape: plate (then `shape` is its outline, for the bounds)
  PlateSpec plate;
  std::string key;  // regions[k], for the messages
  YAML::Node at;
};

// Parses one scene file; every refusal names the file, the line and the key. A key that is absent gives a
// node on which only IsDefined() may be asked (yaml-cpp throws on the others).
class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path), dir_(std::filesystem::path(path).parent_path()) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
    std::string where = at.IsDefined() && at.Mark().line >= 0 ? "line " + std::to_string(at.Mark().line + 1) : "";
    if (!key.empty()) where += (where.empty() ? "" : ", ") + key;
    throw Error("scene file '" + path_ + "': " + (where.empty() ? "" : where + ": ") + what);
  }

  YAML::Node load(const std::string& text) const {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      throw Error("scene file '" + path_ + "': line " + std::to_string(e.mark.line + 1) + ", column " +
                  std::to_string(e.mark.column + 1) + ": YAML syntax error (" + e.msg + "); fix the syntax there");
    }
    refuse_repeated_keys(root);
    return root;
  }

  // yaml-cpp keeps a key given twice in one mapping and answers the first: the second (dimension: 2,
  // then 3) would be silently ignored.
  void refuse_repeated_keys(const YAML::Node& n) const {
    if (n.IsSequence())
      for (const auto& item : n) refuse_repeated_keys(item);
    if (!n.IsMap()) return;
    std::map<std::string, int> seen;  // key -> its first line
    for (const auto& item : n) {
      if (item.first.IsScalar()) {
        const auto [first, fresh] = seen.emplace(item.first.Scalar(), item.first.Mark().line + 1);
        if (!fresh)
          fail(item.first, "",
               "key '" + item.first.Scalar() + "' is given a second time in one mapping (first on line " +
                   std::to_string(first->second) + "); keep one");
      }
      refuse_repeated_keys(item.second);
    }
  }

  YAML::Node parse() {
    std::error_code ec;
    if (std::filesystem::is_directory(path_, ec))
      throw Error("scene file '" + path_ +
                  "': is a folder, not a scene file; give -scene_file the path of a .vtp or .yaml file");
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw Error("scene file '" + path_ + "': cannot be opened; check the path given to -scene_file");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    checksum = fnv1a(checksum, text.data(), text.size());
    const YAML::Node root = load(text);
    if (!root.IsMap())
      throw Error("scene file '" + path_ +
                  "': holds no YAML mapping; write keys such as dimension: 2 and regions: "
                  "(docs/user-guide.md, YAML scenes)");
    only_keys(root, "",
              {"dimension", "dx", "box", "periodic", "physics", "regions", "gravity", "nu", "rho0", "U", "free_surface",
               "t_end"});
    const YAML::Node d = root["dimension"];
    if (!d.IsDefined()) fail(YAML::Node(), "", "has no key 'dimension'; add dimension: 2 or dimension: 3");
    const double value = number(d, "dimension");
    if (value != 2 && value != 3) fail(d, "dimension", "is " + number_text(value) + "; give 2 or 3");
    dim = static_cast<int>(value);
    return root;
  }

  void only_keys(const YAML::Node& map, const std::string& key, std::initializer_list<const char*> allowed) const {
    if (!map.IsMap()) fail(map, key, "is not a mapping of keys to values; write {key: value, ...}");
    std::string list;
    for (const char* k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
    for (const auto& item : map) {
      const std::string name = item.first.Scalar();
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* k) { return name == k; }))
        fail(item.first, key,
             "unknown key '" + name + "'; the keys " + (key.empty() ? "at the top" : "here") + " are " + list);
    }
  }

  double number(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(n, key, "is not a number; give one, e.g. 0.5");
    double v = 0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, key, "is '" + n.Scalar() + "', not a number; give one, e.g. 0.5 (no arithmetic)");
    }
    if (!std::isfinite(v)) fail(n, key, "is " + n.Scalar() + "; give a finite number");
    return v;
  }

  std::vector<double> numbers(const YAML::Node& n, const std::string& key, std::size_t count,
                              const std::string& form) const {
    if (!n.IsSequence() || n.size() != count)
      fail(n, key,
           (n.IsSequence() ? "has " + std::to_string(n.size()) + " numbers" : std::string("is not a list")) + "; a " +
               std::to_string(dim) + "D scene takes " + std::to_string(count) + ": " + form);
    std::vector<double> v;
    for (std::size_t k = 0; k < count; ++k) v.push_back(number(n[k], key + "[" + std::to_string(k) + "]"));
    return v;
  }

  Point3 point(const YAML::Node& n, const std::string& key) const {
    const std::vector<double> v = numbers(n, key, dim, dim == 2 ? "[x, y]" : "[x, y, z]");
    return Point3(v[0], v[1], dim == 3 ? v[2] : 0.0);
  }

  double radius(const YAML::Node& map, const std::string& key) const {
    const YAML::Node r = map["radius"];
    if (!r.IsDefined()) fail(map, key, "has no radius; add radius: R");
    const double v = number(r, key + ".radius");
    if (!(v > 0)) fail(r, key + ".radius", "is " + number_text(v) + "; a radius must be positive");
    return v;
  }

  // The lower and upper corners of a box [x0, x1, y0, y1(, z0, z1)], each pair increasing.
  std::pair<Point3, Point3> box(const YAML::Node& n, const std::string& key) const {
    const std::vector<double> v = numbers(n, key, 2 * dim, dim == 2 ? "[x0, x1, y0, y1]" : "[x0, x1, y0, y1, z0, z1]");
    Point3 lo = Point3::Zero(), hi = Point3::Zero();
    for (int a = 0; a < dim; ++a) {
      lo[a] = v[2 * a], hi[a] = v[2 * a + 1];
      if (!(hi[a] > lo[a]))
        fail(n, key, std::string("has ") + "xyz"[a] + "1 <= " + "xyz"[a] + "0; give each axis as min, max");
    }
    return {lo, hi};
  }

  ShapePtr shape(const YAML::Node& n, const std::string& key) {
    const std::string known = dim == 2 ? "box, circle, polygon, half_space, union, intersection, difference"
                                       : "box, sphere, cylinder, half_space, mesh, union, intersection, difference";
    if (!n.IsMap() || n.size() != 1) fail(n, key, "is not one shape; write {SHAPE: ...} with SHAPE one of " + known);
    const std::string kind = n.begin()->first.Scalar();
    const YAML::Node v = n.begin()->second;
    const std::string k = key + "." + kind;
    auto need_dim = [&](int d, const char* instead) {
      if (dim != d)
        fail(n, k, "is a " + std::to_string(d) + "D shape, this scene is " + std::to_string(dim) + "D; use " + instead);
    };
    if (kind == "box") {
      const auto [lo, hi] = box(v, k);
      return make_box(lo, hi, dim);
    }
    if (kind == "circle" || kind == "sphere") {
      need_dim(kind == "circle" ? 2 : 3, kind == "circle" ? "sphere" : "circle");
      only_keys(v, k, {"centre", "center", "radius"});
      const YAML::Node c = v["centre"].IsDefined() ? v["centre"] : v["center"];
      if (!c.IsDefined()) fail(v, k, "has no centre; add centre: [x, y" + std::string(dim == 3 ? ", z]" : "]"));
      return make_ball(point(c, k + ".centre"), radius(v, k));
    }
    if (kind == "polygon") {
      need_dim(2, "a mesh, or a union of boxes, spheres and cylinders");
      if (!v.IsSequence() || v.size() < 3) fail(v, k, "needs a list of at least 3 vertices [[x, y], ...]");
      std::vector<Eigen::Vector2d> vertices;
      for (std::size_t i = 0; i < v.size(); ++i)
        vertices.push_back(point(v[i], k + "[" + std::to_string(i) + "]").head<2>());
      // Collinear vertices enclose nothing: the lattice points on the line would be a region of no area.
      double area = 0, extent = 0;
      for (std::size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++) {
        area += 0.5 * (vertices[j].x() * vertices[i].y() - vertices[i].x() * vertices[j].y());
        extent = std::max(extent, (vertices[i] - vertices[0]).norm());
      }
      if (!(std::abs(area) > 1e-12 * extent * extent))
        fail(v, k, "encloses no area (its vertices lie on one line); give vertices around the region");
      return make_polygon(vertices);
    }
    if (kind == "cylinder") {
      need_dim(3, "circle");
      only_keys(v, k, {"ends", "radius"});
      const YAML::Node ends = v["ends"];
      if (!ends.IsDefined() || !ends.IsSequence() || ends.size() != 2)
        fail(ends.IsDefined() ? ends : v, k + ".ends", "needs the centres of both ends: [[x, y, z], [x, y, z]]");
      const Point3 a = point(ends[0], k + ".ends[0]"), b = point(ends[1], k + ".ends[1]");
      if ((b - a).norm() == 0) fail(ends, k + ".ends", "are the same point; give a cylinder a length");
      return make_cylinder(a, b, radius(v, k));
    }
    if (kind == "half_space") {
      only_keys(v, k, {"point", "normal"});
      if (!v["point"].IsDefined() || !v["normal"].IsDefined())
        fail(v, k, "needs point and normal: the solid side is where (x - point) . normal <= 0");
      const Point3 normal = point(v["normal"], k + ".normal");
      if (normal.norm() == 0) fail(v["normal"], k + ".normal", "is zero; give the outward normal of the solid");
      return make_half_space(point(v["point"], k + ".point"), normal);
    }
    if (kind == "union" || kind == "intersection" || kind == "difference") {
      const std::size_t least = kind == "difference" ? 2 : 1;
      if (!v.IsSequence() || v.size() < least)
        fail(v, k, "needs a list of at least " + std::to_string(least) + " shapes [{SHAPE: ...}, ...]");
      std::vector<ShapePtr> parts;
      for (std::size_t i = 0; i < v.size(); ++i) parts.push_back(shape(v[i], k + "[" + std::to_string(i) + "]"));
      return kind == "union"          ? make_union(parts)
             : kind == "intersection" ? make_intersection(parts)
                                      : make_difference(parts);
    }
    if (kind == "mesh") {
      need_dim(3, "polygon");
      if (!v.IsScalar() || v.Scalar().empty()) fail(v, k, "needs a file name: mesh: surface.stl");
      std::filesystem::path file(v.Scalar());
      if (file.is_relative()) file = dir_ / file;
      std::error_code ec;
      if (std::filesystem::is_directory(file, ec))
        fail(v, k,
             "'" + file.string() +
                 "' is a folder, not a mesh; give an .stl, .obj or .vtp file (paths are "
                 "relative to the scene file)");
      try {
        ShapePtr mesh = make_mesh(file.string());
        meshes.push_back({v, k, file.string(), mesh->bounds()});
        std::ifstream in(file, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        checksum = fnv1a(checksum, bytes.data(), bytes.size());
        return mesh;
      } catch (const Error& e) {
        fail(v, k, std::string(e.what()) + " (paths are relative to the scene file)");
      }
    }
    fail(n.begin()->first, key, "unknown shape '" + kind + "'; use one of " + known);
  }

  // {type: fixed}, {type: constant, velocity: [..]} or {type: sinusoidal, amplitude: [..], period: T,
  // phase: degrees (optional)}.
  MotionSpec motion(const YAML::Node& m, const std::string& key) {
    if (m["type"].IsDefined() && m["type"].IsScalar() && m["type"].Scalar() == "free") return free_motion(m, key);
    only_keys(m, key,
              {"type", "velocity", "amplitude", "period", "phase", "rotation", "file", "centre", "center", "axis"});
    MotionSpec spec;
    if (m["type"].IsDefined() && m["type"].IsScalar() && m["type"].Scalar() == "table") {
      table_motion(m, key, spec);
      return spec;
    }
    for (const char* name : {"file", "centre", "center", "axis"})
      if (m[name].IsDefined()) fail(m[name], key + "." + name, "belongs to type: table; remove it");
    if (m["rotation"].IsDefined()) rotation(m["rotation"], key + ".rotation", spec);
    const YAML::Node type = m["type"];
    if (!type.IsDefined() && spec.spin != "fixed") return spec;  // a rotation alone
    if (!type.IsDefined() || !type.IsScalar())
      fail(m, key, "has no type; give type: constant (with velocity) or sinusoidal (with amplitude and period)");
    spec.type = type.Scalar();
    auto vector = [&](const char* name, std::array<double, 3>& out) {
      if (!m[name].IsDefined()) fail(m, key, "of type " + spec.type + " needs " + name + ": [...]");
      const Point3 v = point(m[name], key + "." + name);
      out = {v[0], v[1], v[2]};
    };
    auto refuse_extra = [&](std::initializer_list<const char*> extra) {
      for (const char* name : extra)
        if (m[name].IsDefined()) fail(m[name], key + "." + name, "does not apply to type " + spec.type + "; remove it");
    };
    if (spec.type == "fixed") {
      refuse_extra({"velocity", "amplitude", "period", "phase"});
    } else if (spec.type == "constant") {
      vector("velocity", spec.velocity);
      refuse_extra({"amplitude", "period", "phase"});
    } else if (spec.type == "sinusoidal") {
      vector("amplitude", spec.amplitude);
      if (!m["period"].IsDefined()) fail(m, key, "of type sinusoidal needs period: T");
      spec.period = number(m["period"], key + ".period");
      if (!(spec.period > 0))
        fail(m["period"], key + ".period", "is " + number_text(spec.period) + "; give a positive period");
      if (m["phase"].IsDefined()) spec.phase_degrees = number(m["phase"], key + ".phase");
      refuse_extra({"velocity"});
    } else {
      fail(type, key + ".type", "is '" + spec.type + "'; give fixed, constant, sinusoidal or table");
    }
    return spec;
  }

  // A free body's density: or mass: (one of them, positive), keys of its region beside its motion.
  void body_mass(const YAML::Node& n, const std::string& key, MotionSpec& motion) const {
    for (const char* name : {"density", "mass"}) {
      const YAML::Node v = n[name];
      if (!v.IsDefined()) continue;
      if (motion.type != "free")
        fail(v, key + "." + name, "is given for a body the fluid does not move; add motion: {type: free} or remove it");
      const double x = number(v, key + "." + name);
      if (!(x > 0)) fail(v, key + "." + name, "is " + number_text(x) + "; give a positive " + name);
      (name[0] == 'd' ? motion.density : motion.mass) = x;
    }
    if (motion.type != "free") return;
    if (n["density"].IsDefined() && n["mass"].IsDefined())
      fail(n["mass"], key + ".mass", "is given with density:; give one of them");
    if (!n["density"].IsDefined() && !n["mass"].IsDefined())
      fail(n["motion"], key + ".motion", "makes a free body with no mass; add density: (kg/m^3) or mass: beside it");
  }

  // {type: free, velocity: [..], rate: deg/s ([..] in 3D), fixed: [x, y, z, rotation, rx, ry, rz],
  // hinge: [..](, axis: [..] in 3D)}: a body the fluid moves (src/boundary/free_body.hpp); its density
  // or mass is a key of the region.
  MotionSpec free_motion(const YAML::Node& m, const std::string& key) const {
    only_keys(m, key, {"type", "velocity", "rate", "fixed", "hinge", "axis"});
    MotionSpec spec;
    spec.type = "free";
    if (m["velocity"].IsDefined()) {
      const Point3 v = point(m["velocity"], key + ".velocity");
      spec.velocity = {v[0], v[1], v[2]};
    }
    if (const YAML::Node r = m["rate"]; r.IsDefined()) {
      if (dim == 2) {
        if (!r.IsScalar()) fail(r, key + ".rate", "is not a number; a 2D body turns about z at rate: degrees/s");
        spec.rate3_degrees[2] = number(r, key + ".rate");
      } else {
        const Point3 w = point(r, key + ".rate");
        spec.rate3_degrees = {w[0], w[1], w[2]};
      }
    }
    if (const YAML::Node f = m["fixed"]; f.IsDefined()) {
      if (!f.IsSequence() || f.size() == 0)
        fail(f, key + ".fixed",
             "is not a list of axes; give e.g. fixed: [x, rotation] (x, y, z, rotation, rx, ry, rz)");
      for (const auto& item : f) {
        const std::string a = item.IsScalar() ? item.Scalar() : "";
        const std::size_t t = std::string("xyz").find(a),
                          r = a.size() == 2 && a[0] == 'r' ? std::string("xyz").find(a[1]) : std::string::npos;
        if (a.size() == 1 && t < static_cast<std::size_t>(dim)) spec.fixed_translation[t] = true;
        else if (a == "rotation") spec.fixed_rotation = {true, true, true};
        else if (dim == 3 && r != std::string::npos) spec.fixed_rotation[r] = true;
        else
          fail(item, key + ".fixed",
               "names '" + a + "', which is no axis; give " +
                   (dim == 2 ? "x, y or rotation" : "x, y, z, rotation, rx, ry or rz"));
      }
    }
    if (const YAML::Node h = m["hinge"]; h.IsDefined()) {
      if (m["fixed"].IsDefined())
        fail(h, key + ".hinge", "is given with fixed:; a hinged body only turns about it, remove one");
      const Point3 p = point(h, key + ".hinge");
      spec.hinged = true, spec.hinge = {p[0], p[1], p[2]};
      if (dim == 3) {
        if (!m["axis"].IsDefined()) fail(m, key, "has a hinge but no axis; a 3D hinge needs axis: [x, y, z]");
        spec.axis = unit_axis(m["axis"], key + ".axis");
      }
    }
    if (m["axis"].IsDefined() && (dim == 2 || !m["hinge"].IsDefined()))
      fail(m["axis"], key + ".axis",
           dim == 2 ? "is given in a 2D scene, where bodies turn about z; remove it"
                    : "is given without a hinge; remove it or add hinge: [x, y, z]");
    return spec;
  }

  // {type: table, file: motion.csv(, centre: [..], axis: [..])}: a CSV with the header t,x,y(,z)(,angle)
  // (angle in degrees, about the axis through centre), t increasing; the path relative to the scene file.
  void table_motion(const YAML::Node& m, const std::string& key, MotionSpec& spec) {
    for (const char* name : {"velocity", "amplitude", "period", "phase", "rotation"})
      if (m[name].IsDefined()) fail(m[name], key + "." + name, "does not apply to type table; remove it");
    if (!m["file"].IsDefined() || !m["file"].IsScalar()) fail(m, key, "of type table needs file: motion.csv");
    std::filesystem::path file(m["file"].Scalar());
    if (file.is_relative()) file = dir_ / file;
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
      fail(m["file"], key + ".file",
           "'" + file.string() +
               "' is a folder, not a file; give the motion table, a CSV with the header t,x,y "
               "(paths are relative to the scene file)");
    std::ifstream in(file, std::ios::binary);
    if (!in)
      fail(m["file"], key + ".file",
           "cannot be opened ('" + file.string() + "'; paths are relative to the scene file)");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    checksum = fnv1a(checksum, text.data(), text.size());
    std::istringstream lines(text);
    std::string line, where = key + ".file '" + file.string() + "'";
    auto cells = [](const std::string& l) {
      std::vector<std::string> out;
      std::stringstream row(l);
      for (std::string cell; std::getline(row, cell, ',');) {
        const auto a = cell.find_first_not_of(" \t\r"), b = cell.find_last_not_of(" \t\r");
        out.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
      }
      return out;
    };
    std::getline(lines, line);
    const std::vector<std::string> header = cells(line);
    std::vector<std::string> want = {"t", "x", "y"};
    if (dim == 3) want.push_back("z");
    const bool with_angle = header.size() == want.size() + 1 && header.back() == "angle";
    if (with_angle) want.push_back("angle");
    if (header != want)
      fail(m["file"], where,
           std::string("has the header '") + line + "'; give t,x,y" + (dim == 3 ? ",z" : "") +
               " (and ,angle in degrees) in the first line");
    for (int row = 2; std::getline(lines, line); ++row) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::vector<std::string> v = cells(line);
      if (v.size() != want.size())
        fail(m["file"], where,
             "row " + std::to_string(row) + " has " + std::to_string(v.size()) + " values; give " +
                 std::to_string(want.size()));
      std::vector<double> x;
      for (const std::string& cell : v) {
        char* end = nullptr;
        const double value = std::strtod(cell.c_str(), &end);
        if (cell.empty() || *end != '\0' || !std::isfinite(value))
          fail(m["file"], where, "row " + std::to_string(row) + ": '" + cell + "' is not a finite number");
        x.push_back(value);
      }
      if (!spec.table_t.empty() && !(x[0] > spec.table_t.back()))
        fail(m["file"], where, "row " + std::to_string(row) + ": t = " + number_text(x[0]) + " does not increase");
      spec.table_t.push_back(x[0]);
      for (int a = 0; a < dim; ++a) spec.table_x[a].push_back(x[1 + a]);
      if (with_angle) spec.table_angle_degrees.push_back(x.back());
    }
    if (spec.table_t.size() < 2)
      fail(m["file"], where, "holds fewer than two rows; give the motion at two times at least");
    spec.type = "table";
    if (!with_angle) return;
    spec.spin = "table";
    rotation_axis(m, key, spec, "turns the body (an angle column) but has no centre; give centre: [...]");
  }

  // An axis's direction, made unit.
  std::array<double, 3> unit_axis(const YAML::Node& n, const std::string& key) const {
    const Point3 axis = point(n, key);
    if (axis.norm() == 0) fail(n, key, "is zero; give the direction of the axis");
    const Point3 unit = axis.normalized();
    return {unit[0], unit[1], unit[2]};
  }

  // The centre the rotation's axis goes through and, in 3D, its direction (none in 2D: about z).
  void rotation_axis(const YAML::Node& r, const std::string& key, MotionSpec& spec,
                     const std::string& no_centre) const {
    const YAML::Node c = r["centre"].IsDefined() ? r["centre"] : r["center"];
    if (!c.IsDefined()) fail(r, key, no_centre);
    const Point3 centre = point(c, key + ".centre");
    spec.centre = {centre[0], centre[1], centre[2]};
    if (dim == 3) {
      if (!r["axis"].IsDefined()) fail(r, key, "has no axis; a 3D rotation needs axis: [x, y, z]");
      spec.axis = unit_axis(r["axis"], key + ".axis");
    } else if (r["axis"].IsDefined()) {
      fail(r["axis"], key + ".axis", "is given in a 2D scene, where bodies turn about z; remove it");
    }
  }

  // {type: constant, rate: deg/s, centre: [..](, axis: [..] in 3D)} or {type: sinusoidal, amplitude:
  // degrees, period: T, phase: degrees (optional), centre, axis}.
  void rotation(const YAML::Node& r, const std::string& key, MotionSpec& spec) const {
    only_keys(r, key, {"type", "rate", "amplitude", "period", "phase", "centre", "center", "axis"});
    const YAML::Node type = r["type"];
    if (!type.IsDefined() || !type.IsScalar())
      fail(r, key, "has no type; give type: constant (with rate) or sinusoidal (with amplitude and period)");
    spec.spin = type.Scalar();
    auto scalar = [&](const char* name, double& out) {
      if (!r[name].IsDefined()) fail(r, key, "of type " + spec.spin + " needs " + name);
      out = number(r[name], key + "." + name);
    };
    if (spec.spin == "constant") {
      scalar("rate", spec.rate_degrees);
    } else if (spec.spin == "sinusoidal") {
      scalar("amplitude", spec.angle_degrees);
      scalar("period", spec.spin_period);
      if (!(spec.spin_period > 0))
        fail(r["period"], key + ".period", "is " + number_text(spec.spin_period) + "; give a positive period");
      if (r["phase"].IsDefined()) spec.spin_phase_degrees = number(r["phase"], key + ".phase");
    } else {
      fail(type, key + ".type", "is '" + spec.spin + "'; give constant or sinusoidal");
    }
    rotation_axis(r, key, spec, "has no centre; give the point the axis goes through: centre: [...]");
  }

  // g: the scene's gravity, for a hydrostatic start.
  // A shape written inline, `shape: NAME` with its parameters beside it in the region (`shape: circle,
  // centre: [..], radius: R`; `shape: difference, of: [..]`; box: bounds, polygon: vertices, mesh: file),
  // as the nested form {NAME: value}.
  YAML::Node inline_shape(const YAML::Node& n, const std::string& key) const {
    const std::string kind = n["shape"].Scalar();
    YAML::Node nested;
    if (kind == "circle" || kind == "sphere" || kind == "cylinder" || kind == "half_space") {
      YAML::Node params(YAML::NodeType::Map);
      for (const auto& item : n)
        if (kInlineParameters.count(item.first.Scalar())) params[item.first.Scalar()] = item.second;
      nested[kind] = params;
      return nested;
    }
    const char* value = kind == "box" ? "bounds" : kind == "polygon" ? "vertices" : kind == "mesh" ? "file" : "of";
    if (!n[value].IsDefined())
      fail(n, key, "has shape: " + kind + " but no " + value + "; add " + value + ": ... beside it");
    nested[kind] = n[value];
    return nested;
  }

  // {from: [x, y], to: [x, y], thickness: T (default 0)}: a plate's mid-line and thickness; its outline,
  // a rectangle, is the region's shape for the bounds and the body's surface.
  void read_plate(const YAML::Node& v, const std::string& k, Region& r) {
    if (dim != 2)
      fail(v, k,
           "is a plate, which only 2D scenes have; in 3D give the solid at least the kernel's support in thickness");
    if (!v["from"].IsDefined() || !v["to"].IsDefined())
      fail(v, k, "is a plate without from and to; give its mid-line: from: [x, y], to: [x, y]");
    r.is_plate = true;
    r.plate.a = point(v["from"], k + ".from");
    r.plate.b = point(v["to"], k + ".to");
    if ((r.plate.b - r.plate.a).norm() == 0)
      fail(v["to"], k + ".to", "is the plate's from point; give the plate a length");
    if (v["thickness"].IsDefined()) {
      r.plate.thickness = number(v["thickness"], k + ".thickness");
      if (!(r.plate.thickness >= 0))
        fail(v["thickness"], k + ".thickness", "is negative; give a thickness of 0 or more");
    }
    const Eigen::Vector2d a = r.plate.a.head<2>(), b = r.plate.b.head<2>(), e = (b - a).normalized();
    const Eigen::Vector2d n(-e[1], e[0]);
    const double half = std::max(0.5 * r.plate.thickness, 1e-12);
    r.shape = make_polygon({a - half * n, b - half * n, b + half * n, a + half * n});
  }

  // Whether region n is an inlet or an outlet (role: inlet / outlet).
  static bool is_open_boundary(const YAML::Node& n) {
    const YAML::Node role = n.IsMap() ? n["role"] : YAML::Node();
    return role.IsDefined() && role.IsScalar() && (role.Scalar() == "inlet" || role.Scalar() == "outlet");
  }

  // {role: inlet, side: x-, velocity: [u, v] or {parabolic: U_max}, ramp: T} or {role: outlet, side: x+,
  // pressure: p}: the side and the condition; the buffer's place and section come with the lattice.
  // Where it lies: on a side of the box (the box given, the axis not periodic, the side free), with a
  // buffer `depth` deep.
  OpenBoundarySpec open_boundary(const YAML::Node& n, const std::string& key, bool has_box, const Point3& box_lo,
                                 const Point3& box_hi, const std::vector<double>& periodic,
                                 const std::vector<OpenBoundarySpec>& others, double depth) const {
    OpenBoundarySpec b = open_boundary_condition(n, key);
    const std::string side = std::string(1, "xyz"[b.axis]) + (b.side < 0 ? "-" : "+");
    if (!has_box) fail(n, key, "lies on a side of the box, and the scene has none; add box: [...]");
    if (periodic[b.axis])
      fail(n["side"], key + ".side", "is side " + side + " of a periodic axis; make the axis not periodic");
    for (const OpenBoundarySpec& o : others)
      if (o.axis == b.axis && o.side == b.side)
        fail(n["side"], key + ".side", "is side " + side + " a second time; one inlet or outlet a side");
    b.plane = b.side < 0 ? box_lo[b.axis] : box_hi[b.axis];
    b.depth = depth;
    return b;
  }

  OpenBoundarySpec open_boundary_condition(const YAML::Node& n, const std::string& key) const {
    OpenBoundarySpec b;
    b.inlet = n["role"].Scalar() == "inlet";
    if (b.inlet) only_keys(n, key, {"role", "side", "velocity", "ramp"});
    else only_keys(n, key, {"role", "side", "pressure"});
    const YAML::Node side = n["side"];
    const std::string sides = dim == 2 ? "x-, x+, y- or y+" : "x-, x+, y-, y+, z- or z+";
    if (!side.IsDefined()) fail(n, key, "has no side; add side: one of " + sides + " (the box's side it lies on)");
    const std::string s = side.IsScalar() ? side.Scalar() : "";
    const std::size_t axis = s.size() == 2 ? std::string("xyz").find(s[0]) : std::string::npos;
    if (axis == std::string::npos || axis >= static_cast<std::size_t>(dim) || (s[1] != '-' && s[1] != '+'))
      fail(side, key + ".side", "is not a side of the box; give one of " + sides);
    b.axis = static_cast<int>(axis), b.side = s[1] == '-' ? -1 : 1;
    if (!b.inlet) {
      if (n["pressure"].IsDefined()) b.pressure = number(n["pressure"], key + ".pressure");
      return b;
    }
    const YAML::Node v = n["velocity"];
    if (!v.IsDefined())
      fail(n, key, "is an inlet without a velocity; add velocity: [u, v] or velocity: {parabolic: U_max}");
    if (v.IsMap()) {
      only_keys(v, key + ".velocity", {"parabolic"});
      if (!v["parabolic"].IsDefined())
        fail(v, key + ".velocity", "has no parabolic: U_max; give the profile's peak speed");
      b.peak = number(v["parabolic"], key + ".velocity.parabolic");
      if (!(b.peak > 0))
        fail(v["parabolic"], key + ".velocity.parabolic",
             "is " + number_text(b.peak) + "; the peak speed into the box must be positive");
    } else {
      const Point3 u = point(v, key + ".velocity");
      for (int a = 0; a < 3; ++a) b.velocity[a] = u[a];
      if (!(-b.side * u[b.axis] > 0))
        fail(v, key + ".velocity",
             "points out of the box or along its side (" + std::string(1, "xyz"[b.axis]) + " component " +
                 number_text(u[b.axis]) + " at side " + s + "); an inlet's velocity must point into the box");
    }
    if (n["ramp"].IsDefined()) {
      b.ramp = number(n["ramp"], key + ".ramp");
      if (!(b.ramp >= 0)) fail(n["ramp"], key + ".ramp", "is negative; give the time to full speed, 0 or more");
    }
    return b;
  }

  Region region(const YAML::Node& n, const std::string& key, std::vector<std::string>& bodies, const Point3& g) {
    only_keys(n, key, {"role",   "shape",    "velocity", "pressure",  "motion",  "slip",   "name", "of",
                       "bounds", "vertices", "file",     "centre",    "center",  "radius", "ends", "point",
                       "normal", "from",     "to",       "thickness", "density", "mass"});
    Region r;
    const YAML::Node role = n["role"];
    if (!role.IsDefined())
      fail(n, key, "has no role; add role: fluid, wall, inlet, outlet, or role: body with name: NAME");
    std::string body;
    if (role.IsScalar() && role.Scalar() == "fluid") r.role = Role::Fluid;
    else if (role.IsScalar() && role.Scalar() == "wall") r.role = Role::Wall;
    else if (role.IsScalar() && role.Scalar() == "body") {
      if (!n["name"].IsDefined() || !n["name"].IsScalar() || n["name"].Scalar().empty())
        fail(n, key, "is a body without a name; add name: NAME");
      body = n["name"].Scalar();
    } else if (role.IsMap() && role.size() == 1 && role["body"].IsDefined() && role["body"].IsScalar() &&
               !role["body"].Scalar().empty()) {
      body = role["body"].Scalar();
    } else {
      fail(role, key + ".role", "is not fluid, wall, body, inlet or outlet; give one of those");
    }
    if (!body.empty()) {
      r.role = Role::Body;
      if (body.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") !=
          std::string::npos)
        fail(n, key,
             "names body '" + body + "'; a body's name takes letters, digits and _ (it names timeseries columns)");
      if (body == "walls") fail(n, key, "names a body 'walls', the name of the walls' own force columns; rename it");
      r.body = static_cast<int>(std::find(bodies.begin(), bodies.end(), body) - bodies.begin());
      if (r.body == static_cast<int>(bodies.size())) bodies.push_back(body);
    } else if (n["name"].IsDefined()) {
      fail(n["name"], key + ".name", "names a region that is no body; only role: body takes a name");
    }
    const YAML::Node s = n["shape"];
    if (!s.IsDefined()) fail(n, key, "has no shape; add shape: {box: [...]} or another shape");
    const bool inline_form = s.IsScalar();
    for (const auto& item : n)
      if (kInlineParameters.count(item.first.Scalar()) && !inline_form)
        fail(item.first, key,
             "gives " + item.first.Scalar() + " beside a nested shape; write shape: NAME for the inline form");
    const bool plate =
        inline_form ? s.Scalar() == "plate" : s.IsMap() && s.size() == 1 && s.begin()->first.Scalar() == "plate";
    if (plate) {
      read_plate(inline_form ? n : s["plate"], key + ".shape", r);
      if (r.role == Role::Fluid) fail(n, key, "is a plate of fluid; a plate is a wall or a body (role: wall)");
      if (n["motion"].IsDefined())
        fail(n["motion"], key + ".motion",
             "moves a plate; plates are fixed (a body of at least the kernel's support in thickness can move)");
    } else {
      r.shape = shape(inline_form ? inline_shape(n, key) : s, key + ".shape");
    }
    for (const char* value : {"velocity", "pressure"})
      if (r.role != Role::Fluid && n[value].IsDefined())
        fail(n[value], key + "." + value,
             "is given for a wall; walls are at rest with no pressure of their own: "
             "remove it or make the region's role fluid");
    if (n["velocity"].IsDefined()) r.velocity = point(n["velocity"], key + ".velocity");
    if (const YAML::Node slip = n["slip"]; slip.IsDefined()) {
      if (r.role == Role::Fluid)
        fail(slip, key + ".slip", "is given for fluid; only walls and bodies have a slip condition");
      if (!slip.IsScalar() || (slip.Scalar() != "free" && slip.Scalar() != "no_slip"))
        fail(slip, key + ".slip", "is not free or no_slip; give one of those");
      r.free_slip = slip.Scalar() == "free";
    }
    if (const YAML::Node m = n["motion"]; m.IsDefined()) {
      if (r.role != Role::Body)
        fail(m, key + ".motion", "is given for a region that is no body; only role: body moves (fixed walls do not)");
      r.motion = motion(m, key + ".motion");
    }
    body_mass(n, key, r.motion);
    const YAML::Node p = n["pressure"];
    r.hydrostatic = p.IsDefined() && p.IsScalar() && p.Scalar() == "hydrostatic";
    if (!r.hydrostatic && p.IsDefined()) r.pressure = number(p, key + ".pressure");
    if (r.hydrostatic) {
      if (g.norm() == 0)
        fail(p, key + ".pressure", "is hydrostatic but the scene has no gravity; add physics: {gravity: [...]}");
      r.top = r.shape->highest(-g.normalized());
      if (!std::isfinite(r.top))
        fail(p, key + ".pressure", "is hydrostatic but the region has no top along -g; bound its shape");
    }
    return r;
  }

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
std::vector<double> periodic_axes(const Reader& r, const YAML::Node& n) {
  std::vector<double> flags(r.dim, 0.0);
  if (n.IsScalar() && n.Scalar() == "none") return flags;
  std::vector<YAML::Node> axes;
  if (n.IsScalar()) axes.push_back(n);
  else if (n.IsSequence())
    for (const auto& a : n) axes.push_back(a);
  for (const YAML::Node& a : axes) {
    const std::size_t k = a.IsScalar() && a.Scalar().size() == 1 ? std::string("xyz").find(a.Scalar()) : 3;
    if (k >= static_cast<std::size_t>(r.dim))
      r.fail(a, "periodic",
             std::string("names no axis of this ") + std::to_string(r.dim) + "D scene; give none, x or " +
                 (r.dim == 2 ? "[x, y]" : "[x, y, z]"));
    flags[k] = 1.0;
  }
  if (axes.empty()) r.fail(n, "periodic", "is empty; give none, x or [x, y]");
  return flags;
}

// prefix: where the keys stand, "physics." or "" (at the top), for the messages.
void read_physics(Reader& r, const YAML::Node& n, SceneFile& s, const std::string& prefix) {
  r.only_keys(n, "physics", {"gravity", "nu", "rho0", "U", "free_surface", "t_end"});
  if (n["gravity"].IsDefined())
    s.field["gravity"] = r.numbers(n["gravity"], prefix + "gravity", r.dim, r.dim == 2 ? "[gx, gy]" : "[gx, gy, gz]");
  // Checked here, where the file can be named; the options that override them are checked by the case.
  struct Limit {
    const char* name;
    bool zero_allowed;
  };
  for (const Limit l : {Limit{"nu", true}, Limit{"rho0", false}, Limit{"U", false}, Limit{"t_end", false}}) {
    if (!n[l.name].IsDefined()) continue;
    const double v = r.number(n[l.name], prefix + l.name);
    if (v < 0 || (v == 0 && !l.zero_allowed))
      r.fail(n[l.name], prefix + l.name,
             "is " + number_text(v) + "; give a " + (l.zero_allowed ? "non-negative" : "positive") + " number");
    s.field[l.name] = {v};
  }
  if (const YAML::Node f = n["free_surface"]; f.IsDefined()) {
    bool on = false;
    if (!f.IsScalar() || !YAML::convert<bool>::decode(f, on)) {
      const double v = r.number(f, prefix + "free_surface");
      if (v != 0 && v != 1) r.fail(f, prefix + "free_surface", "is " + number_text(v) + "; give true or false");
      on = v == 1;
    }
    s.field["free_surface"] = {on ? 1.0 : 0.0};
  }
}

// A mesh drawn in other units than the scene (millimetres in a scene of metres) is far larger or
// smaller than the scene's box: refused naming the likely unit, before its surface is sampled at the
// scene's spacing (a 400-wide cube refined to dx/4 exhausts any memory).
void check_mesh_units(const Reader& r, const Point3& box_lo, const Point3& box_hi) {
  double box = 0;
  for (int a = 0; a < r.dim; ++a) box = std::max(box, box_hi[a] - box_lo[a]);
  for (const Reader::MeshRead& m : r.meshes) {
    double size = 0;
    for (int a = 0; a < r.dim; ++a) size = std::max(size, m.bounds.hi[a] - m.bounds.lo[a]);
    const double ratio = size / box;
    if (ratio <= 100) continue;
    // The likely unit: the smallest of the usual ones (as factors against the scene's) that brings the
    // mesh within the box.
    struct Unit {
      const char* name;
      double per_metre;
    };
    static const Unit units[] = {{"inches", 39.37}, {"centimetres", 1e2}, {"millimetres", 1e3}, {"micrometres", 1e6}};
    const Unit* best = nullptr;
    for (const Unit& u : units)
      if (!best && size / u.per_metre <= box) best = &u;
    r.fail(m.at, m.key,
           "'" + m.file + "' spans " + number_text(size) + ", " + number_text(ratio) + " times the scene's box (" +
               number_text(box) + "); " +
               (best ? "is it in " + std::string(best->name) + "? scale it by " + number_text(1 / best->per_metre)
                     : std::string("scale it")) +
               " to the scene's units");
  }
}

// A fluid region or a body that got no particle would silently be missing from the run (a body smaller
// than the spacing, outside the box, or thinner than dx; fluid beyond the box): refused, naming it. One
// that got under a quarter of what its kept area (volume) holds, area / dx^D, lost most of its shape
// between the lattice's rows (thin parts): refused too. `kept` is that area per region: its shape
// within the box, less what the regions after it cover.
void check_regions_filled(const Reader& r, const std::vector<Region>& fluids, const std::vector<Region>& solids,
                          const std::vector<Region>& plates, const std::vector<std::string>& bodies,
                          std::map<const Region*, long>& taken, std::map<const Region*, double>& kept, double dx) {
  const std::string fix = " at dx = " + number_text(dx) +
                          ": it is smaller or thinner than the spacing, outside the box, or covered by the "
                          "regions after it; refine (a larger -nx), enlarge it or move it into the box";
  const double cell = std::pow(dx, r.dim);
  const std::string measure = r.dim == 2 ? "area" : "volume";
  auto too_few = [&](const Region& at, const std::string& what, long n, double area) {
    const double expected = area / cell;
    if (n > 0 && n < 0.25 * expected)
      r.fail(at.at, at.key,
             what + " holds " + std::to_string(n) + " particle" + (n == 1 ? "" : "s") + " at dx = " + number_text(dx) +
                 ", under a quarter of the " + number_text(std::round(expected)) + " its " + measure + " (" +
                 number_text(area) +
                 ", less what the regions after it cover) holds: parts of it thinner than "
                 "the spacing are lost between the lattice's rows; refine (a larger -nx) or thicken them");
  };
  for (const Region& f : fluids) {
    if (taken[&f] == 0) r.fail(f.at, f.key, "is a fluid region that holds no particle" + fix);
    too_few(f, "is a fluid region that", taken[&f], kept[&f]);
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    long n = 0;
    double area = 0;
    const Region* first = nullptr;
    bool plate = false;
    for (const Region& w : solids)
      if (w.body == static_cast<int>(b)) n += taken[&w], area += kept[&w], first = first ? first : &w;
    for (const Region& p : plates) plate = plate || p.body == static_cast<int>(b);  // its layers come later
    if (n == 0 && first && !plate)
      r.fail(first->at, first->key, "is body '" + bodies[b] + "', which holds no particle" + fix);
    if (first && !plate) too_few(*first, "is body '" + bodies[b] + "', which", n, area);
  }
}

// The area (volume) of the region's shape within [lo, hi] that the region keeps (holds(x)), from a
// Halton sample of its bounds: 0 where too few sample points fall in it to tell.
template <class Holds>
double kept_measure(const Shape& shape, const Point3& box_lo, const Point3& box_hi, int dim, const Holds& holds) {
  const Bounds b = shape.bounds();
  Point3 lo = Point3::Zero(), hi = Point3::Zero();
  double volume = 1;
  for (int a = 0; a < dim; ++a) {
    lo[a] = std::max(b.lo[a], box_lo[a]), hi[a] = std::min(b.hi[a], box_hi[a]);
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(hi[a] > lo[a])) return 0.0;
    volume *= hi[a] - lo[a];
  }
  constexpr int kSamples = 1024, kEnough = 16;
  const int base[3] = {2, 3, 5};
  int hits = 0;
  for (int k = 1; k <= kSamples; ++k) {
    Point3 x = Point3::Zero();
    for (int a = 0; a < dim; ++a) {
      double f = 1.0, u = 0.0;
      for (int i = k; i > 0; i /= base[a]) f /= base[a], u += f * (i % base[a]);
      x[a] = lo[a] + u * (hi[a] - lo[a]);
    }
    hits += holds(x);
  }
  return hits >= kEnough ? volume * hits / kSamples : 0.0;
}

// Lattice points (i + 1/2) dx of one axis within [lo, hi] ([lo, hi) when periodic), as index range.
std::pair<long, long> lattice_range(double lo, double hi, double dx, bool periodic) {
  const long first = static_cast<long>(std::ceil(lo / dx - 0.5 - kOnSurface));
  const long last = periodic ? static_cast<long>(std::ceil(hi / dx - 0.5 - kOnSurface)) - 1
                             : static_cast<long>(std::floor(hi / dx - 0.5 + kOnSurface));
  return {first, last};
}

}  // namespace

bool is_yaml_scene(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".yaml" || ext == ".yml";
}

int yaml_scene_dimension(const std::string& path) {
  Reader r(path);
  r.parse();
  return r.dim;
}

namespace {
// A plate's unit direction from a to b and its normal (the +1 face's side), in the xy plane.
std::pair<Point3, Point3> plate_frame(const PlateSpec& p) {
  const Point3 e = (p.b - p.a).normalized();
  return {e, Point3(-e[1], e[0], 0.0)};
}

// Whether lattice point x lies within a plate or closer to its faces than half a spacing: no fluid
// there (the first fluid particles stand dx/2 off each face, as beside any wall).
bool in_plate_gap(const std::vector<Region>& plates, const Point3& x, double dx) {
  const double on = kOnSurface * dx;
  for (const Region& r : plates) {
    const auto [e, n] = plate_frame(r.plate);
    const double along = (x - r.plate.a).dot(e), length = (r.plate.b - r.plate.a).norm();
    const double gap = 0.5 * (r.plate.thickness + dx) - on;
    if (std::abs((x - r.plate.a).dot(n)) < gap && along > -gap && along < length + gap) return true;
  }
  return false;
}

// Each face's wall layers: rows along the plate's part within the box, spaced as near dx as divides
// that part (on an axis-aligned plate, the lattice's own points), from the face inwards through the
// plate and on, layer after layer, into the other side; each particle labelled with its face (+1 the
// side the normal points to, -1 the other) for the neighbour lists (src/neighbours/screens.hpp).
// Where an end stands on a wall (`solids`), the layers and the screen go on through that wall, as
// deep as its layers: a wall particle beside the plate's foot would otherwise see the fluid of both
// sides, and its pressure, extrapolated from both, let the two sides' pressures meet under the plate
// (still water at two levels either side of a plate lost a fifth of its force); screened without the
// layers, the fluid in the corner would miss the wall beyond the plate from its support
// (docs/verification/thin_plate.md).
void add_plate_layers(const std::vector<Region>& plates, const std::vector<Region>& solids, int wall_layers, double dx,
                      const Point3& box_lo, const Point3& box_hi, YamlScene& out) {
  SceneFile& s = out.file;
  out.plate_face.resize(s.x.size(), 0);
  auto in_a_wall = [&](const Point3& x) {
    for (const Region& w : solids)
      if (w.shape->distance(x) <= 0.5 * dx) return true;
    return false;
  };
  for (std::size_t k = 0; k < plates.size(); ++k) {
    const PlateSpec& p = plates[k].plate;
    const auto [e, n] = plate_frame(p);
    const double length = (p.b - p.a).norm();
    // The part of the mid-line within the box: [s0, s1] along it.
    double s0 = 0.0, s1 = length;
    for (int a = 0; a < 2; ++a) {
      if (std::abs(e[a]) < 1e-14) continue;
      double t0 = (box_lo[a] - p.a[a]) / e[a], t1 = (box_hi[a] - p.a[a]) / e[a];
      if (t0 > t1) std::swap(t0, t1);
      s0 = std::max(s0, t0), s1 = std::min(s1, t1);
    }
    const long rows = std::lround((s1 - s0) / dx);
    if (rows < 1) continue;  // no layers: no plate for the screens, whose indices the labels below use
    const double step = (s1 - s0) / static_cast<double>(rows);
    const long before = s0 == 0.0 && in_a_wall(p.a) ? wall_layers : 0,
               after = s1 == length && in_a_wall(p.b) ? wall_layers : 0;
    for (int face : {1, -1})
      for (int layer = 0; layer < wall_layers; ++layer)
        for (long m = -before; m < rows + after; ++m) {
          const Point3 x = p.a + (s0 + (m + 0.5) * step) * e + (face * (0.5 * p.thickness - (layer + 0.5) * dx)) * n;
          bool inside = true;
          for (int a = 0; a < 2; ++a) inside = inside && x[a] >= box_lo[a] && x[a] <= box_hi[a];
          if (!inside) continue;
          s.x.push_back({x[0], x[1], 0.0});
          s.v.push_back({0.0, 0.0, 0.0}), s.p.push_back(0.0), s.kind.push_back(kSceneFixedWall);
          out.body.push_back(plates[k].body), out.free_slip.push_back(plates[k].free_slip);
          out.plate_face.push_back(static_cast<std::int8_t>(face * (static_cast<int>(out.plates.size()) + 1)));
        }
    const Point3 a = p.a - (before * step) * e, b = p.b + (after * step) * e;
    out.plates.push_back({a[0], a[1], b[0], b[1]});
  }
}

// A plate's outline added to a body's surface: its two faces, each in segments no longer than
// `step`, and its ends when it has a thickness. The outline is closed, and each face's pressure is
// fitted from the fluid on its own side (src/sph/surface_force.hpp): a zero-thickness plate's faces
// lie on one line and still take their sides' pressures.
void add_outline(const PlateSpec& p, double step, SurfaceMesh& surface) {
  const auto [e, n] = plate_frame(p);
  const Point3 h = 0.5 * p.thickness * n;
  const long pieces = std::max(1L, static_cast<long>(std::ceil((p.b - p.a).norm() / step)));
  const bool first_outline = surface.cells.empty();
  surface.lines = true;
  auto add_point = [&](const Point3& x) {
    surface.points.push_back({x[0], x[1], 0.0});
    return static_cast<long>(surface.points.size()) - 1;
  };
  // Round the outline a - h -> b - h -> b + h -> a + h -> a - h: each segment's normal, (b - a) turned
  // clockwise, points out of the plate.
  const Point3 corners[4] = {p.a - h, p.b - h, p.b + h, p.a + h};
  const long start = add_point(corners[0]);
  long last = start;
  for (int c = 0; c < 4; ++c) {
    const bool face = c % 2 == 0;
    if (!face && p.thickness <= 0.0) {  // an end of no length: no face, the points coincide
      if (c == 3) surface.cells.back()[1] = start;
      continue;
    }
    const long n_pieces = face ? pieces : 1;
    for (long m = 1; m <= n_pieces; ++m) {
      const bool closes = c == 3 && m == n_pieces;
      const Point3 x = corners[c] + (static_cast<double>(m) / n_pieces) * (corners[(c + 1) % 4] - corners[c]);
      const long next = closes ? start : add_point(x);
      surface.cells.push_back({last, next});
      last = next;
    }
  }
  // A body of plates alone is closed; with other parts it is as closed as their surface was.
  if (first_outline) surface.closed = true;
}

// The open boundaries' buffers lie beyond the box's sides: the lattice, the regions' reach and the
// run's box (field data `box`) grow by them.
void grow_by_buffers(const std::vector<OpenBoundarySpec>& open, int D, Point3& lo, Point3& hi, Bounds& reach,
                     SceneFile& s) {
  if (open.empty()) return;
  for (const OpenBoundarySpec& b : open) {
    (b.side < 0 ? lo : hi)[b.axis] = b.plane + b.side * b.depth;
    (b.side < 0 ? reach.lo : reach.hi)[b.axis] = b.plane + b.side * b.depth;
  }
  s.field["box"].clear();
  for (int a = 0; a < D; ++a) s.field["box"].push_back(lo[a]), s.field["box"].push_back(hi[a]);
}

// An open boundary's section, the part of its side where the fluid meets it: along each other axis,
// from the buffer's outermost points to the solids beside them (a channel's walls), or half a spacing
// beyond them where no solid is within a spacing.
void place_section(OpenBoundarySpec& b, const std::vector<Point3>& y, const std::vector<Region>& solids, double dx) {
  auto solid_distance = [&](const Point3& x) {
    double d = kInf;
    for (const Region& w : solids) d = std::min(d, w.shape->distance(x));
    return d;
  };
  Point3 centre = Point3::Zero();
  for (const Point3& p : y) centre += p / static_cast<double>(y.size());
  for (int a = 0; a < 3; ++a) {
    if (a == b.axis) continue;
    // The outermost points nearest the section's middle along the other axes: their nearest solid is
    // the one across this axis.
    auto outermost = [&](int sign) {
      const Point3* best = &y[0];
      auto further = [&](const Point3& p, const Point3& q) {
        if (sign * (p[a] - q[a]) > 1e-9 * dx) return true;
        if (std::abs(p[a] - q[a]) > 1e-9 * dx) return false;
        Point3 dp = p - centre, dq = q - centre;
        dp[a] = dq[a] = 0;
        return dp.norm() < dq.norm();
      };
      for (const Point3& p : y)
        if (further(p, *best)) best = &p;
      return *best;
    };
    const Point3 lo = outermost(-1), hi = outermost(1);
    const double d_lo = solid_distance(lo), d_hi = solid_distance(hi);
    b.section_lo[a] = lo[a] - (d_lo < dx ? d_lo : 0.5 * dx);
    b.section_hi[a] = hi[a] + (d_hi < dx ? d_hi : 0.5 * dx);
  }
}

// The share of the lattice's points in `range` that `keeps` keeps, from a sample of about 2^16 of
// them: the scene's particle count before any particle exists.
template <class Keeps>
double share_of_lattice_kept(const std::array<std::pair<long, long>, 3>& range, int D, const Keeps& keeps) {
  std::array<long, 3> stride{1, 1, 1};
  const long per_axis = static_cast<long>(std::ceil(std::pow(65536.0, 1.0 / D)));
  for (int a = 0; a < D; ++a) stride[a] = std::max(1L, (range[a].second - range[a].first + 1) / per_axis);
  double sampled = 0, kept = 0;
  std::array<long, 3> i{};
  for (i[2] = D == 3 ? range[2].first : 0; i[2] <= (D == 3 ? range[2].second : 0); i[2] += stride[2])
    for (i[1] = range[1].first; i[1] <= range[1].second; i[1] += stride[1])
      for (i[0] = range[0].first; i[0] <= range[0].second; i[0] += stride[0]) sampled += 1, kept += keeps(i);
  return sampled > 0 ? kept / sampled : 0.0;
}
// Per body, 1 where the fluid moves it; such a body in a scene without fluid is refused.
std::vector<char> free_bodies(const Reader& r, const std::vector<Region>& solids, const std::vector<Region>& fluids,
                              const std::vector<MotionSpec>& motions, const std::vector<std::string>& names) {
  std::vector<char> free(motions.size(), 0);
  for (const Region& w : solids)
    if (w.role == Role::Body && motions[w.body].type == "free") {
      free[w.body] = 1;
      if (fluids.empty())
        r.fail(w.at, w.key,
               "makes body '" + names[w.body] +
                   "' free in a scene with no fluid region; add the fluid that moves it, or prescribe its motion");
    }
  return free;
}

// A free body that starts inside a wall or another body would be pushed out by nothing: refused at
// the first lattice point x deep inside both.
void refuse_free_body_inside(const Reader& r, const std::vector<Region>& solids, const std::vector<char>& free,
                             const std::vector<std::string>& names, const Point3& x, double dx) {
  const Region* body = nullptr;
  for (const Region& w : solids)
    if (w.role == Role::Body && free[w.body] && w.shape->distance(x) < -0.5 * dx) body = &w;
  if (!body) return;
  for (const Region& w : solids)
    if (w.body != body->body && w.shape->distance(x) < -0.5 * dx)
      r.fail(body->at, body->key,
             "is free body '" + names[body->body] + "', which starts inside " + w.key +
                 (w.role == Role::Body ? " (body '" + names[w.body] + "')" : " (a wall)") + "; move it clear");
}

}  // namespace

YamlScene read_yaml_scene(const std::string& path, double dx, int wall_layers) {
  Reader r(path);
  const YAML::Node root = r.parse();
  const int D = r.dim;
  YamlScene out;
  SceneFile& s = out.file;
  s.path = path;
  s.dim = D;

  if (dx <= 0) {
    if (!root["dx"].IsDefined())
      r.fail(YAML::Node(), "", "gives no particle spacing; pass -nx N (dx = 1/N) or -scene_dx, or add dx: to the file");
    dx = r.number(root["dx"], "dx");
    if (!(dx > 0)) r.fail(root["dx"], "dx", "is " + number_text(dx) + "; give a positive spacing");
  }
  s.field["dx"] = {dx};

  // The domain: a box cuts the lattice (solids may run past it); periodic axes need one.
  const bool has_box = root["box"].IsDefined();
  Point3 box_lo = Point3::Constant(-kInf), box_hi = Point3::Constant(kInf);
  if (has_box) {
    std::tie(box_lo, box_hi) = r.box(root["box"], "box");
    for (int a = 0; a < D; ++a) s.field["box"].push_back(box_lo[a]), s.field["box"].push_back(box_hi[a]);
  }
  std::vector<double> periodic(D, 0.0);
  if (root["periodic"].IsDefined()) periodic = periodic_axes(r, root["periodic"]);
  for (int a = 0; a < D; ++a) {
    if (!periodic[a]) continue;
    if (!has_box) r.fail(root["periodic"], "periodic", "needs a box to set the period; add box: [...]");
    const double cells = (box_hi[a] - box_lo[a]) / dx;
    if (std::abs(cells - std::round(cells)) > kOnSurface * std::max(1.0, cells))
      r.fail(root["box"], "box",
             std::string("is ") + number_text(box_hi[a] - box_lo[a]) + " long along periodic " + "xyz"[a] +
                 ", not a whole number of dx = " + number_text(dx) +
                 "; choose -nx (or dx) so that the length holds whole spacings");
  }
  s.field["periodic"] = periodic;
  if (root["physics"].IsDefined()) read_physics(r, root["physics"], s, "physics.");
  // The physics keys may also stand at the top (gravity: [0, -1]), but not in both places.
  YAML::Node top(YAML::NodeType::Map);
  for (const char* k : {"gravity", "nu", "rho0", "U", "free_surface", "t_end"})
    if (root[k].IsDefined()) {
      if (root["physics"].IsDefined() && root["physics"][k].IsDefined())
        r.fail(root[k], k, std::string("is given at the top and under physics; keep one"));
      top[k] = root[k];
    }
  if (top.size() > 0) read_physics(r, top, s, "");
  const double rho0 = s.field.count("rho0") ? s.field["rho0"][0] : 1.0;
  Point3 g = Point3::Zero();
  if (s.field.count("gravity"))
    for (int a = 0; a < D; ++a) g[a] = s.field["gravity"][a];

  const YAML::Node list = root["regions"];
  if (!list.IsDefined() || !list.IsSequence() || list.size() == 0)
    r.fail(list.IsDefined() ? list : root, "regions", "needs a list of regions - {role: ..., shape: ...}");
  std::vector<Region> solids, fluids, plates;
  Bounds reach{Point3::Constant(kInf), Point3::Constant(-kInf)};
  std::vector<char> given;                                     // per body: its motion was given
  std::vector<std::pair<YAML::Node, std::string>> open_nodes;  // each open boundary's region and key, for messages
  for (std::size_t k = 0; k < list.size(); ++k) {
    if (Reader::is_open_boundary(list[k])) {
      const std::string key = "regions[" + std::to_string(k) + "]";
      // The buffer as deep as the walls: the kernel's support.
      out.open.push_back(r.open_boundary(list[k], key, has_box, box_lo, box_hi, periodic, out.open, wall_layers * dx));
      open_nodes.emplace_back(list[k], key);
      continue;
    }
    Region region = r.region(list[k], "regions[" + std::to_string(k) + "]", out.bodies, g);
    region.key = "regions[" + std::to_string(k) + "]", region.at = list[k];
    // A body's motion, given once (on any of its regions).
    if (region.role == Role::Body) {
      out.motions.resize(out.bodies.size());
      given.resize(out.bodies.size(), 0);
      if (list[k]["motion"].IsDefined()) {
        if (given[region.body])
          r.fail(list[k]["motion"], "regions[" + std::to_string(k) + "].motion",
                 "moves body '" + out.bodies[region.body] + "' a second time; give its motion on one region");
        given[region.body] = 1, out.motions[region.body] = region.motion;
      }
    }
    const Bounds b = region.shape->bounds();
    reach.lo = reach.lo.cwiseMin(b.lo), reach.hi = reach.hi.cwiseMax(b.hi);
    (region.is_plate ? plates : region.role == Role::Fluid ? fluids : solids).push_back(region);
    // A particle names its plate's face in a signed byte (src/neighbours/screens.hpp).
    if (plates.size() > 127)
      r.fail(list[k], "regions[" + std::to_string(k) + "]", "is the 128th plate; a scene holds at most 127");
  }

  if (has_box) check_mesh_units(r, box_lo, box_hi);
  if (!out.open.empty() && fluids.empty())
    r.fail(list, "regions", "has inlets or outlets but no fluid region; add one");
  const std::vector<char> free = free_bodies(r, solids, fluids, out.motions, out.bodies);
  const bool any_free = std::find(free.begin(), free.end(), 1) != free.end();
  auto check_clear = [&](const Point3& x) { refuse_free_body_inside(r, solids, free, out.bodies, x, dx); };
  Point3 lattice_lo = box_lo, lattice_hi = box_hi;
  grow_by_buffers(out.open, D, lattice_lo, lattice_hi, reach, s);

  // The lattice over the regions' reach, within the box.
  std::array<std::pair<long, long>, 3> range{};
  double points = 1;
  for (int a = 0; a < D; ++a) {
    const double lo = std::max(reach.lo[a], lattice_lo[a]), hi = std::min(reach.hi[a], lattice_hi[a]);
    if (!std::isfinite(lo) || !std::isfinite(hi))
      r.fail(list, "regions",
             std::string("reach to infinity along ") + "xyz"[a] +
                 " (a half_space); give a box to cut them, or bound them by intersection");
    range[a] = lattice_range(lo, hi, dx, periodic[a] != 0);
    points *= std::max(0L, range[a].second - range[a].first + 1);
  }
  if (points > 2e9)
    r.fail(YAML::Node(), "",
           "spans " + number_text(points) + " lattice points at dx = " + number_text(dx) +
               "; raise the spacing (a smaller -nx) or cut the regions with a box");

  const double on = kOnSurface * dx, deep = -wall_layers * dx + on;
  // Hydrostatic starts: the water above a particle ends where neither a fluid region nor a solid is.
  const Point3 up = g.norm() > 0 ? Point3(-g.normalized()) : Point3::Zero();
  double box_top = 0.0;
  for (int a = 0; a < D; ++a) box_top += std::max(up[a] * box_lo[a], up[a] * box_hi[a]);
  double shapes_top = -kInf;
  for (const auto* group : {&fluids, &solids})
    for (const Region& r : *group) shapes_top = std::max(shapes_top, r.shape->highest(up));
  box_top = std::min(box_top, shapes_top);
  auto occupied = [&](const Point3& y) {
    double d = kInf;
    for (const Region& f : fluids) d = std::min(d, f.shape->distance(y));
    for (const Region& w : solids) d = std::min(d, w.shape->distance(y));
    return d;
  };
  // What a lattice point becomes: a solid's particle (holder), a fluid region's, or none.
  struct Fill {
    const Region* holder = nullptr;
    const Region* fluid = nullptr;
  };
  auto fill = [&](const Point3& x) {
    Fill f;
    // The solids' union: its distance is the nearest part's; the last solid holding x names it.
    double solid = kInf;
    for (const Region& w : solids) {
      const double d = w.shape->distance(x);
      solid = std::min(solid, d);
      if (d <= on) f.holder = &w;
    }
    if (!f.holder && !in_plate_gap(plates, x, dx))
      for (const Region& fl : fluids)
        if (fl.shape->distance(x) <= on) f.fluid = &fl;
    // A body is kept whole: it is a solid with a mass, and a hollow shell's inner face would read
    // as a wall thinner than the support where the shell curves (scene_geometry.hpp's measure).
    if (f.holder && !(solid > deep || f.holder->role == Role::Body)) f.holder = nullptr;
    return f;
  };
  auto lattice_point = [&](const std::array<long, 3>& i) {
    Point3 x = Point3::Zero();
    for (int a = 0; a < D; ++a) x[a] = std::clamp((i[a] + 0.5) * dx, lattice_lo[a], lattice_hi[a]);
    return x;
  };
  // The memory check before the particles exist, so a scene far too large is refused in well under a
  // second.
  const double share_kept = share_of_lattice_kept(range, D, [&](const std::array<long, 3>& i) {
    const Fill f = fill(lattice_point(i));
    return f.holder || f.fluid;
  });
  if (share_kept * points > static_cast<double>(particle_budget().limit)) refuse_over_budget();
  long fluid = 0;
  std::map<const Region*, long> taken;  // particles per fluid region and per solid region
  // The open boundary whose buffer x lies in (beyond its side of the box), or -1.
  auto open_side = [&](const Point3& x) {
    for (std::size_t o = 0; o < out.open.size(); ++o)
      if (out.open[o].side * (x[out.open[o].axis] - out.open[o].plane) > 0) return static_cast<int>(o);
    return -1;
  };
  // Each buffer's points where they meet the box (the first fluid row inside), for its section.
  std::vector<std::vector<Point3>> sections(out.open.size());
  std::array<long, 3> i{};
  for (i[2] = D == 3 ? range[2].first : 0; i[2] <= (D == 3 ? range[2].second : 0); ++i[2])
    for (i[1] = range[1].first; i[1] <= range[1].second; ++i[1]) {
      if (s.x.size() > particle_budget().limit) refuse_over_budget();
      for (i[0] = range[0].first; i[0] <= range[0].second; ++i[0]) {
        const Point3 x = lattice_point(i);
        Fill f = fill(x);
        if (any_free && f.holder) check_clear(x);
        if (const int o = open_side(x); o >= 0) {
          if (!f.holder) {
            // A buffer particle where the fluid inside meets the side, with that fluid's start.
            const OpenBoundarySpec& b = out.open[o];
            Point3 y = x;
            y[b.axis] = b.plane - b.side * 0.5 * dx;
            const Fill inside = fill(y);
            if (!inside.fluid) continue;
            const Region& in = *inside.fluid;
            const double p = !b.inlet         ? b.pressure
                             : in.hydrostatic ? rho0 * g.norm() * depth_below_surface(occupied, y, up, box_top, dx)
                                              : in.pressure;
            s.x.push_back({x[0], x[1], x[2]});
            s.v.push_back({in.velocity[0], in.velocity[1], in.velocity[2]});
            s.p.push_back(p), s.kind.push_back(b.inlet ? kSceneInlet : kSceneOutlet);
            out.body.push_back(-1), out.free_slip.push_back(0);
            sections[o].push_back(y);
            continue;
          }
          f.fluid = nullptr;  // the buffer, not the fluid regions, fills the space beyond an open side
        }
        if (!f.holder && !f.fluid) continue;
        ++taken[f.holder ? f.holder : f.fluid];
        const std::array<double, 3> xa = {x[0], x[1], x[2]};
        s.x.push_back(xa);
        if (f.holder) {
          s.v.push_back({0.0, 0.0, 0.0}), s.p.push_back(0.0), s.kind.push_back(kSceneFixedWall);
          out.body.push_back(f.holder->body), out.free_slip.push_back(f.holder->free_slip);
          continue;
        }
        const Region* in_fluid = f.fluid;
        const double p = in_fluid->hydrostatic ? rho0 * g.norm() * depth_below_surface(occupied, x, up, box_top, dx)
                                               : in_fluid->pressure;
        s.v.push_back({in_fluid->velocity[0], in_fluid->velocity[1], in_fluid->velocity[2]});
        s.p.push_back(p), s.kind.push_back(kSceneFluid), out.body.push_back(-1), out.free_slip.push_back(0);
        ++fluid;
      }
    }
  add_plate_layers(plates, solids, wall_layers, dx, box_lo, box_hi, out);
  for (std::size_t o = 0; o < out.open.size(); ++o) {
    if (sections[o].empty())
      r.fail(open_nodes[o].first, open_nodes[o].second,
             "is an inlet or outlet where no fluid region meets the box's side; move it or the fluid");
    place_section(out.open[o], sections[o], solids, dx);
  }
  out.plate_face.resize(s.x.size(), 0);
  if (fluid == 0)
    r.fail(list, "regions",
           "hold no fluid particle at dx = " + number_text(dx) +
               ": no lattice point lies inside a fluid region, outside the solids and inside the box; refine "
               "(a larger -nx) or move the fluid regions");
  std::map<const Region*, double> kept;  // per fluid region and body region: the area (volume) it keeps
  for (const Region& f : fluids)
    kept[&f] = kept_measure(*f.shape, box_lo, box_hi, D, [&](const Point3& x) { return fill(x).fluid == &f; });
  for (const Region& w : solids)
    if (w.role == Role::Body)
      kept[&w] = kept_measure(*w.shape, box_lo, box_hi, D, [&](const Point3& x) { return fill(x).holder == &w; });
  check_regions_filled(r, fluids, solids, plates, out.bodies, taken, kept, dx);

  // Each body's surface, sampled at a quarter of the spacing (an eighth of the body across at least in
  // 2D, at most 200 steps along an edge in 3D), within the box.
  out.surfaces.resize(out.bodies.size());
  for (std::size_t b = 0; b < out.bodies.size(); ++b) {
    std::vector<const Shape*> parts;
    Point3 lo = Point3::Constant(kInf), hi = Point3::Constant(-kInf);
    for (const Region& s : solids)
      if (s.body == static_cast<int>(b)) {
        parts.push_back(s.shape.get());
        const Bounds reach_b = s.shape->bounds();
        lo = lo.cwiseMin(reach_b.lo), hi = hi.cwiseMax(reach_b.hi);
      }
    double extent = 0.0;
    for (int a = 0; a < D; ++a) {
      lo[a] = std::max(lo[a] - 2 * dx, box_lo[a]), hi[a] = std::min(hi[a] + 2 * dx, box_hi[a]);
      extent = std::max(extent, hi[a] - lo[a]);
    }
    if (!parts.empty() && std::isfinite(extent)) {
      const double step = D == 2 ? std::min(0.25 * dx, extent / 8) : std::max(0.25 * dx, extent / 200);
      out.surfaces[b] = body_surface(parts, D, lo, hi, step);
    }
    for (const Region& p : plates)
      if (p.body == static_cast<int>(b)) add_outline(p.plate, 0.25 * dx, out.surfaces[b]);
  }

  std::uint64_t h = r.checksum;
  h = fnv1a(h, &dx, sizeof dx);
  h = fnv1a(h, &wall_layers, sizeof wall_layers);
  s.checksum = h;
  return out;
}

}  // namespace sph
