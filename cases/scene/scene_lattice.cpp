#include "cases/scene/scene_lattice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "cases/scene/scene_plates.hpp"
#include "src/particles/particle_budget.hpp"

namespace sph::scene_detail {

namespace {

// How far x lies below the free surface above it: the distance along `up` to the first point that
// `occupied` (a signed distance: negative inside the scene's fluid regions or solids) leaves empty, so
// that a tilted or curved surface starts in hydrostatic balance column by column and a submerged body
// does not cut the column. Marched in steps of dx (an overhang is found) and refined by bisection to
// round-off; `top` (the box's highest point along up) ends the march. A point on the face where the
// fluid meets a solid is in both (distance 0 to each) and counts as occupied, as the lattice counts it
// (kOnSurface), so a column up a body's side is not cut where the side lies on a lattice column.
template <class Occupied>
double depth_below_surface(const Occupied& occupied, const Point3& x, const Point3& up, double top, double dx) {
  const double reach = top - up.dot(x), on = kOnSurface * dx;
  if (reach <= 0.0 || occupied(x) > on) return 0.0;
  double inside = 0.0, outside = reach;
  for (double s = dx; s < reach; s += dx) {
    if (occupied(x + s * up) > on) {
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

// One scene's lattice: what each point becomes, and the particles it makes.
class Lattice {
 public:
  Lattice(const Reader& r, const SceneFrame& frame, const SceneRegions& regions, int wall_layers, YamlScene& out);
  void fill();

 private:
  // What a lattice point becomes: a solid's particle (holder), a fluid region's, or none.
  struct Fill {
    const Region* holder = nullptr;
    const Region* fluid = nullptr;
  };
  void set_range();
  void set_water_top();
  Fill at(const Point3& x) const;
  Point3 point(const std::array<long, 3>& i) const;
  double occupied(const Point3& y) const;
  double start_pressure(const Region& in, const Point3& x) const;
  int open_side(const Point3& x) const;
  void add_point(const Point3& x);
  void add_buffer_particle(const Point3& x, int o);
  void place_sections();
  void check_inlet_expressions(std::size_t o);
  void check_filled();

  const Reader& r_;
  const SceneFrame& frame_;
  const SceneRegions& regions_;
  YamlScene& out_;
  const int D;
  const int wall_layers_;
  const double dx_, on_, deep_;
  Point3 lattice_lo_, lattice_hi_;
  Bounds reach_;
  std::array<std::pair<long, long>, 3> range_{};
  double points_ = 1;
  // Hydrostatic starts: the water above a particle ends where neither a fluid region nor a solid is.
  Point3 up_ = Point3::Zero();
  double water_top_ = 0.0;
  bool any_free_ = false;
  long fluid_ = 0;
  std::map<const Region*, long> taken_;        // particles per fluid region and per solid region
  std::vector<std::vector<Point3>> sections_;  // each buffer's points where they meet the box
};

Lattice::Lattice(const Reader& r, const SceneFrame& frame, const SceneRegions& regions, int wall_layers, YamlScene& out)
    : r_(r),
      frame_(frame),
      regions_(regions),
      out_(out),
      D(frame.dim),
      wall_layers_(wall_layers),
      dx_(frame.dx),
      on_(kOnSurface * frame.dx),
      deep_(-wall_layers * frame.dx + kOnSurface * frame.dx),
      lattice_lo_(frame.box_lo),
      lattice_hi_(frame.box_hi),
      reach_(regions.reach),
      any_free_(std::find(regions.free.begin(), regions.free.end(), 1) != regions.free.end()),
      sections_(out.open.size()) {
  grow_by_buffers(out_.open, D, lattice_lo_, lattice_hi_, reach_, out_.file);
  set_range();
  set_water_top();
}

// The lattice over the regions' reach, within the box.
void Lattice::set_range() {
  for (int a = 0; a < D; ++a) {
    const double lo = std::max(reach_.lo[a], lattice_lo_[a]), hi = std::min(reach_.hi[a], lattice_hi_[a]);
    if (!std::isfinite(lo) || !std::isfinite(hi))
      r_.fail(regions_.list, "regions",
              std::string("reach to infinity along ") + "xyz"[a] +
                  " (a half_space); give a box to cut them, or bound them by intersection");
    range_[a] = lattice_range(lo, hi, dx_, frame_.periodic[a] != 0);
    points_ *= std::max(0L, range_[a].second - range_[a].first + 1);
  }
  if (points_ > 2e9)
    r_.fail(YAML::Node(), "",
            "spans " + number_text(points_) + " lattice points at dx = " + number_text(dx_) +
                "; raise the spacing (a smaller -nx) or cut the regions with a box");
}

void Lattice::set_water_top() {
  const Point3& g = frame_.g;
  up_ = g.norm() > 0 ? Point3(-g.normalized()) : Point3::Zero();
  for (int a = 0; a < D; ++a) water_top_ += std::max(up_[a] * frame_.box_lo[a], up_[a] * frame_.box_hi[a]);
  double shapes_top = -kInf;
  for (const auto* group : {&regions_.fluids, &regions_.solids})
    for (const Region& r : *group) shapes_top = std::max(shapes_top, r.shape->highest(up_));
  water_top_ = std::min(water_top_, shapes_top);
}

double Lattice::occupied(const Point3& y) const {
  double d = kInf;
  for (const Region& f : regions_.fluids) d = std::min(d, f.shape->distance(y));
  for (const Region& w : regions_.solids) d = std::min(d, w.shape->distance(y));
  return d;
}

Lattice::Fill Lattice::at(const Point3& x) const {
  Fill f;
  // The solids' union: its distance is the nearest part's; the last solid holding x names it.
  double solid = kInf;
  for (const Region& w : regions_.solids) {
    const double d = w.shape->distance(x);
    solid = std::min(solid, d);
    if (d <= on_) f.holder = &w;
  }
  if (!f.holder && !in_plate_gap(regions_.plates, x, dx_))
    for (const Region& fl : regions_.fluids)
      if (fl.shape->distance(x) <= on_) f.fluid = &fl;
  // A body is kept whole: it is a solid with a mass, and a hollow shell's inner face would read
  // as a wall thinner than the support where the shell curves (scene_geometry.hpp's measure).
  if (f.holder && !(solid > deep_ || f.holder->role == Role::Body)) f.holder = nullptr;
  return f;
}

Point3 Lattice::point(const std::array<long, 3>& i) const {
  Point3 x = Point3::Zero();
  for (int a = 0; a < D; ++a) x[a] = std::clamp((i[a] + 0.5) * dx_, lattice_lo_[a], lattice_hi_[a]);
  return x;
}

double Lattice::start_pressure(const Region& in, const Point3& x) const {
  return in.hydrostatic ? frame_.rho0 * frame_.g.norm() *
                              depth_below_surface([&](const Point3& y) { return occupied(y); }, x, up_, water_top_, dx_)
                        : in.pressure;
}

// The open boundary whose buffer x lies in (beyond its side of the box), or -1.
int Lattice::open_side(const Point3& x) const {
  for (std::size_t o = 0; o < out_.open.size(); ++o)
    if (out_.open[o].side * (x[out_.open[o].axis] - out_.open[o].plane) > 0) return static_cast<int>(o);
  return -1;
}

void Lattice::fill() {
  // The memory check before the particles exist, so a scene far too large is refused in well under a
  // second.
  const double share_kept = share_of_lattice_kept(range_, D, [&](const std::array<long, 3>& i) {
    const Fill f = at(point(i));
    return f.holder || f.fluid;
  });
  if (share_kept * points_ > static_cast<double>(particle_budget().limit)) refuse_over_budget();
  std::array<long, 3> i{};
  for (i[2] = D == 3 ? range_[2].first : 0; i[2] <= (D == 3 ? range_[2].second : 0); ++i[2])
    for (i[1] = range_[1].first; i[1] <= range_[1].second; ++i[1]) {
      if (out_.file.x.size() > particle_budget().limit) refuse_over_budget();
      for (i[0] = range_[0].first; i[0] <= range_[0].second; ++i[0]) add_point(point(i));
    }
  add_plate_layers(regions_.plates, regions_.solids, wall_layers_, dx_, frame_.box_lo, frame_.box_hi, out_);
  place_sections();
  out_.plate_face.resize(out_.file.x.size(), 0);
  check_filled();
}

void Lattice::add_point(const Point3& x) {
  Fill f = at(x);
  if (any_free_ && f.holder) refuse_free_body_inside(r_, regions_.solids, regions_.free, out_.bodies, x, dx_);
  if (const int o = open_side(x); o >= 0) {
    if (!f.holder) return add_buffer_particle(x, o);
    f.fluid = nullptr;  // the buffer, not the fluid regions, fills the space beyond an open side
  }
  if (!f.holder && !f.fluid) return;
  ++taken_[f.holder ? f.holder : f.fluid];
  SceneFile& s = out_.file;
  s.x.push_back({x[0], x[1], x[2]});
  if (f.holder) {
    s.v.push_back({0.0, 0.0, 0.0}), s.p.push_back(0.0), s.kind.push_back(kSceneFixedWall);
    out_.body.push_back(f.holder->body), out_.free_slip.push_back(f.holder->free_slip);
    out_.wall_pressure.push_back(f.holder->wall_pressure);
    return;
  }
  const Region& in = *f.fluid;
  const double p = start_pressure(in, x);
  s.v.push_back({in.velocity[0], in.velocity[1], in.velocity[2]});
  s.p.push_back(p), s.kind.push_back(kSceneFluid), out_.body.push_back(-1), out_.free_slip.push_back(0);
  out_.wall_pressure.push_back(-1);
  ++fluid_;
}

// A buffer particle where the fluid inside meets the side, with that fluid's start.
void Lattice::add_buffer_particle(const Point3& x, int o) {
  const OpenBoundarySpec& b = out_.open[o];
  Point3 y = x;
  y[b.axis] = b.plane - b.side * 0.5 * dx_;
  const Fill inside = at(y);
  if (!inside.fluid) return;
  const double p = b.inlet         ? start_pressure(*inside.fluid, y)
                   : b.keeps_level ? b.pressure + frame_.rho0 * frame_.g.norm() * std::max(b.level - up_.dot(x), 0.0)
                                   : b.pressure;
  const Point3& u = inside.fluid->velocity;
  SceneFile& s = out_.file;
  s.x.push_back({x[0], x[1], x[2]});
  s.v.push_back({u[0], u[1], u[2]});
  s.p.push_back(p), s.kind.push_back(b.inlet ? kSceneInlet : kSceneOutlet);
  out_.body.push_back(-1), out_.free_slip.push_back(0), out_.wall_pressure.push_back(-1);
  sections_[o].push_back(y);
}

void Lattice::place_sections() {
  for (std::size_t o = 0; o < out_.open.size(); ++o) {
    if (sections_[o].empty())
      r_.fail(regions_.open_nodes[o].first, regions_.open_nodes[o].second,
              "is an inlet or outlet where no fluid region meets the box's side; move it or the fluid");
    place_section(out_.open[o], sections_[o], regions_.solids, dx_);
    check_inlet_expressions(o);
  }
}

// An inlet's velocity expressions at the points where its buffer meets the fluid: finite, into the box
// (or along its side) at every one of them; and their largest speed, which sets the reference speed U,
// over a grid of an eighth of a spacing across the section (at the lattice's points alone a parabola's
// peak read 0.9975 for 1 at nx 20).
void Lattice::check_inlet_expressions(std::size_t o) {
  OpenBoundarySpec& b = out_.open[o];
  if (b.expressions.empty()) return;
  const std::string key = regions_.open_nodes[o].second + ".velocity.expression";
  for (const Point3& y : sections_[o]) {
    Point3 u = Point3::Zero();
    for (std::size_t a = 0; a < b.expressions.size(); ++a) u[a] = b.expressions[a](y[0], y[1], y[2], 0.0);
    const std::string where = "at (" + number_text(y[0]) + ", " + number_text(y[1]) +
                              (D == 3 ? ", " + number_text(y[2]) : std::string()) + ")";
    if (!u.allFinite())
      r_.fail(regions_.open_nodes[o].first, key, "is not a finite number " + where + "; check the expressions");
    if (-b.side * u[b.axis] < 0)
      r_.fail(regions_.open_nodes[o].first, key,
              "points out of the box " + where + " (" + std::string(1, "xyz"[b.axis]) + " component " +
                  number_text(u[b.axis]) + "); an inlet's velocity must point into the box");
  }
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < D; ++a)
    if (a != b.axis) n[a] = 1 + static_cast<int>(std::ceil((b.section_hi[a] - b.section_lo[a]) / (dx_ / 8)));
  for (int i = 0; i < n[0] * n[1] * n[2]; ++i) {
    Point3 y = Point3::Zero(), u = Point3::Zero();
    const std::array<int, 3> k{i % n[0], (i / n[0]) % n[1], i / (n[0] * n[1])};
    for (int a = 0; a < D; ++a)
      y[a] = a == b.axis ? b.plane - b.side * 0.5 * dx_
                         : b.section_lo[a] + (b.section_hi[a] - b.section_lo[a]) * k[a] / std::max(n[a] - 1, 1);
    for (std::size_t a = 0; a < b.expressions.size(); ++a) u[a] = b.expressions[a](y[0], y[1], y[2], 0.0);
    if (u.allFinite()) b.top_speed = std::max(b.top_speed, u.norm());
  }
}

void Lattice::check_filled() {
  if (fluid_ == 0)
    r_.fail(regions_.list, "regions",
            "hold no fluid particle at dx = " + number_text(dx_) +
                ": no lattice point lies inside a fluid region, outside the solids and inside the box; refine "
                "(a larger -nx) or move the fluid regions");
  std::map<const Region*, double> kept;  // per fluid region and body region: the area (volume) it keeps
  for (const Region& f : regions_.fluids)
    kept[&f] =
        kept_measure(*f.shape, frame_.box_lo, frame_.box_hi, D, [&](const Point3& x) { return at(x).fluid == &f; });
  for (const Region& w : regions_.solids)
    if (w.role == Role::Body)
      kept[&w] =
          kept_measure(*w.shape, frame_.box_lo, frame_.box_hi, D, [&](const Point3& x) { return at(x).holder == &w; });
  check_regions_filled(r_, regions_.fluids, regions_.solids, regions_.plates, out_.bodies, taken_, kept, dx_);
}

}  // namespace

// Per body, 1 where the fluid moves it; such a body in a scene without fluid, or with a plate, is
// refused (a plate moves only with a prescribed motion: MovingBodies moves its screen).
std::vector<char> free_bodies(const Reader& r, const std::vector<Region>& solids, const std::vector<Region>& fluids,
                              const std::vector<Region>& plates, const std::vector<MotionSpec>& motions,
                              const std::vector<std::string>& names) {
  std::vector<char> free(motions.size(), 0);
  for (const Region& p : plates)
    if (p.role == Role::Body && motions[p.body].type == "free")
      r.fail(p.at, p.key,
             "is a plate of free body '" + names[p.body] +
                 "'; a plate moves only with a prescribed motion (a free body needs the kernel's support in "
                 "thickness)");
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

void fill_lattice(const Reader& r, const SceneFrame& frame, const SceneRegions& regions, int wall_layers,
                  YamlScene& out) {
  Lattice(r, frame, regions, wall_layers, out).fill();
}

}  // namespace sph::scene_detail
