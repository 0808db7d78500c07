#pragma once
// A rigid body the fluid moves (two-way coupled): Newton-Euler for its centre of mass and its rotation,
// driven by the fluid's force and moment on its wall particles (src/run/wall_groups.hpp) and gravity.
// Constraints: translation along chosen axes held fixed, rotation held fixed (all of it, or about
// chosen axes in 3D), or a hinge: rotation only, about a fixed point (2D) or a fixed axis through it
// (3D), as a flap hinged at the floor. Rotations are quaternions (2D: about z). The time integration
// is the fluid's kick-drift-kick: kick(dt/2) with the load at the step's start, the drift moves the
// body's particles with the half-step velocities (MovingBodies::move_to), kick(dt/2) with the load at
// the step's end (docs/verification/free_bodies.md).
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "src/core/types.hpp"

namespace sph {

template <int D> struct FreeBody {
  bool active = false;
  // Mass properties, from the body's particles as laid out (SceneCase) or given.
  double mass = 0.0, volume = 0.0;                    // per unit length in 2D
  long particles = 0;                                 // its wall particles
  double reach = 0.0;                                 // its farthest particle's distance from the centre
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre of mass, body frame (2D: zz)
  Vector<D> centre0 = Vector<D>::Zero();              // centre of mass as laid out
  // Constraints.
  std::array<bool, D> fixed_translation{};  // per axis
  std::array<bool, 3> fixed_rotation{};     // per axis (2D: only z counts)
  bool hinged = false;
  Vector<D> hinge = Vector<D>::Zero();                    // the fixed point
  Eigen::Vector3d hinge_axis = Eigen::Vector3d::UnitZ();  // unit (2D: z)
  // State (the same on every rank).
  Vector<D> centre = Vector<D>::Zero(), velocity = Vector<D>::Zero(), acceleration = Vector<D>::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();                   // from the layout
  Eigen::Vector3d omega = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();  // world frame
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // what the spin's kick takes (set_load), about the centre
  Vector<D> contact = Vector<D>::Zero();             // the contact force in the last load (body_contact.hpp)
  // The coupling's anticipated added mass over the body's mass, r: the accelerations solve
  // (1 + r) M a_new = F + M g + r M a_old (and so for the rotation), which leaves a state at rest
  // as it is and damps the step-to-step oscillation of an explicit coupling with a fluid whose
  // pressure answers the body's acceleration at once (Causin, Gerbeau & Nobile 2005; the remedy of
  // Foerster, Wall & Ramm 2007). The lag it adds is first order in dt.
  double added_mass_ratio = 0.0;

  // The inertia tensor about the centre of mass in the world frame.
  Eigen::Matrix3d world_inertia() const {
    const Eigen::Matrix3d R = orientation.toRotationMatrix();
    return R * inertia * R.transpose();
  }

  // Sets the accelerations from the fluid's force F and moment T (about the centre of mass) and
  // gravity g, within the constraints.
  void set_load(const Vector<D>& F, const Eigen::Vector3d& T, const Vector<D>& g) {
    const Vector<D> weight = mass * g;
    if (hinged) {
      // Rotation about the hinge alone: I_p alpha = T_p along the axis.
      const Vector<D> d = centre - hinge;
      const Eigen::Vector3d d3 = lift(d), n = hinge_axis;
      const Eigen::Vector3d Tp = T + d3.cross(lift(Vector<D>(F + weight)));
      const Eigen::Matrix3d Ip =
          world_inertia() + mass * (d3.squaredNorm() * Eigen::Matrix3d::Identity() - d3 * d3.transpose());
      const double r = added_mass_ratio;
      alpha = ((Tp.dot(n) + r * n.dot(Ip * n) * alpha.dot(n)) / ((1.0 + r) * n.dot(Ip * n))) * n;
      acceleration = (alpha.cross(d3) + omega.cross(omega.cross(d3))).template head<D>();
      return;
    }
    const double r = added_mass_ratio;
    acceleration = (F + weight + r * mass * acceleration) / ((1.0 + r) * mass);
    for (int a = 0; a < D; ++a)
      if (fixed_translation[a]) acceleration[a] = 0.0;
    torque = (T + r * world_inertia() * alpha) / (1.0 + r);
    for (int a = 0; a < 3; ++a)
      if (fixed_rotation[a] || (D == 2 && a < 2)) torque[a] = 0.0;
    const Eigen::Matrix3d I = world_inertia();
    alpha = D == 2 ? Eigen::Vector3d(0.0, 0.0, torque[2] / I(2, 2))
                   : Eigen::Vector3d(I.ldlt().solve(torque - omega.cross(I * omega)));
    for (int a = 0; a < 3; ++a)
      if (fixed_rotation[a] || (D == 2 && a < 2)) alpha[a] = 0.0;
  }

  // Velocities over half_dt with the current load. The spin's kick is that of the angular momentum,
  // L = I omega, by the torque: without torque L stays exactly, as it does in the drift.
  void kick(double half_dt) {
    if (hinged) {
      omega += half_dt * alpha;
      velocity = omega.cross(lift(Vector<D>(centre - hinge))).template head<D>();
      return;
    }
    velocity += half_dt * acceleration;
    omega += half_dt * (D == 2 ? Eigen::Vector3d(alpha) : Eigen::Vector3d(world_inertia().ldlt().solve(torque)));
    for (int a = 0; a < 3; ++a)
      if (fixed_rotation[a]) omega[a] = 0.0;
  }

  // Moves the body over dt with its velocities; returns the rigid map x -> pivot' + R (x - pivot).
  struct Map {
    Vector<D> from, to;
    Eigen::Quaterniond turn;
    Vector<D> operator()(const Vector<D>& x) const {
      return to + (turn * lift(Vector<D>(x - from))).template head<D>();
    }
  };
  Map drift(double dt) {
    Map m;
    if (dt == 0.0) {  // no move, and no round-off: a restart moves its bodies to the time they are at
      m.from = m.to = centre, m.turn = Eigen::Quaterniond::Identity();
      return m;
    }
    const Eigen::Vector3d L = world_inertia() * omega;
    // In 3D the spin changes as the body turns (L stays): turned with the spin at the half turn, the
    // drift is second order.
    Eigen::Vector3d w = omega;
    if (D == 3 && !hinged) {
      const Eigen::Quaterniond half = (rotation(omega, 0.5 * dt) * orientation).normalized();
      const Eigen::Matrix3d R = half.toRotationMatrix();
      w = (R * inertia * R.transpose()).ldlt().solve(L);
    }
    m.turn = rotation(w, dt);
    if (hinged) {
      m.from = m.to = hinge;
    } else {
      m.from = centre, m.to = centre + dt * velocity;
    }
    centre = m(centre);
    orientation = (m.turn * orientation).normalized();
    if (hinged) velocity = omega.cross(lift(Vector<D>(centre - hinge))).template head<D>();
    if (D == 3 && !hinged) {  // the angular momentum stays; the spin follows the turned inertia
      omega = world_inertia().ldlt().solve(L);
      for (int a = 0; a < 3; ++a)
        if (fixed_rotation[a]) omega[a] = 0.0;
    }
    return m;
  }
  static Eigen::Quaterniond rotation(const Eigen::Vector3d& w, double dt) {
    const double angle = w.norm() * dt;
    return angle != 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized())) : Eigen::Quaterniond::Identity();
  }

  // Where the point laid out at x0 is now.
  Vector<D> placed(const Vector<D>& x0) const {
    return centre + (orientation * lift(Vector<D>(x0 - centre0))).template head<D>();
  }
  Vector<D> point_velocity(const Vector<D>& x) const {
    return velocity + omega.cross(lift(Vector<D>(x - centre))).template head<D>();
  }
  Vector<D> point_acceleration(const Vector<D>& x) const {
    const Eigen::Vector3d r = lift(Vector<D>(x - centre));
    return acceleration + (alpha.cross(r) + omega.cross(omega.cross(r))).template head<D>();
  }
  // The rotation angle about z (2D), radians.
  double angle() const { return 2.0 * std::atan2(orientation.z(), orientation.w()); }
  // The fastest a point of the body moves now.
  double top_speed() const { return velocity.norm() + omega.norm() * reach; }
  double kinetic_energy() const {
    return 0.5 * mass * velocity.squaredNorm() + 0.5 * omega.dot(world_inertia() * omega);
  }

  nlohmann::json state() const {
    auto list = [](const auto& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
    return {{"centre", list(centre)},
            {"velocity", list(velocity)},
            {"acceleration", list(acceleration)},
            {"orientation", {orientation.w(), orientation.x(), orientation.y(), orientation.z()}},
            {"omega", list(omega)},
            {"alpha", list(alpha)},
            {"torque", list(torque)}};
  }
  void restore(const nlohmann::json& j) {
    auto get = [&](const char* key, auto& v) {
      const std::vector<double> x = j.at(key).get<std::vector<double>>();
      for (int a = 0; a < static_cast<int>(v.size()); ++a) v[a] = x.at(static_cast<std::size_t>(a));
    };
    get("centre", centre), get("velocity", velocity), get("acceleration", acceleration);
    get("omega", omega), get("alpha", alpha), get("torque", torque);
    const std::vector<double> q = j.at("orientation").get<std::vector<double>>();
    orientation = Eigen::Quaterniond(q.at(0), q.at(1), q.at(2), q.at(3));
  }

  static Eigen::Vector3d lift(const Vector<D>& v) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    r.head<D>() = v;
    return r;
  }
};

}  // namespace sph
