#include "solvers/registry.hpp"

#include "solvers/compressible/compressible_solver.hpp"
#include "solvers/isph/isph_solver.hpp"
#include "solvers/wcsph/wcsph_solver.hpp"
#include "src/core/error.hpp"

namespace sph {

namespace {
// The one table of solvers: name -> factory, in the order -help lists them.
template <int D> struct SolverEntry {
  const char* name;
  std::unique_ptr<Solver<D>> (*make)();
};
template <int D, class S> std::unique_ptr<Solver<D>> make_solver() { return std::make_unique<S>(); }
template <int D> const std::vector<SolverEntry<D>>& solver_table() {
  static const std::vector<SolverEntry<D>> table = {{"isph", make_solver<D, IsphSolver<D>>},
                                                    {"wcsph", make_solver<D, WcsphSolver<D>>},
                                                    {"compressible", make_solver<D, CompressibleSolver<D>>}};
  return table;
}
}  // namespace

const std::vector<std::string>& solver_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& e : solver_table<2>()) n.emplace_back(e.name);
    return n;
  }();
  return names;
}

template <int D> std::unique_ptr<Solver<D>> create_solver(const std::string& name) {
  for (const auto& e : solver_table<D>())
    if (name == e.name) return e.make();
  std::string list;
  for (const auto& n : solver_names()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown solver '" + name + "'; choose -solver from: " + list);
}

template std::unique_ptr<Solver<1>> create_solver<1>(const std::string&);
template std::unique_ptr<Solver<2>> create_solver<2>(const std::string&);
template std::unique_ptr<Solver<3>> create_solver<3>(const std::string&);

}  // namespace sph
