#include "src/core/options.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cstdarg>
#include <regex>

#include <unistd.h>
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

namespace {
std::string g_help_text;

PetscErrorCode capture_help(MPI_Comm, const char format[], ...) {
  char buf[4096];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  g_help_text += buf;
  return 0;
}
}  // namespace

std::vector<std::string> documented_options(const std::function<void()>& read_all) {
  g_help_text.clear();
  const auto saved = PetscHelpPrintf;
  PetscHelpPrintf = capture_help;
  // PETSc prints each options block once per run; a fresh record makes the blocks already read
  // by this run print again.
  PetscOptionsHelpPrinted printed = PetscOptionsHelpPrintedSingleton;
  // Lists of types (-ksp_type ...) go straight to standard output rather than through
  // PetscHelpPrintf: capture the file descriptor too.
  std::FILE* type_lists = std::tmpfile();
  std::fflush(stdout);
  const int stdout_saved = type_lists ? dup(STDOUT_FILENO) : -1;
  if (stdout_saved >= 0) dup2(fileno(type_lists), STDOUT_FILENO);
  SPH_PETSC(PetscOptionsHelpPrintedCreate(&PetscOptionsHelpPrintedSingleton));
  SPH_PETSC(PetscOptionsSetValue(nullptr, "-help", nullptr));
  try {
    read_all();
  } catch (const Error&) {
    // Reading the blocks is all that matters here; value checks may fail for other components.
  }
  SPH_PETSC(PetscOptionsClearValue(nullptr, "-help"));
  SPH_PETSC(PetscOptionsHelpPrintedDestroy(&PetscOptionsHelpPrintedSingleton));
  PetscOptionsHelpPrintedSingleton = printed;
  PetscHelpPrintf = saved;
  std::fflush(stdout);
  if (stdout_saved >= 0) {
    dup2(stdout_saved, STDOUT_FILENO);
    close(stdout_saved);
  }
  if (type_lists) {
    std::rewind(type_lists);
    char line[4096];
    while (std::fgets(line, sizeof line, type_lists)) g_help_text += line;
    std::fclose(type_lists);
  }
  std::vector<std::string> names;
  const std::regex option("\\n  -([A-Za-z0-9_]+)");
  for (auto it = std::sregex_iterator(g_help_text.begin(), g_help_text.end(), option); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1].str());
  return names;
}

void check_unused_options(const std::function<void()>& list_all_options) {
  const Unused u = unused_options();
  for (const std::string& name : u.names) {
    if (read_late(name)) continue;
    std::string best;
    std::size_t best_d = 3;  // suggest only close matches
    for (const std::string& known : documented_options(list_all_options)) {
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
