#pragma once
// The parts of summary.json that describe how a run ended beyond its status and times: the solver's
// models, KSP figures, parameters and conservation figures, momentum drift, and the case's error norms
// at the final state. The time loop (time_loop.cpp) adds the rest.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "src/run/case.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/run_statistics.hpp"
#include "src/run/solver.hpp"

namespace sph {

template <int D> void add_final_state(nlohmann::json& summary, const Solver<D>& solver, const Case<D>& run_case,
                                      const Particles<D>& P, double t, const StepStats& stats,
                                      const Totals<D>& initial) {
  nlohmann::json solver_info = solver.describe();
  summary["models"] = solver_info["models"];
  if (solver_info.contains("ksp")) {
    summary["ksp"] = solver_info["ksp"];
    summary["ksp"]["iterations_mean"] = stats.mean_iterations();
    summary["ksp"]["iterations_max"] = stats.max_iterations;
  }
  // Total momentum change relative to the initial sum of |m v|: round-off for pairwise-symmetric
  // schemes without shifting (shifting's Taylor correction and corrected gradients do not conserve it).
  // Relative to the larger of the initial and final sums of |m v|: a scene that starts at rest (the
  // cavity) has no initial scale to measure against.
  const Totals<D> now = totals(P);
  summary["conservation"] = {{"momentum_drift", (now.momentum - initial.momentum).norm() /
                                                    std::max({initial.momentum_scale, now.momentum_scale, 1e-300})},
                             {"fluid_mass", fluid_mass(P)}};
  for (auto it = solver_info.begin(); it != solver_info.end(); ++it) {
    if (it.key() == "models" || it.key() == "ksp") continue;
    if (it.key() == "conservation") summary["conservation"].update(it.value());
    else summary["solver_parameters"][it.key()] = it.value();
  }
  if (const EnergyBudget* budget = solver.energy_budget())
    summary["conservation"]["energy_budget"] = budget->describe(P);
  summary["errors"] = nlohmann::json::object();
  for (const auto& [name, value] : run_case.errors(P, t)) {
    summary["errors"][name] = value;  // NaN becomes null: a metric that could not be measured
    if (std::isfinite(value)) continue;
    const std::string why = run_case.unmeasured_reason(name);
    summary["errors_unmeasured"][name] = why.empty() ? "not a finite number at the end of the run" : why;
  }
}

}  // namespace sph
