#pragma once
// What timeseries.csv and summary.json say of the free bodies (src/boundary/free_body.hpp): each one's
// centre of mass, its velocity, and its rotation, as <name>_x, <name>_u, ... Angles and rates in
// degrees (as the scene file gives them); in 3D the orientation as a unit quaternion.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/boundary/moving_bodies.hpp"

namespace sph {

template <int D>
std::vector<std::string> free_body_columns(const std::vector<std::string>& names, const MovingBodies<D>& bodies) {
  std::vector<std::string> c;
  for (std::size_t b = 0; b < names.size(); ++b) {
    if (!bodies.free_body(b)) continue;
    const std::string& n = names[b];
    for (int a = 0; a < D; ++a) c.push_back(n + "_" + "xyz"[a]);
    for (int a = 0; a < D; ++a) c.push_back(n + "_" + "uvw"[a]);
    if (D == 2) {
      c.insert(c.end(), {n + "_angle", n + "_rate"});
    } else {
      for (const char* q : {"qw", "qx", "qy", "qz", "rate_x", "rate_y", "rate_z"}) c.push_back(n + "_" + q);
    }
    c.push_back(n + "_kinetic_energy");
    for (int a = 0; a < D; ++a) c.push_back(n + "_contact_" + "xyz"[a]);
  }
  return c;
}

template <int D> std::vector<double> free_body_row(const MovingBodies<D>& bodies) {
  constexpr double kDegree = 180.0 / M_PI;
  std::vector<double> r;
  for (std::size_t b = 0; b < bodies.count(); ++b) {
    const FreeBody<D>* f = bodies.free_body(b);
    if (!f) continue;
    r.insert(r.end(), f->centre.data(), f->centre.data() + D);
    r.insert(r.end(), f->velocity.data(), f->velocity.data() + D);
    if (D == 2) {
      r.insert(r.end(), {f->angle() * kDegree, f->omega[2] * kDegree});
    } else {
      const Eigen::Quaterniond& q = f->orientation;
      r.insert(r.end(), {q.w(), q.x(), q.y(), q.z()});
      for (int a = 0; a < 3; ++a) r.push_back(f->omega[a] * kDegree);
    }
    r.push_back(f->kinetic_energy());
    r.insert(r.end(), f->contact.data(), f->contact.data() + D);
  }
  return r;
}

template <int D> nlohmann::json free_body_states(const std::vector<std::string>& names, const MovingBodies<D>& bodies) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t b = 0; b < names.size(); ++b)
    if (const FreeBody<D>* f = bodies.free_body(b)) {
      j[names[b]] = f->state();
      j[names[b]]["mass"] = f->mass;
    }
  return j;
}

}  // namespace sph
