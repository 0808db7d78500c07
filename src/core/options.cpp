#include "src/core/options.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace sph {

void require(bool condition, const std::string& option, const std::string& what, double value) {
  if (condition) return;
  std::ostringstream msg;
  msg << option << " must be " << what << " (got " << value << ")";
  throw Error(msg.str());
}

namespace {

// PETSc reads these only at the end of a solve or of the run, so they are unused at start-up.
bool read_late(const std::string& name) {
  static const char* prefixes[] = {"log",         "info",       "malloc",      "options_",  "help",
                                   "version",     "memory_view", "objects_dump", "on_error", "fp_trap",
                                   "no_signal_handler", "ksp_view", "mat_view", "vec_view", "pc_view",
                                   "ksp_converged_rate", "check_pointer_intensity", "use_gpu_aware_mpi",
                                   "mpi_linear_solver_server", "citations", "error_output", "saws"};
  for (const char* p : prefixes)
    if (name.rfind(p, 0) == 0) return true;
  return false;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

struct Unused {
  std::vector<std::string> names;
};

Unused unused_options() {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  SPH_PETSC(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  Unused u;
  for (PetscInt k = 0; k < n; ++k) u.names.emplace_back(names[k]);
  SPH_PETSC(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  return u;
}

}  // namespace

std::vector<std::string> used_option_names() {
  // PETSc keeps a "used" flag per option; options the user did not set are not in the database,
  // so suggestions come from a list of this program's documented options instead.
  return {"case",       "solver",     "dim",        "nx",         "re",         "t_end",
          "dt",         "max_steps",  "output_dir", "output_interval", "kernel", "h_over_dx",
          "neighbour_skin", "progress", "cfl",      "shifting",   "shift_coefficient",
          "pressure_gradient", "rho0",  "U"};
}

void check_unused_options() {
  const Unused u = unused_options();
  for (const std::string& name : u.names) {
    if (read_late(name)) continue;
    std::string best;
    std::size_t best_d = 3;  // suggest only close matches
    for (const std::string& known : used_option_names()) {
      const std::size_t d = edit_distance(name, known);
      if (d < best_d) best_d = d, best = known;
    }
    std::string msg = "unknown option -" + name + " (not used by the chosen case or solver)";
    if (!best.empty()) msg += "; did you mean -" + best + "?";
    msg += " Run with -help to list the options";
    throw Error(msg);
  }
}

void finish_options_check() {
  const Unused u = unused_options();
  for (const std::string& name : u.names)
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: option -%s was never used\n", name.c_str());
}

}  // namespace sph
