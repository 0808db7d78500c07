#include "cases/scene/scene_yaml.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <tuple>

#include "cases/scene/body_surface.hpp"
#include "cases/scene/scene_lattice.hpp"
#include "cases/scene/scene_plates.hpp"
#include "cases/scene/scene_reader.hpp"

namespace sph {

namespace scene_detail {
namespace {

// The spacing (from the caller, else the file's dx:), the box, the periodic axes and the physics.
SceneFrame read_frame(Reader& r, const YAML::Node& root, double dx, SceneFile& s) {
  SceneFrame f;
  const int D = f.dim = r.dim;
  if (dx <= 0) {
    if (!root["dx"].IsDefined())
      r.fail(YAML::Node(), "", "gives no particle spacing; pass -nx N (dx = 1/N) or -scene_dx, or add dx: to the file");
    dx = r.number(root["dx"], "dx");
    if (!(dx > 0)) r.fail(root["dx"], "dx", "is " + number_text(dx) + "; give a positive spacing");
  }
  f.dx = dx;
  s.field["dx"] = {dx};

  // The domain: a box cuts the lattice (solids may run past it); periodic axes need one.
  f.has_box = root["box"].IsDefined();
  if (f.has_box) {
    std::tie(f.box_lo, f.box_hi) = r.box(root["box"], "box");
    for (int a = 0; a < D; ++a) s.field["box"].push_back(f.box_lo[a]), s.field["box"].push_back(f.box_hi[a]);
  }
  f.periodic.assign(D, 0.0);
  if (root["periodic"].IsDefined()) f.periodic = periodic_axes(r, root["periodic"]);
  for (int a = 0; a < D; ++a) {
    if (!f.periodic[a]) continue;
    if (!f.has_box) r.fail(root["periodic"], "periodic", "needs a box to set the period; add box: [...]");
    const double cells = (f.box_hi[a] - f.box_lo[a]) / dx;
    if (std::abs(cells - std::round(cells)) > kOnSurface * std::max(1.0, cells))
      r.fail(root["box"], "box",
             std::string("is ") + number_text(f.box_hi[a] - f.box_lo[a]) + " long along periodic " + "xyz"[a] +
                 ", not a whole number of dx = " + number_text(dx) +
                 "; choose -nx (or dx) so that the length holds whole spacings");
  }
  s.field["periodic"] = f.periodic;
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
  f.rho0 = s.field.count("rho0") ? s.field["rho0"][0] : 1.0;
  if (s.field.count("gravity"))
    for (int a = 0; a < D; ++a) f.g[a] = s.field["gravity"][a];
  return f;
}

// The regions: solids, fluids and plates, the bodies' names and motions, the open boundaries.
SceneRegions read_regions(Reader& r, const YAML::Node& root, const SceneFrame& f, int wall_layers, YamlScene& out) {
  SceneRegions g;
  const YAML::Node list = g.list = root["regions"];
  if (!list.IsDefined() || !list.IsSequence() || list.size() == 0)
    r.fail(list.IsDefined() ? list : root, "regions", "needs a list of regions - {role: ..., shape: ...}");
  std::vector<char> given;  // per body: its motion was given
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string key = "regions[" + std::to_string(k) + "]";
    if (Reader::is_open_boundary(list[k])) {
      // The buffer as deep as the walls: the kernel's support.
      out.open.push_back(
          r.open_boundary(list[k], key, f.has_box, f.box_lo, f.box_hi, f.periodic, out.open, wall_layers * f.dx));
      if (out.open.back().keeps_level && f.g.norm() == 0)
        r.fail(list[k]["level"], key + ".level",
               "keeps a water level, and the scene has no gravity; add gravity: [...] or drop level");
      g.open_nodes.emplace_back(list[k], key);
      continue;
    }
    Region region = r.region(list[k], key, out.bodies, f.g);
    region.key = key, region.at = list[k];
    // A body's motion, given once (on any of its regions).
    if (region.role == Role::Body) {
      out.motions.resize(out.bodies.size());
      given.resize(out.bodies.size(), 0);
      if (list[k]["motion"].IsDefined()) {
        if (given[region.body])
          r.fail(list[k]["motion"], key + ".motion",
                 "moves body '" + out.bodies[region.body] + "' a second time; give its motion on one region");
        given[region.body] = 1, out.motions[region.body] = region.motion;
      }
    }
    const Bounds b = region.shape->bounds();
    g.reach.lo = g.reach.lo.cwiseMin(b.lo), g.reach.hi = g.reach.hi.cwiseMax(b.hi);
    (region.is_plate ? g.plates : region.role == Role::Fluid ? g.fluids : g.solids).push_back(region);
    // A particle names its plate's face in a signed byte (src/neighbours/screens.hpp).
    if (g.plates.size() > 127) r.fail(list[k], key, "is the 128th plate; a scene holds at most 127");
  }
  if (f.has_box) check_mesh_units(r, f.box_lo, f.box_hi);
  if (!out.open.empty() && g.fluids.empty())
    r.fail(list, "regions", "has inlets or outlets but no fluid region; add one");
  g.free = free_bodies(r, g.solids, g.fluids, g.plates, out.motions, out.bodies);
  return g;
}

// Each body's surface, sampled at a quarter of the spacing (an eighth of the body across at least in
// 2D, at most 200 steps along an edge in 3D), within the box.
void add_body_surfaces(const SceneFrame& f, const SceneRegions& g, YamlScene& out) {
  const int D = f.dim;
  const double dx = f.dx;
  out.surfaces.resize(out.bodies.size());
  for (std::size_t b = 0; b < out.bodies.size(); ++b) {
    std::vector<const Shape*> parts;
    Point3 lo = Point3::Constant(kInf), hi = Point3::Constant(-kInf);
    for (const Region& s : g.solids)
      if (s.body == static_cast<int>(b)) {
        parts.push_back(s.shape.get());
        const Bounds reach_b = s.shape->bounds();
        lo = lo.cwiseMin(reach_b.lo), hi = hi.cwiseMax(reach_b.hi);
      }
    double extent = 0.0;
    for (int a = 0; a < D; ++a) {
      lo[a] = std::max(lo[a] - 2 * dx, f.box_lo[a]), hi[a] = std::min(hi[a] + 2 * dx, f.box_hi[a]);
      extent = std::max(extent, hi[a] - lo[a]);
    }
    if (!parts.empty() && std::isfinite(extent)) {
      const double step = D == 2 ? std::min(0.25 * dx, extent / 8) : std::max(0.25 * dx, extent / 200);
      out.surfaces[b] = body_surface(parts, D, lo, hi, step);
    }
    for (const Region& p : g.plates)
      if (p.body == static_cast<int>(b)) add_outline(p.plate, 0.25 * dx, out.surfaces[b]);
  }
}

// The pressure probes: a name each (unique; letters, digits and _, for a column name) and a point
// within the box (on its side counts: a probe on a wall's face).
std::vector<ProbeSpec> read_probes(Reader& r, const YAML::Node& root, const SceneFrame& f) {
  std::vector<ProbeSpec> probes;
  const YAML::Node list = root["probes"];
  if (!list.IsDefined()) return probes;
  if (!list.IsSequence()) r.fail(list, "probes", "is not a list; write probes: [{name: P1, at: [x, y]}]");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string key = "probes[" + std::to_string(k) + "]";
    r.only_keys(list[k], key, {"name", "at"});
    if (!list[k]["name"].IsDefined() || !list[k]["at"].IsDefined())
      r.fail(list[k], key, "needs a name and a point; write {name: P1, at: [x, y]}");
    ProbeSpec p;
    p.name = list[k]["name"].Scalar();
    const bool word = !p.name.empty() && std::all_of(p.name.begin(), p.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!word) r.fail(list[k]["name"], key + ".name", "is '" + p.name + "'; give letters, digits and _ only");
    for (const ProbeSpec& q : probes)
      if (q.name == p.name) r.fail(list[k]["name"], key + ".name", "repeats the probe name '" + p.name + "'");
    const Point3 at = r.point(list[k]["at"], key + ".at");
    for (int a = 0; a < f.dim; ++a) {
      p.at[a] = at[a];
      const double slack = kOnSurface * f.dx;
      if (f.has_box && (at[a] < f.box_lo[a] - slack || at[a] > f.box_hi[a] + slack))
        r.fail(list[k]["at"], key + ".at", std::string("lies outside the box along ") + "xyz"[a] + "; move it inside");
    }
    probes.push_back(p);
  }
  return probes;
}

}  // namespace
}  // namespace scene_detail

bool is_yaml_scene(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".yaml" || ext == ".yml";
}

int yaml_scene_dimension(const std::string& path) {
  scene_detail::Reader r(path);
  r.parse();
  return r.dim;
}

YamlScene read_yaml_scene(const std::string& path, double dx, int wall_layers) {
  using namespace scene_detail;
  Reader r(path);
  const YAML::Node root = r.parse();
  YamlScene out;
  out.file.path = path;
  out.file.dim = r.dim;
  const SceneFrame frame = read_frame(r, root, dx, out.file);
  const SceneRegions regions = read_regions(r, root, frame, wall_layers, out);
  out.probes = read_probes(r, root, frame);
  fill_lattice(r, frame, regions, wall_layers, out);
  add_body_surfaces(frame, regions, out);
  std::uint64_t h = r.checksum;
  h = fnv1a(h, &frame.dx, sizeof frame.dx);
  h = fnv1a(h, &wall_layers, sizeof wall_layers);
  out.file.checksum = h;
  return out;
}

}  // namespace sph
