#pragma once
// The solvers the sph program knows, chosen by name with -solver.
#include <memory>
#include <string>
#include <vector>

#include "src/run/solver.hpp"

namespace sph {

const std::vector<std::string>& solver_names();
template <int D> std::unique_ptr<Solver<D>> create_solver(const std::string& name);  // throws on unknown

}  // namespace sph
