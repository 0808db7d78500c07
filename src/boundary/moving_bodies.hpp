#pragma once
// Bodies whose motion is prescribed as a function of time: a translation (constant velocity, or
// sinusoidal, A (sin(w t + phi) - sin phi), which starts at rest for phi = -90 degrees) and a rotation
// about an axis through a point that moves with it (constant rate, or a sinusoidal angle), or both
// from a table (src/boundary/motion_table.hpp). Their wall particles are moved by the solvers at their drift, and the
// wall condition sees the body's velocity and acceleration: Adami et al. (2012)'s pressure extrapolation takes (g -
// a_w), the continuity equation (WCSPH) and the pressure source (ISPH) the wall's velocity. Membership is by permanent
// particle id, as for the force groups (src/run/wall_groups.hpp). The same object holds the other wall conditions a
// case may ask of its wall groups: which wall particles are free-slip (free_slip()) and how a group's pressure
// continues the fluid's (wall_pressure(), src/boundary/adami_wall_model.hpp). A body may instead be free
// (src/boundary/free_body.hpp): the fluid moves it, and its state travels in the checkpoint (state(), restore()).
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "src/boundary/free_body.hpp"
#include "src/boundary/motion_table.hpp"
#include "src/neighbours/screens.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D> struct PrescribedMotion {
  enum class Type { Fixed, Constant, Sinusoidal, Table };
  // The translation of the body's points.
  Type type = Type::Fixed;
  Vector<D> velocity = Vector<D>::Zero();   // Constant
  Vector<D> amplitude = Vector<D>::Zero();  // Sinusoidal: A (sin(2 pi t / T + phase) - sin phase)
  double period = 1.0, phase = 0.0;         // phase in radians
  // A rotation by the angle theta(t) about the axis through centre + displacement(t): Constant,
  // theta = rate t; Sinusoidal, theta = angle (sin(2 pi t / spin_period + spin_phase) - sin spin_phase).
  Type spin = Type::Fixed;
  double rate = 0.0, angle = 0.0, spin_period = 1.0, spin_phase = 0.0;  // radians
  Vector<D> centre = Vector<D>::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit; 2D: z
  // Table (for the translation and the spin): splines of each coordinate and of the angle (radians);
  // the displacement and angle are taken from the table's first row.
  std::vector<CubicSpline> table_position;
  CubicSpline table_angle;

  bool moves() const { return type != Type::Fixed || spin != Type::Fixed; }
  double omega() const { return 2.0 * M_PI / period; }
  double spin_omega() const { return 2.0 * M_PI / spin_period; }

  Vector<D> displacement(double t) const {
    if (type == Type::Constant) return t * velocity;
    if (type == Type::Sinusoidal) return (std::sin(omega() * t + phase) - std::sin(phase)) * amplitude;
    if (type == Type::Table) return from_table(t, 0) - from_table(table_position[0].first_time(), 0);
    return Vector<D>::Zero();
  }
  Vector<D> velocity_at(double t) const {
    if (type == Type::Constant) return velocity;
    if (type == Type::Sinusoidal) return omega() * std::cos(omega() * t + phase) * amplitude;
    if (type == Type::Table) return from_table(t, 1);
    return Vector<D>::Zero();
  }
  Vector<D> acceleration(double t) const {
    if (type == Type::Sinusoidal) return -omega() * omega() * std::sin(omega() * t + phase) * amplitude;
    if (type == Type::Table) return from_table(t, 2);
    return Vector<D>::Zero();
  }
  double angle_at(double t) const {
    if (spin == Type::Constant) return rate * t;
    if (spin == Type::Sinusoidal) return angle * (std::sin(spin_omega() * t + spin_phase) - std::sin(spin_phase));
    if (spin == Type::Table) return table_angle(t) - table_angle(table_angle.first_time());
    return 0.0;
  }
  double angular_velocity(double t) const {
    if (spin == Type::Constant) return rate;
    if (spin == Type::Sinusoidal) return angle * spin_omega() * std::cos(spin_omega() * t + spin_phase);
    if (spin == Type::Table) return table_angle(t, 1);
    return 0.0;
  }
  double angular_acceleration(double t) const {
    if (spin == Type::Sinusoidal) return -angle * spin_omega() * spin_omega() * std::sin(spin_omega() * t + spin_phase);
    if (spin == Type::Table) return table_angle(t, 2);
    return 0.0;
  }

  // Where the body's point x at time t1 is at time t2.
  Vector<D> moved(const Vector<D>& x, double t1, double t2) const {
    if (spin == Type::Fixed) return x + (displacement(t2) - displacement(t1));
    const Vector<D> c1 = centre + displacement(t1), c2 = centre + displacement(t2);
    return c2 + rotate(x - c1, angle_at(t2) - angle_at(t1));
  }
  // The velocity and acceleration of the body's point at x at time t: the translation's, and the
  // rotation's w x r and dw/dt x r + w x (w x r), r from the axis.
  Vector<D> point_velocity(const Vector<D>& x, double t) const {
    return velocity_at(t) + angular_velocity(t) * axis_cross(x - centre - displacement(t));
  }
  Vector<D> point_acceleration(const Vector<D>& x, double t) const {
    const Vector<D> r = x - centre - displacement(t);
    const double w = angular_velocity(t);
    return acceleration(t) + angular_acceleration(t) * axis_cross(r) + w * w * axis_cross(axis_cross(r));
  }
  // Largest speed over all time of a point within `radius` of the axis, for the step limits.
  double top_speed(double radius) const {
    double s = 0.0;
    if (type == Type::Constant) s = velocity.norm();
    if (type == Type::Sinusoidal) s = omega() * amplitude.norm();
    if (spin == Type::Constant) s += std::abs(rate) * radius;
    if (spin == Type::Sinusoidal) s += std::abs(angle) * spin_omega() * radius;
    // A table's: at its knots and halfway between them.
    auto sampled = [](const CubicSpline& c, auto&& speed) {
      double top = 0.0;
      const std::vector<double>& t = c.times();
      for (std::size_t k = 0; k < t.size(); ++k) {
        top = std::max(top, speed(t[k]));
        if (k + 1 < t.size()) top = std::max(top, speed(0.5 * (t[k] + t[k + 1])));
      }
      return top;
    };
    if (type == Type::Table) s = sampled(table_position[0], [&](double t) { return velocity_at(t).norm(); });
    if (spin == Type::Table)
      s += radius * sampled(table_angle, [&](double t) { return std::abs(angular_velocity(t)); });
    return s;
  }

 private:
  Vector<D> from_table(double t, int order) const {
    Vector<D> v;
    for (int a = 0; a < D; ++a) v[a] = table_position[static_cast<std::size_t>(a)](t, order);
    return v;
  }
  Vector<D> axis_cross(const Vector<D>& r) const {
    Eigen::Vector3d r3 = Eigen::Vector3d::Zero();
    r3.head<D>() = r;
    return axis.cross(r3).template head<D>();
  }
  Vector<D> rotate(const Vector<D>& r, double theta) const {
    if (theta == 0.0) return r;
    Eigen::Vector3d r3 = Eigen::Vector3d::Zero();
    r3.head<D>() = r;
    return (Eigen::AngleAxisd(theta, axis) * r3).template head<D>();
  }
};

