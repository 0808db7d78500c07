#include "solvers/registry.hpp"

#include "solvers/compressible/compressible_solver.hpp"
#include "solvers/isph/isph_solver.hpp"
#include "solvers/wcsph/wcsph_solver.hpp"
#include "src/core/error.hpp"

namespace sph {

const std::vector<std::string>& solver_names() {
  static const std::vector<std::string> names = {"isph", "wcsph", "compressible"};
  return names;
}

template <int D> std::unique_ptr<Solver<D>> create_solver(const std::string& name) {
  if (name == "isph") return std::make_unique<IsphSolver<D>>();
  if (name == "wcsph") return std::make_unique<WcsphSolver<D>>();
  if (name == "compressible") return std::make_unique<CompressibleSolver<D>>();
  std::string list;
  for (const auto& n : solver_names()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown solver '" + name + "'; choose -solver from: " + list);
}

template std::unique_ptr<Solver<1>> create_solver<1>(const std::string&);
template std::unique_ptr<Solver<2>> create_solver<2>(const std::string&);
template std::unique_ptr<Solver<3>> create_solver<3>(const std::string&);

}  // namespace sph
