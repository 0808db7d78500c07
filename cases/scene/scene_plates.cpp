#include "cases/scene/scene_plates.hpp"

#include <algorithm>
#include <cmath>

namespace sph::scene_detail {

namespace {
// A plate's unit direction from a to b and its normal (the +1 face's side), in the xy plane.
std::pair<Point3, Point3> plate_frame(const PlateSpec& p) {
  const Point3 e = (p.b - p.a).normalized();
  return {e, Point3(-e[1], e[0], 0.0)};
}
}  // namespace

// {from: [x, y], to: [x, y], thickness: T (default 0)}: a plate's mid-line and thickness; its outline,
// a rectangle, is the region's shape for the bounds and the body's surface.
void Reader::read_plate(const YAML::Node& v, const std::string& k, Region& r) {
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
    if (!(r.plate.thickness >= 0)) fail(v["thickness"], k + ".thickness", "is negative; give a thickness of 0 or more");
  }
  const Eigen::Vector2d a = r.plate.a.head<2>(), b = r.plate.b.head<2>(), e = (b - a).normalized();
  const Eigen::Vector2d n(-e[1], e[0]);
  const double half = std::max(0.5 * r.plate.thickness, 1e-12);
  r.shape = make_polygon({a - half * n, b - half * n, b + half * n, a + half * n});
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
          out.wall_pressure.push_back(plates[k].wall_pressure);
          out.plate_face.push_back(static_cast<std::int8_t>(face * (static_cast<int>(out.plates.size()) + 1)));
        }
    const Point3 a = p.a - (before * step) * e, b = p.b + (after * step) * e;
    out.plates.push_back({a[0], a[1], b[0], b[1]});
    out.plate_body.push_back(plates[k].body);
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

}  // namespace sph::scene_detail
