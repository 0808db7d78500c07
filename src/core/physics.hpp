#pragma once
// What a scene asks of the physics; solvers compose only the terms switched on here.
#include <nlohmann/json.hpp>

#include "src/core/types.hpp"

namespace sph {

template <int D> struct Physics {
  double rho0 = 1.0;                       // reference density
  double nu = 0.0;                         // kinematic viscosity; 0 switches the viscous term off
  double U = 1.0;                          // reference speed: time-step and shifting scales
  Vector<D> gravity = Vector<D>::Zero();         // body force per unit mass; zero switches it off

  bool viscous() const { return nu > 0.0; }
  bool has_body_force() const { return gravity.squaredNorm() > 0.0; }

  nlohmann::json describe() const {
    nlohmann::json j{{"rho0", rho0}, {"nu", nu}, {"U_ref", U}};
    if (has_body_force()) j["gravity"] = std::vector<double>(gravity.data(), gravity.data() + D);
    return j;
  }
};

}  // namespace sph
