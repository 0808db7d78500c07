#pragma once
// What a scene asks of the physics; solvers compose only the terms switched on here.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "src/core/types.hpp"

namespace sph {

template <int D> struct Physics {
  double rho0 = 1.0;                      // reference density
  double nu = 0.0;                        // kinematic viscosity; 0 switches the viscous term off
  double U = 1.0;                         // reference speed: time-step and shifting scales
  Vector<D> gravity = Vector<D>::Zero();  // body force per unit mass; zero switches it off
  // Position-dependent body force per unit mass (e.g. the toy star's -Omega^2 x), its potential (for
  // energy accounting) and a label for summary.json; an empty function switches it off.
  std::function<Vector<D>(const Vector<D>&)> external_acceleration;
  std::function<double(const Vector<D>&)> external_potential;
  std::string external_label;
  // Ideal gas (solvers/compressible): adiabatic index, P = (gamma - 1) rho u; 0: not a gas scene.
  // isentropic: no energy equation, P / rho^gamma stays constant per particle apart from dissipation
  // (a polytrope P = K rho^gamma when the case starts with it).
  double gamma = 0.0;
  bool isentropic = false;

  // The scene has a free surface: ISPH detects surface particles and imposes p = 0 there.
  bool free_surface = false;

  // The velocity to add to the case's incompressible start so that a weakly compressible fluid with
  // sound speed c0 starts on its slow manifold: grad phi with lap phi = -(Dp/Dt) / (rho0 c0^2), Dp/Dt
  // the incompressible pressure's material rate at t = 0. Without it the start excites sound waves
  // whose pressure is O(Mach) times the flow's (the particles carry their pressure, which the
  // incompressible field changes along their paths). Given by cases that know their exact solution;
  // empty: not available. Used by WCSPH's -prepared_start.
  std::function<Vector<D>(const Vector<D>&, double)> slow_manifold_velocity;

  bool viscous() const { return nu > 0.0; }
  bool has_body_force() const { return gravity.squaredNorm() > 0.0; }
  bool has_external_force() const { return static_cast<bool>(external_acceleration); }
  bool is_gas() const { return gamma > 0.0; }

  nlohmann::json describe() const {
    nlohmann::json j{{"rho0", rho0}, {"nu", nu}, {"U_ref", U}};
    if (has_body_force()) j["gravity"] = std::vector<double>(gravity.data(), gravity.data() + D);
    if (has_external_force())
      j["external_acceleration"] = external_label.empty() ? "position-dependent" : external_label;
    if (is_gas()) j["gas"] = {{"gamma", gamma}, {"isentropic", isentropic}};
    if (free_surface) j["free_surface"] = true;
    return j;
  }
};

}  // namespace sph
