#pragma once
// Bodies whose motion is prescribed as a function of time (a translation: constant velocity, or
// sinusoidal, A (sin(w t + phi) - sin phi), which starts at rest for phi = -90 degrees). Their wall particles are moved by the solvers at their drift, and the wall condition
// sees the body's velocity and acceleration: Adami et al. (2012)'s pressure extrapolation takes
// (g - a_w), the continuity equation (WCSPH) and the pressure source (ISPH) the wall's velocity.
// Membership is by permanent particle id, as for the force groups (src/run/wall_groups.hpp).
#include <cmath>
#include <vector>

#include "src/particles/particles.hpp"

namespace sph {

template <int D> struct PrescribedMotion {
  enum class Type { Fixed, Constant, Sinusoidal };
  Type type = Type::Fixed;
  Vector<D> velocity = Vector<D>::Zero();   // Constant
  Vector<D> amplitude = Vector<D>::Zero();  // Sinusoidal: A (sin(2 pi t / T + phase) - sin phase)
  double period = 1.0, phase = 0.0;         // phase in radians

  bool moves() const { return type != Type::Fixed; }
  double omega() const { return 2.0 * M_PI / period; }
  Vector<D> displacement(double t) const {
    if (type == Type::Constant) return t * velocity;
    if (type == Type::Sinusoidal) return (std::sin(omega() * t + phase) - std::sin(phase)) * amplitude;
    return Vector<D>::Zero();
  }
  Vector<D> velocity_at(double t) const {
    if (type == Type::Constant) return velocity;
    if (type == Type::Sinusoidal) return omega() * std::cos(omega() * t + phase) * amplitude;
    return Vector<D>::Zero();
  }
  Vector<D> acceleration(double t) const {
    if (type == Type::Sinusoidal) return -omega() * omega() * std::sin(omega() * t + phase) * amplitude;
    return Vector<D>::Zero();
  }
  // Largest speed over all time, for the step limits.
  double top_speed() const {
    if (type == Type::Constant) return velocity.norm();
    if (type == Type::Sinusoidal) return omega() * amplitude.norm();
    return 0.0;
  }
};

template <int D> class MovingBodies {
 public:
  MovingBodies() = default;
  // label: by particle id, the body's index into motions (-1: none); t: the time the particles are at.
  MovingBodies(std::vector<PrescribedMotion<D>> motions, std::vector<int> label, double t)
      : motions_(std::move(motions)), label_(std::move(label)), t_(t) {
    for (const auto& m : motions_) any_ |= m.moves();
  }

  bool any() const { return any_; }
  double top_speed() const {
    double s = 0.0;
    for (const auto& m : motions_) s = std::max(s, m.top_speed());
    return s;
  }

  // The motion of particle i (owned or ghost), or nullptr when it is in no moving body.
  const PrescribedMotion<D>* motion_of(const Particles<D>& P, std::size_t i) const {
    if (!any_ || P.kind[i] != kWall) return nullptr;
    const GlobalIndex id = P.id[i];
    if (id < 0 || static_cast<std::size_t>(id) >= label_.size() || label_[static_cast<std::size_t>(id)] < 0)
      return nullptr;
    const PrescribedMotion<D>& m = motions_[static_cast<std::size_t>(label_[static_cast<std::size_t>(id)])];
    return m.moves() ? &m : nullptr;
  }

  // Moves the owned particles of moving bodies from the time they are at to time t, and gives them
  // the body's velocity there. Every rank calls it with the same times.
  void move_to(Particles<D>& P, double t) {
    if (!any_) return;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (const PrescribedMotion<D>* m = motion_of(P, i)) {
        P.x[i] += m->displacement(t) - m->displacement(t_);
        P.v[i] = m->velocity_at(t);
      }
    t_ = t;
  }
  double time() const { return t_; }

  // Per owned particle: the body's acceleration at time t (zero off moving bodies). Empty when no
  // body moves.
  std::vector<Vector<D>> accelerations(const Particles<D>& P, double t) const {
    if (!any_) return {};
    std::vector<Vector<D>> a(P.n_owned, Vector<D>::Zero());
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (const PrescribedMotion<D>* m = motion_of(P, i)) a[i] = m->acceleration(t);
    return a;
  }

  // Per particle, owned and ghost: the wall velocity the continuity equation and the pressure
  // source see, the body's current velocity on moving bodies (P.v, kept current in ghosts by the
  // neighbourhood's update) and `fixed` on the other walls. Fluid entries are zero.
  std::vector<Vector<D>> wall_velocities(const Particles<D>& P, const Vector<D>& fixed) const {
    std::vector<Vector<D>> u(P.size(), Vector<D>::Zero());
    for (std::size_t i = 0; i < P.size(); ++i)
      if (P.kind[i] == kWall) u[i] = motion_of(P, i) ? Vector<D>(P.v[i]) : fixed;
    return u;
  }

 private:
  std::vector<PrescribedMotion<D>> motions_;
  std::vector<int> label_;
  double t_ = 0.0;
  bool any_ = false;
};

}  // namespace sph
