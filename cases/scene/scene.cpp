#include "cases/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "cases/common/lattice.hpp"
#include "cases/scene/scene_geometry.hpp"
#include "cases/scene/scene_yaml.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/kernels/kernel_options.hpp"

namespace sph {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

template <int D> std::string point(const Vector<D>& x) {
  std::string s = "(";
  for (int a = 0; a < D; ++a) s += (a ? ", " : "") + number(x[a]);
  return s + ")";
}

// Axis flags from "x,y", "z", "none".
template <int D> std::array<bool, D> parse_axes(const std::string& text) {
  std::array<bool, D> flags{};
  if (text == "none") return flags;
  std::stringstream in(text);
  std::string axis;
  while (std::getline(in, axis, ',')) {
    const std::size_t a = std::string("xyz").find(axis);
    if (axis.size() != 1 || a == std::string::npos || static_cast<int>(a) >= D)
      throw Error("-scene_periodic must list axes of this " + std::to_string(D) + "D scene, e.g. " +
                  (D == 2 ? "x or x,y" : "x or x,y,z") + ", or none (got '" + text + "')");
    flags[a] = true;
  }
  return flags;
}

PetscErrorCode read_options(SceneOptions* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Scene from a file (-case scene)", "Case");
  PetscCall(option_string(PetscOptionsObject, "-scene_file",
                          "VTK XML PolyData (.vtp) scene: point arrays kind (0 fluid, 1 fixed wall, 2 "
                          "moving wall), velocity, pressure; parameters as field data. Or a YAML (.yaml, "
                          ".yml) scene of shapes, sampled at the run's spacing",
                          o->path, o->path, sizeof(o->path), nullptr));
  PetscCall(option_int(PetscOptionsObject, "-nx", "YAML scenes: particles per unit length, dx = 1/nx", o->nx, &o->nx,
                       &o->nx_set));
  PetscCall(option_real(PetscOptionsObject, "-scene_dx", "Particle spacing (overrides the file's field data dx)", o->dx,
                        &o->dx, &o->dx_set));
  PetscCall(option_reals(PetscOptionsObject, "-scene_box",
                         "Box xmin,xmax,ymin,ymax[,zmin,zmax] (overrides field data box; default: "
                         "the particles' bounding box grown by dx/2)",
                         o->box, &o->box_n, &o->box_set));
  PetscCall(option_string(PetscOptionsObject, "-scene_periodic",
                          "Periodic axes, e.g. x or x,y, or none (overrides field data periodic)", o->periodic,
                          o->periodic, sizeof(o->periodic), &o->periodic_set));
  PetscCall(option_reals(PetscOptionsObject, "-gravity",
                         "Body force per unit mass gx,gy[,gz] (overrides field data gravity; default 0)", o->gravity,
                         &o->gravity_n, &o->gravity_set));
  PetscCall(option_real(PetscOptionsObject, "-nu", "Kinematic viscosity (overrides field data nu; default 0)", o->nu,
                        &o->nu, &o->nu_set));
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density (overrides field data rho0; default 1)", o->rho0,
                        &o->rho0, &o->rho0_set));
  PetscCall(option_real(PetscOptionsObject, "-U",
                        "Reference speed (overrides field data U; default: the largest particle speed or the "
                        "free-fall speed over the fluid's height)",
                        o->U, &o->U, &o->U_set));
  PetscCall(option_bool(PetscOptionsObject, "-free_surface",
                        "Free surface (overrides field data free_surface; default: on when some fluid "
                        "particle lies on an open face of the scene)",
                        o->free_surface, &o->free_surface, &o->free_surface_set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

template <int D> std::vector<Probe<D>> probes_of(const std::vector<ProbeSpec>& specs) {
  std::vector<Probe<D>> probes;
  for (const ProbeSpec& spec : specs) {
    Probe<D> probe{spec.name};
    for (int a = 0; a < D; ++a) probe.at[a] = spec.at[a];
    probes.push_back(probe);
  }
  return probes;
}

// A body's motion as the run moves it: angles in radians, tables as splines; a free body's none.
template <int D> PrescribedMotion<D> motion_of(const MotionSpec& spec) {
  PrescribedMotion<D> m;
  using Type = typename PrescribedMotion<D>::Type;
  auto type_of = [](const std::string& name) {
    return name == "constant"     ? Type::Constant
           : name == "sinusoidal" ? Type::Sinusoidal
           : name == "table"      ? Type::Table
                                  : Type::Fixed;
  };
  m.type = type_of(spec.type);
  if (m.type == Type::Table)
    for (int a = 0; a < D; ++a) m.table_position.emplace_back(spec.table_t, spec.table_x[a]);
  for (int a = 0; a < D; ++a) m.velocity[a] = spec.velocity[a], m.amplitude[a] = spec.amplitude[a];
  m.period = spec.period, m.phase = spec.phase_degrees * M_PI / 180.0;
  m.spin = type_of(spec.spin);
  const double degree = M_PI / 180.0;
  if (m.spin == Type::Table) {
    std::vector<double> radians;
    for (double a : spec.table_angle_degrees) radians.push_back(a * degree);
    m.table_angle = CubicSpline(spec.table_t, radians);
  }
  m.rate = spec.rate_degrees * degree, m.angle = spec.angle_degrees * degree;
  m.spin_period = spec.spin_period, m.spin_phase = spec.spin_phase_degrees * degree;
  for (int a = 0; a < D; ++a) m.centre[a] = spec.centre[a];
  m.axis = Eigen::Vector3d(spec.axis[0], spec.axis[1], spec.axis[2]);
  if (spec.type == "free") m = PrescribedMotion<D>{};  // the fluid moves it
  return m;
}

}  // namespace

template <int D> void SceneCase<D>::set_from_options() {
  opt_.box_n = 6, opt_.gravity_n = 3;
  SPH_PETSC(read_options(&opt_));
  if (!opt_.path[0])
    throw Error(
        "-case scene needs -scene_file FILE (a YAML scene of shapes such as cases/scenes/falling_block.yaml, "
        "or a VTK .vtp scene; scripts/make-scene writes examples)");
  read_file();
  if (file_.dim != D && yaml_)
    throw Error(file_.error("has dimension: " + std::to_string(file_.dim) + ", not " + std::to_string(D) +
                            "; drop -dim, the scene's dimension comes from the file"));
  if (file_.dim != D)
    throw Error(file_.error("holds " + std::to_string(file_.dim) + "D points (" +
                            (file_.dim == 2 ? "all z equal" : "z varies") + "), not " + std::to_string(D) +
                            "D; drop -dim, the scene's dimension comes from its points"));
  resolve_parameters();
  check_particles_in_box();

  // Free surface and wall thickness from the particles' arrangement (every rank, the whole scene). A
  // thin plate's layers stand for a solid beside each face that the arrangement does not show (they
  // overlap the other side's fluid): left out here. They come last (add_plate_layers), so the indices
  // of x are file_'s.
  std::vector<Vector<D>> x;
  std::vector<int> kind;
  for (std::size_t i = 0; i < file_.x.size(); ++i) {
    if (!plate_face_.empty() && plate_face_[i] != 0) continue;
    Vector<D> xi;
    for (int a = 0; a < D; ++a) xi[a] = file_.x[i][a];
    x.push_back(xi);
    kind.push_back(file_.kind[i] == kSceneFluid ? kFluid : kWall);  // a buffer closes the fluid as a wall does
  }
  const PointGrid<D> grid(x, box_, dx_);
  const std::vector<int> count = neighbour_counts(grid, x, dx_);
  free_surface_detected_ = has_open_fluid_face<D>(count, kind);
  check_moving_walls(grid, x);
  const WallThickness w = measure_wall_thickness(grid, x, kind, count, dx_);
  walls_ = w.thickness;
  thinnest_at_ = x[w.particle];
  if (!free_surface_given_) physics_.free_surface = free_surface_detected_;
}

template <int D> void SceneCase<D>::read_file() {
  yaml_ = is_yaml_scene(opt_.path);
  if (!yaml_) {
    if (opt_.nx_set)
      throw Error("-nx sets the spacing of YAML scenes; the particles of '" + std::string(opt_.path) +
                  "' are fixed: remove -nx (the spacing is its field data dx, or -scene_dx)");
    file_ = read_scene_file(opt_.path);
    free_slip_ = file_.free_slip;
    return;
  }
  if (opt_.nx_set && opt_.dx_set) throw Error("-nx and -scene_dx both set the particle spacing; give one of them");
  if (opt_.nx_set) require(opt_.nx >= 1, "-nx", "at least 1", opt_.nx);
  if (opt_.dx_set) require(opt_.dx > 0, "-scene_dx", "positive", opt_.dx);
  // Walls as deep as the kernel's support, the depth the run checks them against (TimeLoop). A scheme's
  // own default (Solver::default_kernel) is no wider than the general one read here.
  const KernelChoice kernel = read_kernel_options();
  const double support_dx = kernel.resolved_h_over_dx<D>() * Kernel<D>::support_factor(kernel.type);
  const int layers = static_cast<int>(std::ceil(support_dx - 1e-9));
  YamlScene scene = read_yaml_scene(opt_.path, opt_.nx_set ? 1.0 / opt_.nx : opt_.dx_set ? opt_.dx : 0.0, layers);
  file_ = std::move(scene.file);
  body_ = std::move(scene.body);
  if (std::find(scene.free_slip.begin(), scene.free_slip.end(), 1) != scene.free_slip.end())
    free_slip_ = std::move(scene.free_slip);
  if (std::find_if(scene.wall_pressure.begin(), scene.wall_pressure.end(), [](signed char c) { return c >= 0; }) !=
      scene.wall_pressure.end())
    wall_pressure_ = std::move(scene.wall_pressure);
  surfaces_ = std::move(scene.surfaces);
  probes_ = probes_of<D>(scene.probes);
  if (!scene.plates.empty()) {
    plate_face_ = std::move(scene.plate_face);
    for (std::size_t k = 0; k < scene.plates.size(); ++k) {
      const auto& q = scene.plates[k];
      typename Screens<D>::Plate plate;
      for (int a = 0; a < D; ++a) plate.a[a] = a < 2 ? q[a] : 0.0, plate.b[a] = a < 2 ? q[2 + a] : 0.0;
      plate.body = scene.plate_body[k];
      plates_.push_back(plate);
    }
  }
  for (const MotionSpec& spec : scene.motions) motions_.push_back(motion_of<D>(spec));
  free_ = free_bodies_of(scene.motions, file_.field["dx"].at(0));
  bodies_ = std::move(scene.bodies);
  for (const OpenBoundarySpec& spec : scene.open) {
    OpenBoundary<D> b;
    b.type = spec.inlet ? OpenBoundary<D>::Type::Inlet : OpenBoundary<D>::Type::Outlet;
    b.axis = spec.axis, b.side = spec.side, b.plane = spec.plane, b.depth = spec.depth, b.pressure = spec.pressure;
    b.keeps_level = spec.keeps_level, b.level = spec.level;
    for (int a = 0; a < D; ++a)
      b.section_lo[a] = spec.section_lo[a], b.section_hi[a] = spec.section_hi[a],
      b.inflow.velocity[a] = spec.velocity[a];
    if (spec.peak > 0) b.inflow.profile = InletVelocity<D>::Profile::Parabolic, b.inflow.peak = spec.peak;
    if (!spec.expressions.empty())
      b.inflow.profile = InletVelocity<D>::Profile::Expressions, b.inflow.expressions = spec.expressions,
      b.inflow.expressions_top = spec.top_speed;
    b.inflow.ramp = spec.ramp;
    b.inflow.table_t = spec.speed_t, b.inflow.table_factor = spec.speed_factor;
    open_.push_back(b);
  }
}

// The free bodies' mass, centre of mass and inertia from their particles as laid out, each the centre
// of a lattice cell of side dx (so a cell's own inertia, m dx^2 / 6 about each axis, adds to m r^2).
template <int D>
std::vector<FreeBody<D>> SceneCase<D>::free_bodies_of(const std::vector<MotionSpec>& specs, double dx) const {
  std::vector<FreeBody<D>> free(specs.size());
  const double cell = std::pow(dx, D);
  for (std::size_t b = 0; b < specs.size(); ++b) {
    const MotionSpec& spec = specs[b];
    if (spec.type != "free") continue;
    FreeBody<D>& f = free[b];
    f.active = true;
    double volume = 0.0;
    Vector<D> sum = Vector<D>::Zero();
    std::vector<Vector<D>> x;
    for (std::size_t i = 0; i < body_.size(); ++i)
      if (body_[i] == static_cast<int>(b)) {
        Vector<D> xi;
        for (int a = 0; a < D; ++a) xi[a] = file_.x[i][a];
        x.push_back(xi), sum += xi, volume += cell;
      }
    if (x.empty()) continue;  // refused by the scene's geometry check
    const double density = spec.mass > 0 ? spec.mass / volume : spec.density;
    const double m = density * cell;
    f.mass = density * volume, f.volume = volume, f.particles = static_cast<long>(x.size());
    f.centre0 = f.centre = sum / static_cast<double>(x.size());
    for (const Vector<D>& xi : x) {
      const Eigen::Vector3d r = FreeBody<D>::lift(Vector<D>(xi - f.centre0));
      f.reach = std::max(f.reach, r.norm());
      f.inertia += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    const double own = m * dx * dx / 6.0;  // a cell's inertia about its centre: m (dx^2 + dx^2) / 12
    f.inertia += static_cast<double>(x.size()) * own * Eigen::Matrix3d::Identity();
    for (int a = 0; a < D; ++a) {
      f.fixed_translation[a] = spec.fixed_translation[a];
      f.velocity[a] = spec.fixed_translation[a] ? 0.0 : spec.velocity[a];
    }
    f.fixed_rotation = spec.fixed_rotation;
    for (int a = 0; a < 3; ++a) f.omega[a] = spec.fixed_rotation[a] ? 0.0 : spec.rate3_degrees[a] * M_PI / 180.0;
    if (D == 2) f.omega[0] = f.omega[1] = 0.0;
    f.hinged = spec.hinged;
    if (f.hinged) {
      for (int a = 0; a < D; ++a) f.hinge[a] = spec.hinge[a];
      f.hinge_axis = D == 2 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(spec.axis[0], spec.axis[1], spec.axis[2]);
      f.omega = f.omega.dot(f.hinge_axis) * f.hinge_axis;
      f.velocity = f.omega.cross(FreeBody<D>::lift(Vector<D>(f.centre - f.hinge))).template head<D>();
    }
  }
  return free;
}

template <int D> void SceneCase<D>::resolve_parameters() {
  resolve_spacing();
  resolve_box();
  resolve_physics();
  resolve_reference_speed();
}

// The field data `name`, checked to hold `want` finite values (`shape` says them); null when absent.
template <int D>
const std::vector<double>* SceneCase<D>::field(const char* name, std::size_t want, const std::string& shape) const {
  const auto it = file_.field.find(name);
  if (it == file_.field.end()) return nullptr;
  if (it->second.size() != want)
    throw Error(file_.error(std::string("field data '") + name + "' has " + std::to_string(it->second.size()) +
                            " values; give " + shape));
  for (double value : it->second)
    if (!std::isfinite(value))
      throw Error(
          file_.error(std::string("field data '") + name + "' holds " + number(value) + "; give a finite number"));
  return &it->second;
}

// An option's value where it was set, else the field data's, else the fallback.
template <int D> double SceneCase<D>::scalar(const char* name, PetscBool set, double opt, double fallback) const {
  if (set) return opt;
  const std::vector<double>* f = field(name, 1, "one");
  return f ? (*f)[0] : fallback;
}

template <int D> void SceneCase<D>::resolve_spacing() {
  dx_ = scalar("dx", opt_.dx_set, opt_.dx, 0.0);
  if (!opt_.dx_set && !file_.field.count("dx"))
    throw Error(file_.error("gives no particle spacing; add field data 'dx' or pass -scene_dx"));
  require(dx_ > 0, opt_.dx_set ? "-scene_dx" : "the scene's field data dx", "positive", dx_);
  // A .vtp scene's particles are fixed: a spacing far from theirs gives a kernel that reaches no
  // neighbour (or all of them), and the run goes on without its particles interacting.
  if (!yaml_) {
    const double measured = median_spacing(file_);
    if (measured > 0 && (dx_ < 0.5 * measured || dx_ > 2.0 * measured)) {
      const std::string given = opt_.dx_set ? "-scene_dx " + number(dx_) : "its field data dx " + number(dx_);
      throw Error(file_.error(
          "its particles lie " + number(measured) + " apart (median nearest-neighbour distance), but " + given +
          (opt_.dx_set ? " is given" : " says otherwise") + "; " +
          (opt_.dx_set ? "pass -scene_dx " + number(measured) + " or leave it out"
                       : "set field data dx to " + number(measured) + " or pass -scene_dx " + number(measured))));
    }
  }
}

template <int D> void SceneCase<D>::resolve_box() {
  // Box: option, field data, or the particles' bounding box grown by half a spacing.
  const std::vector<double>* box = nullptr;
  std::vector<double> box_values;
  if (opt_.box_set) {
    if (opt_.box_n != 2 * D)
      throw Error("-scene_box needs " + std::to_string(2 * D) + " values for this " + std::to_string(D) +
                  "D scene (xmin,xmax,ymin,ymax" + (D == 3 ? ",zmin,zmax" : "") + "), got " +
                  std::to_string(opt_.box_n));
    box_values.assign(opt_.box, opt_.box + 2 * D);
    box = &box_values;
  } else {
    box = field("box", 2 * D, std::to_string(2 * D) + " (xmin, xmax, ...)");
  }
  if (opt_.periodic_set) {
    box_.periodic = parse_axes<D>(opt_.periodic);
  } else if (const std::vector<double>* p = field("periodic", D, "one 0/1 flag per axis")) {
    for (int a = 0; a < D; ++a) box_.periodic[a] = (*p)[a] != 0.0;
  }
  if (box) {
    for (int a = 0; a < D; ++a) {
      box_.lo[a] = (*box)[2 * a], box_.hi[a] = (*box)[2 * a + 1];
      if (!(box_.hi[a] > box_.lo[a]))
        throw Error((opt_.box_set ? std::string("-scene_box") : file_.error("field data 'box'")) +
                    " has max <= min along " + "xyz"[a] + "; give xmin,xmax,ymin,ymax" + (D == 3 ? ",zmin,zmax" : ""));
    }
  } else {
    for (int a = 0; a < D; ++a) {
      if (box_.periodic[a])
        throw Error(file_.error(std::string("is periodic along ") + "xyz"[a] +
                                " but gives no box to set the period; add field data 'box' or pass -scene_box"));
      box_.lo[a] = box_.hi[a] = file_.x[0][a];
      for (const auto& x : file_.x) box_.lo[a] = std::min(box_.lo[a], x[a]), box_.hi[a] = std::max(box_.hi[a], x[a]);
      box_.lo[a] -= 0.5 * dx_, box_.hi[a] += 0.5 * dx_;
    }
  }
}

template <int D> void SceneCase<D>::resolve_physics() {
  const std::string vec = D == 2 ? "2 (x, y)" : "3 (x, y, z)";
  physics_.rho0 = scalar("rho0", opt_.rho0_set, opt_.rho0, 1.0);
  require(physics_.rho0 > 0, opt_.rho0_set ? "-rho0" : "the scene's field data rho0", "positive", physics_.rho0);
  physics_.nu = scalar("nu", opt_.nu_set, opt_.nu, 0.0);
  require(physics_.nu >= 0, opt_.nu_set ? "-nu" : "the scene's field data nu", "non-negative", physics_.nu);
  t_end_ = scalar("t_end", PETSC_FALSE, 0.0, 1.0);
  // Named here, where it comes from: -t_end's own check would blame an option the user never gave.
  PetscBool t_end_given = PETSC_FALSE;
  SPH_PETSC(PetscOptionsHasName(nullptr, nullptr, "-t_end", &t_end_given));
  if (!t_end_given) require(t_end_ > 0, "the scene's field data t_end", "positive (or pass -t_end)", t_end_);
  if (opt_.gravity_set) {
    if (opt_.gravity_n != D)
      throw Error("-gravity needs " + std::to_string(D) + " values for this " + std::to_string(D) + "D scene, got " +
                  std::to_string(opt_.gravity_n));
    for (int a = 0; a < D; ++a) physics_.gravity[a] = opt_.gravity[a];
  } else if (const std::vector<double>* g = field("gravity", D, vec)) {
    for (int a = 0; a < D; ++a) physics_.gravity[a] = (*g)[a];
  }
  if (opt_.free_surface_set) physics_.free_surface = opt_.free_surface;
  else if (const std::vector<double>* f = field("free_surface", 1, "one (0 or 1)"))
    physics_.free_surface = (*f)[0] != 0.0;
  free_surface_given_ = opt_.free_surface_set || file_.field.count("free_surface");
}

template <int D> void SceneCase<D>::resolve_reference_speed() {
  // Reference speed: given, else the fastest particle or the fall over the fluid's height.
  double U = 0.0, lo = 1e300, hi = -1e300;
  const double g = physics_.gravity.norm();
  for (std::size_t i = 0; i < file_.x.size(); ++i) {
    if (file_.kind[i] == kSceneFixedWall) continue;
    Vector<D> v, x;
    for (int a = 0; a < D; ++a) v[a] = file_.v[i][a], x[a] = file_.x[i][a];
    U = std::max(U, v.norm());
    if (file_.kind[i] == kSceneFluid && g > 0)
      lo = std::min(lo, x.dot(physics_.gravity) / g), hi = std::max(hi, x.dot(physics_.gravity) / g);
  }
  if (g > 0) U = std::max(U, std::sqrt(2.0 * g * (hi - lo + dx_)));
  // Moving bodies: their fastest point, the farthest from the rotation's axis (or centre).
  std::vector<double> reach(motions_.size(), 0.0);
  for (std::size_t i = 0; i < body_.size(); ++i)
    if (body_[i] >= 0) {
      Vector<D> x;
      for (int a = 0; a < D; ++a) x[a] = file_.x[i][a];
      const PrescribedMotion<D>& m = motions_[static_cast<std::size_t>(body_[i])];
      Eigen::Vector3d r3 = Eigen::Vector3d::Zero();
      r3.head<D>() = x - m.centre;
      reach[static_cast<std::size_t>(body_[i])] =
          std::max(reach[static_cast<std::size_t>(body_[i])], (r3 - r3.dot(m.axis) * m.axis).norm());
    }
  for (std::size_t b = 0; b < motions_.size(); ++b) U = std::max(U, motions_[b].top_speed(reach[b]));
  // Inlets: their full speed, at their speed table's largest factor.
  for (const OpenBoundary<D>& b : open_) U = std::max(U, b.inflow.top_speed());
  physics_.U = opt_.U_set ? opt_.U : scalar("U", PETSC_FALSE, 0.0, U);
  if (!(physics_.U > 0))
    throw Error(opt_.U_set || file_.field.count("U")
                    ? "the reference speed U must be positive (got " + number(physics_.U) + ")"
                    : file_.error(std::string("sets no reference speed and nothing moves (no velocity, no "
                                              "gravity); ") +
                                  (yaml_ ? "add U: (a reference speed) to the file" : "add field data 'U'") +
                                  " or pass -U"));
}

// Walls keep their place: a moving wall (kind 2) only slides along itself, its velocity the no-slip
// condition's. A velocity towards or away from the fluid beside it (within 25 degrees of the normal
// that the fluid within 3 dx gives) would be ignored: the particle would neither move nor push.
template <int D>
void SceneCase<D>::check_moving_walls(const PointGrid<D>& grid, const std::vector<Vector<D>>& x) const {
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (file_.kind[i] != kSceneMovingWall) continue;
    Vector<D> v;
    for (int a = 0; a < D; ++a) v[a] = file_.v[i][a];
    if (v.norm() == 0) continue;
    Vector<D> towards_fluid = Vector<D>::Zero();
    grid.for_each_within(x[i], 3 * dx_, [&](int j, const Vector<D>& d) {
      if (file_.kind[j] == kSceneFluid) towards_fluid += d.normalized();
    });
    if (towards_fluid.norm() == 0) continue;
    const double cosine = std::abs(v.dot(towards_fluid.normalized())) / v.norm();
    if (cosine > std::cos(25 * M_PI / 180))
      throw Error(file_.error("moving-wall particle " + std::to_string(i) + " at " + point<D>(x[i]) + " has velocity " +
                              point<D>(v) + ", " + number(std::round(std::acos(cosine) * 180 / M_PI)) +
                              " degrees from the normal of the fluid beside it; walls keep their place and a moving "
                              "wall (kind 2) slides along itself: give it a velocity along its wall"));
  }
}

template <int D> void SceneCase<D>::check_particles_in_box() const {
  for (std::size_t i = 0; i < file_.x.size(); ++i)
    for (int a = 0; a < D; ++a) {
      const double x = file_.x[i][a];
      // Periodic axes hold [lo, hi): hi is the image of lo.
      if (x < box_.lo[a] || x > box_.hi[a] || (box_.periodic[a] && x >= box_.hi[a])) {
        Vector<D> p;
        for (int b = 0; b < D; ++b) p[b] = file_.x[i][b];
        throw Error(file_.error("particle " + std::to_string(i) + " at " + point<D>(p) + " lies outside the box [" +
                                number(box_.lo[a]) + ", " + number(box_.hi[a]) + (box_.periodic[a] ? ")" : "]") +
                                " along " + "xyz"[a] +
                                "; enlarge the box (field data 'box' or -scene_box) or move the particle"));
      }
    }
}

// A level-keeping outlet's hydrostatic pressure takes the run's density and gravity (-rho0, -gravity
// included), and its section reaches up without end: the water may rise above where it started.
template <int D> std::vector<OpenBoundary<D>> SceneCase<D>::open_boundaries() const {
  std::vector<OpenBoundary<D>> open = open_;
  for (OpenBoundary<D>& b : open) {
    b.rho0 = physics_.rho0, b.gravity = physics_.gravity;
    if (!b.keeps_level) continue;
    for (int a = 0; a < D; ++a) {
      if (physics_.gravity[a] < 0) b.section_hi[a] = std::numeric_limits<double>::infinity();
      if (physics_.gravity[a] > 0) b.section_lo[a] = -std::numeric_limits<double>::infinity();
    }
  }
  return open;
}

template <int D> void SceneCase<D>::create(Particles<D>& P, Domain<D>& domain) const {
  domain = box_;
  const double mass = physics_.rho0 * std::pow(dx_, D);
  Particles<D> all;
  for (std::size_t i = 0; i < file_.x.size(); ++i) {
    Vector<D> x, v = Vector<D>::Zero();
    for (int a = 0; a < D; ++a) x[a] = file_.x[i][a];
    if (file_.kind[i] != kSceneFixedWall)
      for (int a = 0; a < D; ++a) v[a] = file_.v[i][a];
    const int kind = file_.kind[i] == kSceneFluid    ? kFluid
                     : file_.kind[i] == kSceneInlet  ? kInlet
                     : file_.kind[i] == kSceneOutlet ? kOutlet
                                                     : kWall;
    all.add(x, v, mass, physics_.rho0, file_.p[i], kind);
  }
  // The inlets' velocity at t = 0 (the time loop prescribes it at every step).
  OpenBoundaries<D>(open_).prescribe(all, 0.0);
  P = rank_share(all);
  if (!plates_.empty()) domain.screens = std::make_shared<Screens<D>>(plates_, plate_face_);
}

template <int D> int SceneCase<D>::resolution() const { return std::max(1, static_cast<int>(std::lround(1.0 / dx_))); }

template <int D> std::string SceneCase<D>::output_name() const {
  return "scene_" + std::filesystem::path(file_.path).stem().string();
}

template <int D> std::string SceneCase<D>::thin_walls(double thickness_dx, double support_dx) const {
  const std::string fix = yaml_ ? "the solid there is thinner than the support at this spacing: thicken it (a "
                                  "solid may run past the box), raise -nx or lower -h_over_dx"
                                : "add wall layers (scripts/make-scene --wall-layers) or lower -h_over_dx";
  return file_.error("the walls near " + point<D>(thinnest_at_) + " are " + number(thickness_dx) +
                     " dx thick, thinner than the kernel support (" + number(support_dx) + " dx); " + fix);
}

template <int D> nlohmann::json SceneCase<D>::parameters() const {
  char checksum[20];
  std::snprintf(checksum, sizeof checksum, "%016llx", static_cast<unsigned long long>(file_.checksum));
  long counts[5] = {0, 0, 0, 0, 0};
  for (int k : file_.kind) ++counts[k];
  std::vector<double> box;
  std::vector<int> periodic;
  for (int a = 0; a < D; ++a)
    box.push_back(box_.lo[a]), box.push_back(box_.hi[a]), periodic.push_back(box_.periodic[a]);
  nlohmann::json bodies = nlohmann::json::object();  // YAML scenes: wall particles per named body
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    bodies[bodies_[b]] = std::count(body_.begin(), body_.end(), static_cast<int>(b));
  nlohmann::json p = {{"scene_file", file_.path},
                      {"scene_checksum", checksum},
                      {"dx", dx_},
                      {"box", box},
                      {"periodic", periodic},
                      {"gravity", std::vector<double>(physics_.gravity.data(), physics_.gravity.data() + D)},
                      {"nu", physics_.nu},
                      {"rho0", physics_.rho0},
                      {"U", physics_.U},
                      {"free_surface", physics_.free_surface},
                      {"free_surface_detected", free_surface_detected_},
                      {"fluid_particles", counts[kSceneFluid]},
                      {"fixed_wall_particles", counts[kSceneFixedWall]},
                      {"moving_wall_particles", counts[kSceneMovingWall]},
                      {"wall_thickness_dx", walls_ / dx_}};
  if (!bodies_.empty()) p["bodies"] = bodies;
  if (!open_.empty()) p["inlet_particles"] = counts[kSceneInlet], p["outlet_particles"] = counts[kSceneOutlet];
  for (const Probe<D>& probe : probes_)
    p["probes"][probe.name] = std::vector<double>(probe.at.data(), probe.at.data() + D);
  return p;
}

int scene_file_dimension() {
  char path[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  SPH_PETSC(PetscOptionsGetString(nullptr, nullptr, "-scene_file", path, sizeof(path), &set));
  if (!set || !path[0]) return 2;
  return is_yaml_scene(path) ? yaml_scene_dimension(path) : read_scene_file(path).dim;
}

template class SceneCase<2>;
template class SceneCase<3>;

}  // namespace sph
