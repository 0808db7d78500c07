#pragma once
// What the time loop keeps over a run beyond the particles: linear-solver iteration counts and the
// steady-state test. Both travel with checkpoints, so a restarted run's figures cover all its steps and
// it stops where the whole run would.
#include <algorithm>
#include <cmath>
#include <deque>
#include <nlohmann/json.hpp>
#include <utility>

#include "src/run/solver.hpp"

namespace sph {

// Linear-solver iteration statistics over a run.
struct StepStats {
  long solves = 0, total_iterations = 0;
  int max_iterations = 0;
  void add(const StepReport& r) {
    if (r.linear_iterations < 0) return;
    ++solves, total_iterations += r.linear_iterations;
    max_iterations = std::max(max_iterations, r.linear_iterations);
  }
  double mean_iterations() const { return solves ? double(total_iterations) / solves : 0.0; }
  nlohmann::json to_json() const { return {solves, total_iterations, max_iterations}; }
  void from_json(const nlohmann::json& j) {
    if (j.is_array() && j.size() == 3) solves = j[0], total_iterations = j[1], max_iterations = j[2];
  }
};

// Steady state: the relative kinetic-energy change rate over the last time unit below a tolerance.
class SteadyState {
 public:
  explicit SteadyState(double tol) : tol_(tol) {}
  void add(double t, double ke) {
    if (tol_ <= 0) return;
    history_.emplace_back(t, ke);
    while (history_.size() > 2 && history_[1].first <= t - window_) history_.pop_front();
    const auto& [t0, ke0] = history_.front();
    if (t - t0 >= window_ * (1 - 1e-9) && ke > 0) reached_ = std::abs(ke - ke0) / (ke * (t - t0)) < tol_;
  }
  bool reached() const { return reached_; }
  nlohmann::json to_json() const { return history_; }
  void from_json(const nlohmann::json& j) {
    if (!j.is_array()) return;
    for (const auto& e : j) history_.emplace_back(e[0].get<double>(), e[1].get<double>());
  }

 private:
  double tol_, window_ = 1.0;
  bool reached_ = false;
  std::deque<std::pair<double, double>> history_;
};

}  // namespace sph
