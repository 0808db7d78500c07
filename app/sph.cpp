// sph: the command-line program. Picks a case and a solver by name (-case, -solver), reads every
// other parameter from PETSc's options database (-help lists them), and runs.
//
//   ./build/sph -case taylor_green -solver isph -nx 64 -re 100 -t_end 1
//   ./build/sph -options_file cases/taylor_green.opts -ppe_ksp_type gmres -ppe_ksp_monitor
#include <petscsys.h>

#include <csignal>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "cases/registry.hpp"
#include "solvers/registry.hpp"
#include "src/core/error.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options_files.hpp"
#include "src/run/interrupt.hpp"
#include "src/run/provenance.hpp"

namespace {

// -help prints this first (PETSc's own options follow, then every block of this program's, each with
// its default): the options most runs need. cli.options checks that each one exists.
const char kEssentialHelp[] =
    "sph: ISPH, WCSPH and compressible SPH. Essential options (every option is listed\n"
    "below with its default, and in docs/options.md; \"(expert)\" marks the numerical method's settings\n"
    "that few runs change):\n"
    "  -case NAME             the case: taylor_green, lid_driven_cavity, dam_break, still_water, ...,\n"
    "                         or scene with -scene_file FILE (a YAML scene of shapes or a .vtp)\n"
    "  -solver NAME           isph (the default), wcsph or compressible\n"
    "  -nx N                  resolution: particles per unit length (the case says which length)\n"
    "  -re RE                 Reynolds number, for the cases that have one\n"
    "  -t_end T               end time\n"
    "  -cfl C                 ISPH's Courant number (advective); -acoustic_cfl for WCSPH\n"
    "  -output_dir DIR        frames (.vtp), timeseries.csv, summary.json and checkpoint.bin\n"
    "  -output_interval T     time between frames\n"
    "  -restart FILE          continue from a checkpoint.bin\n"
    "  -threads N             OpenMP threads per MPI rank\n"
    "  -ppe_ksp_type, -ppe_pc_type\n"
    "                         the pressure solve (ISPH), any PETSc KSP and PC: its PETSc options\n"
    "                         carry the prefix ppe_ (-ppe_ksp_rtol, -ppe_ksp_monitor, ...)\n"
    "  -options_file FILE     options from a file (cases/*.opts)\n\n";

PetscErrorCode read_names(sph::RunOptions* o, PetscInt* dim, PetscBool* dim_set) {
  PetscFunctionBeginUser;
  std::vector<const char*> cases, solvers;
  for (const auto& e : sph::case_registry()) cases.push_back(e.name.c_str());
  for (const auto& s : sph::solver_names()) solvers.push_back(s.c_str());
  PetscInt c = 0, s = 0;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Case and scheme", "sph");
  PetscCall(sph::option_choice(PetscOptionsObject, "-case", "Case to run", cases.data(),
                               static_cast<PetscInt>(cases.size()), cases[0], &c, nullptr));
  PetscCall(sph::option_choice(PetscOptionsObject, "-solver", "Time-stepping scheme", solvers.data(),
                               static_cast<PetscInt>(solvers.size()), solvers[0], &s, nullptr));
  PetscCall(
      sph::option_int(PetscOptionsObject, "-dim", "Spatial dimension (default: the case's own)", *dim, dim, dim_set));
  PetscOptionsEnd();
  o->case_name = cases[c];
  o->solver_name = solvers[s];
  PetscFunctionReturn(0);
}

}  // namespace

int main(int argc, char** argv) {
  if (!sph::options_files_valid(argc, argv)) return 1;
  // Printing the help into a closed pipe (sph -help | head) must end quietly, as any printing program
  // does, not in PETSc's crash report: its signal handler, installed while it prints, catches SIGPIPE.
  const bool printing = sph::only_prints(argc, argv);
  if (printing) PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  if (PetscInitialize(&argc, &argv, nullptr, kEssentialHelp)) {
    std::fprintf(stderr, "sph: error: could not initialise PETSc/MPI (check -options_file paths)\n");
    return 1;
  }
  sph::install_error_handler();
  sph::install_interrupt_handlers();
  if (printing) std::signal(SIGPIPE, SIG_DFL);
  // PETSc printed its own version during initialisation; -version runs nothing.
  PetscBool version = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-version", &version);
  if (version) {
    PetscPrintf(PETSC_COMM_WORLD, "sph %s\n", sph::program_version());
    PetscFinalize();
    return 0;
  }
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
  } catch (const std::bad_alloc&) {
    // Past the memory check (a memory limit below the machine's, or a peak it did not foresee).
    PetscFPrintf(PETSC_COMM_WORLD, stderr,
                 "sph: error: ran out of memory (an allocation failed): the run needs more than this machine or its "
                 "memory limit (ulimit -v) gives; lower -nx (fewer particles)\n");
    status = 1;
  } catch (const std::exception& e) {
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: internal error: %s\n", e.what());
    status = 2;
  }
  PetscFinalize();
  return status;
}
