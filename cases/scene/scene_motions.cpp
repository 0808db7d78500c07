// A body's motion as a scene file gives it: fixed, constant, sinusoidal, a table, rotations, free.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>

#include "cases/scene/body_surface.hpp"
#include "cases/scene/scene_reader.hpp"
#include "src/core/error.hpp"

namespace sph::scene_detail {

// {type: fixed}, {type: constant, velocity: [..]} or {type: sinusoidal, amplitude: [..], period: T,
// phase: degrees (optional)}.
MotionSpec Reader::motion(const YAML::Node& m, const std::string& key) {
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
void Reader::body_mass(const YAML::Node& n, const std::string& key, MotionSpec& motion) const {
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
MotionSpec Reader::free_motion(const YAML::Node& m, const std::string& key) const {
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
      fail(f, key + ".fixed", "is not a list of axes; give e.g. fixed: [x, rotation] (x, y, z, rotation, rx, ry, rz)");
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
void Reader::table_motion(const YAML::Node& m, const std::string& key, MotionSpec& spec) {
  for (const char* name : {"velocity", "amplitude", "period", "phase", "rotation"})
    if (m[name].IsDefined()) fail(m[name], key + "." + name, "does not apply to type table; remove it");
  if (!m["file"].IsDefined() || !m["file"].IsScalar()) fail(m, key, "of type table needs file: motion.csv");
  std::vector<std::string> want = {"t", "x", "y"};
  if (dim == 3) want.push_back("z");
  bool with_angle = false;
  const CsvTable table =
      csv_table(m["file"], key + ".file", "the motion table, a CSV with the header t,x,y", [&](const CsvTable& t) {
        with_angle = t.header.size() == want.size() + 1 && t.header.back() == "angle";
        if (with_angle) want.push_back("angle");
        if (t.header != want)
          fail(m["file"], t.where,
               "has the header '" + t.header_line + "'; give t,x,y" + (dim == 3 ? ",z" : "") +
                   " (and ,angle in degrees) in the first line");
      });
  for (const std::vector<double>& x : table.rows) {
    spec.table_t.push_back(x[0]);
    for (int a = 0; a < dim; ++a) spec.table_x[a].push_back(x[1 + a]);
    if (with_angle) spec.table_angle_degrees.push_back(x.back());
  }
  spec.type = "table";
  if (!with_angle) return;
  spec.spin = "table";
  rotation_axis(m, key, spec, "turns the body (an angle column) but has no centre; give centre: [...]");
}

// An axis's direction, made unit.
std::array<double, 3> Reader::unit_axis(const YAML::Node& n, const std::string& key) const {
  const Point3 axis = point(n, key);
  if (axis.norm() == 0) fail(n, key, "is zero; give the direction of the axis");
  const Point3 unit = axis.normalized();
  return {unit[0], unit[1], unit[2]};
}

// The centre the rotation's axis goes through and, in 3D, its direction (none in 2D: about z).
void Reader::rotation_axis(const YAML::Node& r, const std::string& key, MotionSpec& spec,
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
void Reader::rotation(const YAML::Node& r, const std::string& key, MotionSpec& spec) const {
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

}  // namespace sph::scene_detail
