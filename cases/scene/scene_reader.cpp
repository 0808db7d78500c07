// Reading a scene file: its keys checked, numbers, shapes, regions and open boundaries.

#include "cases/scene/scene_reader.hpp"

#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>

#include "cases/scene/body_surface.hpp"
#include "src/boundary/wall_pressure.hpp"
#include "src/core/error.hpp"

namespace sph::scene_detail {

void Reader::fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
  std::string where = at.IsDefined() && at.Mark().line >= 0 ? "line " + std::to_string(at.Mark().line + 1) : "";
  if (!key.empty()) where += (where.empty() ? "" : ", ") + key;
  throw Error("scene file '" + path_ + "': " + (where.empty() ? "" : where + ": ") + what);
}

YAML::Node Reader::load(const std::string& text) const {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops at a fixed depth and says only "bad file".
    throw Error("scene file '" + path_ + "': line " + std::to_string(e.mark.line + 1) + ": nested " +
                std::to_string(e.depth()) +
                " levels deep, deeper than the YAML reader takes; give a union's or a difference's shapes as one "
                "list instead of nesting them");
  } catch (const YAML::ParserException& e) {
    throw Error("scene file '" + path_ + "': line " + std::to_string(e.mark.line + 1) + ", column " +
                std::to_string(e.mark.column + 1) + ": YAML syntax error (" + e.msg + "); fix the syntax there");
  }
  refuse_repeated_keys(root);
  return root;
}

// yaml-cpp keeps a key given twice in one mapping and answers the first: the second (dimension: 2,
// then 3) would be silently ignored.
void Reader::refuse_repeated_keys(const YAML::Node& n) const {
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

YAML::Node Reader::parse() {
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
             "t_end", "probes"});
  const YAML::Node d = root["dimension"];
  if (!d.IsDefined()) fail(YAML::Node(), "", "has no key 'dimension'; add dimension: 2 or dimension: 3");
  const double value = number(d, "dimension");
  if (value != 2 && value != 3) fail(d, "dimension", "is " + number_text(value) + "; give 2 or 3");
  dim = static_cast<int>(value);
  return root;
}

