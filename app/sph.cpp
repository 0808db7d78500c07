// sph: the command-line program. Picks a case and a solver by name (-case, -solver), reads every
// other parameter from PETSc's options database (-help lists them), and runs.
//
//   ./build/sph -case taylor_green -solver isph -nx 64 -re 100 -t_end 1
//   ./build/sph -options_file cases/taylor_green.opts -ksp_type gmres -ksp_monitor
#include <petscsys.h>

#include <cstdio>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "cases/registry.hpp"
#include "solvers/registry.hpp"
#include "src/core/error.hpp"
#include "src/run/interrupt.hpp"

namespace {

PetscErrorCode read_names(sph::RunOptions* o, PetscInt* dim, PetscBool* dim_set) {
  PetscFunctionBeginUser;
  std::vector<const char*> cases, solvers;
  for (const auto& e : sph::case_registry()) cases.push_back(e.name.c_str());
  for (const auto& s : sph::solver_names()) solvers.push_back(s.c_str());
  PetscInt c = 0, s = 0;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Scene and scheme", "sph");
  PetscCall(PetscOptionsEList("-case", "Scene to run", "", cases.data(), static_cast<PetscInt>(cases.size()), cases[0], &c,
                              nullptr));
  PetscCall(PetscOptionsEList("-solver", "Time-stepping scheme", "", solvers.data(),
                              static_cast<PetscInt>(solvers.size()), solvers[0], &s, nullptr));
  PetscCall(PetscOptionsInt("-dim", "Spatial dimension (default: the case's own)", "", *dim, dim, dim_set));
  PetscOptionsEnd();
  o->case_name = cases[c];
  o->solver_name = solvers[s];
  PetscFunctionReturn(0);
}

// The first line of an options file that PETSc would refuse with a traceback: one whose first token is
// neither an option (-name) nor an alias line; 0 when every line is fine.
int first_bad_line(std::FILE* f, std::string* token) {
  char buf[4096];
  for (int line = 1; std::fgets(buf, sizeof buf, f); ++line) {
    std::string text(buf);
    text = text.substr(0, text.find('#'));  // '#' starts a comment
    const std::size_t begin = text.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) continue;
    *token = text.substr(begin, text.find_first_of(" \t\r\n", begin) - begin);
    if ((*token)[0] != '-' && *token != "alias") return line;
  }
  return 0;
}

// PETSc reads -options_file during initialisation, before a quiet error handler can be installed:
// check the files first so a wrong path or a malformed line gets one line instead of a PETSc traceback.
bool options_files_valid(int argc, char** argv) {
  for (int k = 1; k + 1 < argc; ++k) {
    const std::string opt = argv[k];
    if (opt != "-options_file" && opt != "-options_file_yaml") continue;
    std::FILE* f = std::fopen(argv[k + 1], "r");
    if (!f) {
      std::fprintf(stderr, "sph: error: cannot read options file '%s' (%s); check the path\n", argv[k + 1], opt.c_str());
      return false;
    }
    std::string token;
    const int line = opt == "-options_file" ? first_bad_line(f, &token) : 0;  // YAML is PETSc's to parse
    std::fclose(f);
    if (line > 0) {
      std::fprintf(stderr,
                   "sph: error: options file '%s' line %d: '%s' is not an option; each line holds -name [value], "
                   "and '#' starts a comment\n",
                   argv[k + 1], line, token.c_str());
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (!options_files_valid(argc, argv)) return 1;
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) {
    std::fprintf(stderr, "sph: error: could not initialise PETSc/MPI (check -options_file paths)\n");
    return 1;
  }
  sph::install_error_handler();
  sph::install_interrupt_handlers();
  int status = 0;
  try {
    sph::RunOptions names;
    PetscInt dim = 0;
    PetscBool dim_set = PETSC_FALSE, help = PETSC_FALSE;
    SPH_PETSC(read_names(&names, &dim, &dim_set));
    SPH_PETSC(PetscOptionsHasHelp(nullptr, &help));
    // -help lists the options without reading the case's input.
    if (!dim_set) dim = help ? sph::find_case(names.case_name).default_dim : sph::case_dimension(names.case_name);
    if (help) sph::print_all_options(static_cast<int>(dim));
    else sph::run_simulation(names, static_cast<int>(dim));
  } catch (const sph::Interrupted& i) {
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: %s\n", i.message.c_str());
    status = 128 + i.signal;
  } catch (const sph::Error& e) {
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: error: %s\n", e.what());
    status = 1;
  } catch (const std::exception& e) {
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: internal error: %s\n", e.what());
    status = 2;
  }
  PetscFinalize();
  return status;
}