template <int D> class MovingBodies {
 public:
  MovingBodies() = default;
  // label: by particle id, the body's index into motions (-1: none); t: the time the particles are at;
  // free_slip: by particle id, 1 for a free-slip wall particle (empty: every wall is no-slip);
  // wall_pressure: by particle id, the WallPressure a wall particle's group chose (-1 or empty: the option's).
  MovingBodies(std::vector<PrescribedMotion<D>> motions, std::vector<int> label, double t,
               std::vector<char> free_slip = {}, std::vector<FreeBody<D>> free = {},
               std::vector<signed char> wall_pressure = {})
      : motions_(std::move(motions)),
        label_(std::move(label)),
        free_slip_(std::move(free_slip)),
        wall_pressure_(std::move(wall_pressure)),
        free_(std::move(free)),
        t_(t) {
    for (const auto& m : motions_) any_ |= m.moves();
    for (const auto& f : free_) any_free_ |= f.active;
    any_ |= any_free_;
    for (const signed char c : wall_pressure_)
      if (c >= 0 && c < static_cast<signed char>(chosen_.size())) chosen_[static_cast<std::size_t>(c)] = true;
  }

  bool any() const { return any_; }
  bool any_free() const { return any_free_; }
  // Body b's free state (nullptr when its motion is prescribed).
  const FreeBody<D>* free_body(std::size_t b) const {
    return b < free_.size() && free_[b].active ? &free_[b] : nullptr;
  }
  FreeBody<D>* free_body(std::size_t b) { return b < free_.size() && free_[b].active ? &free_[b] : nullptr; }
  std::size_t count() const { return std::max(motions_.size(), free_.size()); }

  // The body index of particle i (owned or ghost), -1 for none.
  int body_of(const Particles<D>& P, std::size_t i) const {
    if (P.kind[i] != kWall) return -1;
    const GlobalIndex id = P.id[i];
    if (id < 0 || static_cast<std::size_t>(id) >= label_.size()) return -1;
    return label_[static_cast<std::size_t>(id)];
  }
  // The prescribed motion of particle i (owned or ghost), or nullptr when it is in no moving body or
  // in a free one.
  const PrescribedMotion<D>* motion_of(const Particles<D>& P, std::size_t i) const {
    if (!any_) return nullptr;
    const int b = body_of(P, i);
    if (b < 0 || free_body(static_cast<std::size_t>(b))) return nullptr;
    const PrescribedMotion<D>& m = motions_[static_cast<std::size_t>(b)];
    return m.moves() ? &m : nullptr;
  }
  const FreeBody<D>* free_of(const Particles<D>& P, std::size_t i) const {
    if (!any_free_) return nullptr;
    const int b = body_of(P, i);
    return b < 0 ? nullptr : free_body(static_cast<std::size_t>(b));
  }
  // Whether particle i moves with a body (prescribed or free).
  bool moves(const Particles<D>& P, std::size_t i) const { return motion_of(P, i) || free_of(P, i); }
  // The velocity and acceleration of the body point at x, for particle i of a moving body.
  Vector<D> point_velocity(const Particles<D>& P, std::size_t i, const Vector<D>& x) const {
    if (const FreeBody<D>* f = free_of(P, i)) return f->point_velocity(x);
    if (const PrescribedMotion<D>* m = motion_of(P, i)) return m->point_velocity(x, t_);
    return Vector<D>::Zero();
  }
  Vector<D> point_acceleration(const Particles<D>& P, std::size_t i, const Vector<D>& x) const {
    if (const FreeBody<D>* f = free_of(P, i)) return f->point_acceleration(x);
    if (const PrescribedMotion<D>* m = motion_of(P, i)) return m->point_acceleration(x, t_);
    return Vector<D>::Zero();
  }

  // Whether wall particle i (owned or ghost) is free-slip: the viscous term then sees the fluid's own
  // velocity there instead of the no-slip mirror (AdamiWall::mirror_velocity), so the wall exerts no
  // shear and grows no Stokes layer (docs/verification/free_surface.md, "Standing wave").
  bool free_slip(const Particles<D>& P, std::size_t i) const {
    const GlobalIndex id = P.id[i];
    return P.kind[i] == kWall && id >= 0 && static_cast<std::size_t>(id) < free_slip_.size() &&
           free_slip_[static_cast<std::size_t>(id)] != 0;
  }

  // The form of pressure continuation wall particle i's group chose (a WallPressure), -1 for none.
  int wall_pressure(const Particles<D>& P, std::size_t i) const {
    const GlobalIndex id = P.id[i];
    return P.kind[i] == kWall && id >= 0 && static_cast<std::size_t>(id) < wall_pressure_.size()
               ? wall_pressure_[static_cast<std::size_t>(id)]
               : -1;
  }
  // Whether some wall group chose form f (the same answer on every rank: the choices are by id).
  bool wall_pressure_chosen(int f) const { return f >= 0 && f < static_cast<int>(chosen_.size()) && chosen_[f]; }

  // Moves the owned particles of moving bodies from the time they are at to time t, and gives them
  // the body's velocity there; free bodies drift with their current velocities. Every rank calls it
  // with the same times.
  void move_to(Particles<D>& P, double t) {
    if (!any_) {
      t_ = t;  // the run's time, which the open boundaries' inflow follows too
      return;
    }
    std::vector<typename FreeBody<D>::Map> drift;
    for (FreeBody<D>& f : free_) drift.push_back(f.drift(t - t_));  // none when t == t_
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (const FreeBody<D>* f = free_of(P, i)) {
        P.x[i] = drift[static_cast<std::size_t>(body_of(P, i))](P.x[i]);
        P.v[i] = f->point_velocity(P.x[i]);
      } else if (const PrescribedMotion<D>* m = motion_of(P, i)) {
        P.x[i] = m->moved(P.x[i], t_, t);
        P.v[i] = m->point_velocity(P.x[i], t);
      }
    }
    t_ = t;
    move_plates();
  }
  // Thin plates that belong to bodies move with them: each placed from where the scene laid it, so a
  // restart at t puts it where the uninterrupted run has it. Plates cannot be free (the scene refuses).
  void carry_plates(std::shared_ptr<Screens<D>> screens) {
    screens_ = std::move(screens);
    move_plates();
  }
  // Free bodies: the accelerations from each body's fluid force and moment (about its centre of
  // mass) and gravity; the half kick of their velocities; their particles' velocities after it.
  // contact: the part of force that is contact with walls and other bodies (for the outputs).
  void set_loads(const std::vector<Vector<D>>& force, const std::vector<Eigen::Vector3d>& moment, const Vector<D>& g,
                 const std::vector<Vector<D>>& contact) {
    for (std::size_t b = 0; b < free_.size(); ++b)
      if (free_[b].active) free_[b].set_load(force[b], moment[b], g), free_[b].contact = contact[b];
  }
  void kick(Particles<D>& P, double half_dt) {
    if (!any_free_) return;
    for (FreeBody<D>& f : free_)
      if (f.active) f.kick(half_dt);
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (const FreeBody<D>* f = free_of(P, i)) P.v[i] = f->point_velocity(P.x[i]);
  }
  // The longest step in which no free body's point moves more than `fraction` of h.
  double free_step(double h, double fraction) const {
    double step = std::numeric_limits<double>::infinity();
    for (const FreeBody<D>& f : free_)
      if (f.active && f.top_speed() > 0.0) step = std::min(step, fraction * h / f.top_speed());
    return step;
  }
  nlohmann::json state() const {
    nlohmann::json j = nlohmann::json::array();
    for (const FreeBody<D>& f : free_) j.push_back(f.active ? f.state() : nlohmann::json());
    return j;
  }
  void restore(const nlohmann::json& j) {
    for (std::size_t b = 0; b < free_.size() && b < j.size(); ++b)
      if (free_[b].active) free_[b].restore(j[b]);
  }
  double time() const { return t_; }

  // Per owned particle: the body's acceleration at time t (zero off moving bodies). Empty when no
  // body moves.
  std::vector<Vector<D>> accelerations(const Particles<D>& P, double t) const {
    if (!any_) return {};
    std::vector<Vector<D>> a(P.n_owned, Vector<D>::Zero());
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (const FreeBody<D>* f = free_of(P, i)) a[i] = f->point_acceleration(P.x[i]);
      else if (const PrescribedMotion<D>* m = motion_of(P, i)) a[i] = m->point_acceleration(P.x[i], t);
    return a;
  }

  // Per particle, owned and ghost: the wall velocity the continuity equation and the pressure
  // source see, the body's current velocity on moving bodies (P.v, kept current in ghosts by the
  // neighbourhood's update) and `fixed` on the other walls. Fluid entries are zero.
  std::vector<Vector<D>> wall_velocities(const Particles<D>& P, const Vector<D>& fixed) const {
    // Ghost slots read here, outside a pair loop: a velocity marked written must be refreshed first.
    if (P.stale.v) throw std::logic_error("MovingBodies::wall_velocities: P.v's ghosts are stale (marked written)");
    std::vector<Vector<D>> u(P.size(), Vector<D>::Zero());
    for (std::size_t i = 0; i < P.size(); ++i)
      if (P.kind[i] == kWall) u[i] = moves(P, i) ? Vector<D>(P.v[i]) : fixed;
    return u;
  }

 private:
  void move_plates() {
    if (!screens_) return;
    for (std::size_t k = 0; k < screens_->start().size(); ++k) {
      const typename Screens<D>::Plate& p = screens_->start()[k];
      if (p.body < 0 || static_cast<std::size_t>(p.body) >= motions_.size()) continue;
      const PrescribedMotion<D>& m = motions_[static_cast<std::size_t>(p.body)];
      if (m.moves()) screens_->move(k, m.moved(p.a, 0.0, t_), m.moved(p.b, 0.0, t_));
    }
  }

  std::shared_ptr<Screens<D>> screens_;  // the scene's plates, some of them bodies'
  std::vector<PrescribedMotion<D>> motions_;
  std::vector<int> label_;
  std::vector<char> free_slip_;
  std::vector<signed char> wall_pressure_;
  std::array<bool, 2> chosen_{};   // per WallPressure form: some particle's group chose it
  std::vector<FreeBody<D>> free_;  // per body; inactive where the motion is prescribed
  double t_ = 0.0;
  bool any_ = false, any_free_ = false;
};

}  // namespace sph