void Reader::only_keys(const YAML::Node& map, const std::string& key,
                       std::initializer_list<const char*> allowed) const {
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

double Reader::number(const YAML::Node& n, const std::string& key) const {
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

std::vector<double> Reader::numbers(const YAML::Node& n, const std::string& key, std::size_t count,
                                    const std::string& form) const {
  if (!n.IsSequence() || n.size() != count)
    fail(n, key,
         (n.IsSequence() ? "has " + std::to_string(n.size()) + " numbers" : std::string("is not a list")) + "; a " +
             std::to_string(dim) + "D scene takes " + std::to_string(count) + ": " + form);
  std::vector<double> v;
  for (std::size_t k = 0; k < count; ++k) v.push_back(number(n[k], key + "[" + std::to_string(k) + "]"));
  return v;
}

Point3 Reader::point(const YAML::Node& n, const std::string& key) const {
  const std::vector<double> v = numbers(n, key, dim, dim == 2 ? "[x, y]" : "[x, y, z]");
  return Point3(v[0], v[1], dim == 3 ? v[2] : 0.0);
}

double Reader::radius(const YAML::Node& map, const std::string& key) const {
  const YAML::Node r = map["radius"];
  if (!r.IsDefined()) fail(map, key, "has no radius; add radius: R");
  const double v = number(r, key + ".radius");
  if (!(v > 0)) fail(r, key + ".radius", "is " + number_text(v) + "; a radius must be positive");
  return v;
}

// The lower and upper corners of a box [x0, x1, y0, y1(, z0, z1)], each pair increasing.
std::pair<Point3, Point3> Reader::box(const YAML::Node& n, const std::string& key) const {
  const std::vector<double> v = numbers(n, key, 2 * dim, dim == 2 ? "[x0, x1, y0, y1]" : "[x0, x1, y0, y1, z0, z1]");
  Point3 lo = Point3::Zero(), hi = Point3::Zero();
  for (int a = 0; a < dim; ++a) {
    lo[a] = v[2 * a], hi[a] = v[2 * a + 1];
    if (!(hi[a] > lo[a]))
      fail(n, key, std::string("has ") + "xyz"[a] + "1 <= " + "xyz"[a] + "0; give each axis as min, max");
  }
  return {lo, hi};
}

// polygon: [[x, y], ...], at least 3 vertices enclosing an area.
ShapePtr Reader::polygon(const YAML::Node& v, const std::string& k) const {
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

// mesh: FILE (.stl, .obj, .vtp; relative to the scene file), a closed surface; its bytes enter the checksum.
ShapePtr Reader::mesh(const YAML::Node& v, const std::string& k) {
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
    ShapePtr surface = make_mesh(file.string());
    meshes.push_back({v, k, file.string(), surface->bounds()});
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    checksum = fnv1a(checksum, bytes.data(), bytes.size());
    return surface;
  } catch (const Error& e) {
    fail(v, k, std::string(e.what()) + " (paths are relative to the scene file)");
  }
}

ShapePtr Reader::shape(const YAML::Node& n, const std::string& key) {
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
    return polygon(v, k);
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
    return mesh(v, k);
  }
  fail(n.begin()->first, key, "unknown shape '" + kind + "'; use one of " + known);
}

// A shape written inline, `shape: NAME` with its parameters beside it in the region (`shape: circle,
// centre: [..], radius: R`; `shape: difference, of: [..]`; box: bounds, polygon: vertices, mesh: file),
// as the nested form {NAME: value}.
YAML::Node Reader::inline_shape(const YAML::Node& n, const std::string& key) const {
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

// Whether region n is an inlet or an outlet (role: inlet / outlet).
bool Reader::is_open_boundary(const YAML::Node& n) {
  const YAML::Node role = n.IsMap() ? n["role"] : YAML::Node();
  return role.IsDefined() && role.IsScalar() && (role.Scalar() == "inlet" || role.Scalar() == "outlet");
}

// {role: inlet, side: x-, velocity: [u, v] or {parabolic: U_max}, ramp: T, speed_table: FILE} or
// {role: outlet, side: x+, pressure: p, level: H}: the side and the condition; the buffer's place and
// section come with the lattice.
// Where it lies: on a side of the box (the box given, the axis not periodic, the side free), with a
// buffer `depth` deep.
OpenBoundarySpec Reader::open_boundary(const YAML::Node& n, const std::string& key, bool has_box, const Point3& box_lo,
                                       const Point3& box_hi, const std::vector<double>& periodic,
                                       const std::vector<OpenBoundarySpec>& others, double depth) {
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

// velocity: {expression: [u, v]} (3D [u, v, w]): each component an expression of x, y (and z), the
// inlet particle's place; muParser's syntax (src/core/expression.hpp).
void Reader::inlet_expressions(const YAML::Node& n, const std::string& key, OpenBoundarySpec& b) const {
  const std::string names = dim == 2 ? "xy" : "xyz";
  if (!n.IsSequence() || n.size() != static_cast<std::size_t>(dim))
    fail(n, key,
         std::string("must list ") + (dim == 2 ? "two expressions, [u, v]," : "three expressions, [u, v, w],") +
             " one a velocity component, of " + (dim == 2 ? "x and y" : "x, y and z"));
  for (std::size_t a = 0; a < n.size(); ++a) {
    if (!n[a].IsScalar()) fail(n[a], key + "[" + std::to_string(a) + "]", "is not an expression; write it as text");
    try {
      b.expressions.emplace_back(n[a].Scalar(), names);
    } catch (const Error& e) {
      fail(n[a], key + "[" + std::to_string(a) + "]", e.what());
    }
  }
}

OpenBoundarySpec Reader::open_boundary_condition(const YAML::Node& n, const std::string& key) {
  OpenBoundarySpec b;
  b.inlet = n["role"].Scalar() == "inlet";
  if (b.inlet) only_keys(n, key, {"role", "side", "velocity", "ramp", "speed_table"});
  else only_keys(n, key, {"role", "side", "pressure", "level"});
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
    if (n["level"].IsDefined()) b.keeps_level = true, b.level = number(n["level"], key + ".level");
    return b;
  }
  const YAML::Node v = n["velocity"];
  if (!v.IsDefined())
    fail(n, key,
         "is an inlet without a velocity; add velocity: [u, v], velocity: {parabolic: U_max} or velocity: "
         "{expression: [u, v]}");
  if (v.IsMap() && v["expression"].IsDefined()) {
    only_keys(v, key + ".velocity", {"expression"});
    inlet_expressions(v["expression"], key + ".velocity.expression", b);
  } else if (v.IsMap()) {
    only_keys(v, key + ".velocity", {"parabolic", "expression"});
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
  if (n["speed_table"].IsDefined()) inlet_speed_table(n["speed_table"], key + ".speed_table", b);
  return b;
}

// role: fluid, wall, body (with name: NAME) or {body: NAME}; a body's name added to `bodies`.
void Reader::read_role(const YAML::Node& n, const std::string& key, Region& r, std::vector<std::string>& bodies) const {
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
    if (body.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string::npos)
      fail(n, key,
           "names body '" + body + "'; a body's name takes letters, digits and _ (it names timeseries columns)");
    if (body == "walls") fail(n, key, "names a body 'walls', the name of the walls' own force columns; rename it");
    r.body = static_cast<int>(std::find(bodies.begin(), bodies.end(), body) - bodies.begin());
    if (r.body == static_cast<int>(bodies.size())) bodies.push_back(body);
  } else if (n["name"].IsDefined()) {
    fail(n["name"], key + ".name", "names a region that is no body; only role: body takes a name");
  }
}

// A wall or body region's own wall conditions: slip: free | no_slip, wall_pressure: adami | continued.
void Reader::wall_conditions(const YAML::Node& n, const std::string& key, Region& r) const {
  if (const YAML::Node slip = n["slip"]; slip.IsDefined()) {
    if (r.role == Role::Fluid)
      fail(slip, key + ".slip", "is given for fluid; only walls and bodies have a slip condition");
    if (!slip.IsScalar() || (slip.Scalar() != "free" && slip.Scalar() != "no_slip"))
      fail(slip, key + ".slip", "is not free or no_slip; give one of those");
    r.free_slip = slip.Scalar() == "free";
  }
  if (const YAML::Node form = n["wall_pressure"]; form.IsDefined()) {
    if (r.role == Role::Fluid)
      fail(form, key + ".wall_pressure", "is given for fluid; only walls and bodies continue the fluid's pressure");
    const auto* names = std::begin(wall_pressure_names);
    const auto* found = form.IsScalar() ? std::find(names, std::end(wall_pressure_names), form.Scalar())
                                        : std::end(wall_pressure_names);
    if (found == std::end(wall_pressure_names))
      fail(form, key + ".wall_pressure", "is not adami or continued; give one of those (-help, -wall_pressure)");
    r.wall_pressure = static_cast<signed char>(found - names);
  }
}

Region Reader::region(const YAML::Node& n, const std::string& key, std::vector<std::string>& bodies, const Point3& g) {
  only_keys(n, key, {"role",   "shape",    "velocity", "pressure",  "motion",  "slip",   "name",         "of",
                     "bounds", "vertices", "file",     "centre",    "center",  "radius", "ends",         "point",
                     "normal", "from",     "to",       "thickness", "density", "mass",   "wall_pressure"});
  Region r;
  read_role(n, key, r, bodies);
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
  } else {
    r.shape = shape(inline_form ? inline_shape(n, key) : s, key + ".shape");
  }
  for (const char* value : {"velocity", "pressure"})
    if (r.role != Role::Fluid && n[value].IsDefined())
      fail(n[value], key + "." + value,
           "is given for a wall; walls are at rest with no pressure of their own: "
           "remove it or make the region's role fluid");
  if (n["velocity"].IsDefined()) r.velocity = point(n["velocity"], key + ".velocity");
  wall_conditions(n, key, r);
  if (const YAML::Node m = n["motion"]; m.IsDefined()) {
    if (r.role != Role::Body)
      fail(m, key + ".motion",
           "is given for a region that is no body; only role: body moves (fixed walls do not: make a moving tank "
           "a body, role: body with name: tank, and its plates role: {body: tank})");
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

}  // namespace sph::scene_detail
