// sph: the command-line program. Picks a case and a solver by name (-case, -solver), reads every
// other parameter from PETSc's options database (-help lists them), and runs.
//
//   ./build/sph -case taylor_green -solver isph -nx 64 -re 100 -t_end 1
//   ./build/sph -options_file cases/taylor_green.opts -ppe_ksp_type gmres -ppe_ksp_monitor
#include <petscsys.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "cases/registry.hpp"
#include "solvers/registry.hpp"
#include "src/core/error.hpp"
#include "src/core/option_reads.hpp"
#include "src/run/interrupt.hpp"
#include "src/run/provenance.hpp"

namespace {

// -help prints this first (PETSc's own options follow, then every block of this program's, each with
// its default): the options most runs need. cli.options checks that each one exists.
const char kEssentialHelp[] =
    "sph: ISPH and WCSPH smoothed particle hydrodynamics. Essential options (every option is listed\n"
    "below with its default, and in docs/options.md; \"(expert)\" marks the numerical method's settings\n"
    "that few runs change):\n"
    "  -case NAME             the scene: taylor_green, lid_driven_cavity, dam_break, still_water, ...,\n"
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
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Scene and scheme", "sph");
  PetscCall(sph::option_choice(PetscOptionsObject, "-case", "Scene to run", cases.data(),
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

// A line of an options file as PETSc splits it: words, a double-quoted one counting as one.
std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  for (std::size_t k = line.find_first_not_of(" \t\r\n"); k != std::string::npos;
       k = line.find_first_not_of(" \t\r\n", k)) {
    const bool quoted = line[k] == '"';
    const std::size_t end = quoted ? line.find('"', k + 1) : line.find_first_of(" \t\r\n", k);
    out.push_back(line.substr(k + quoted, end == std::string::npos ? std::string::npos : end - k - quoted));
    k = end == std::string::npos ? end : end + quoted;
  }
  return out;
}

// What PETSc would refuse in an options file with a traceback (or, for a file that includes itself,
// with a crash): checked here, with the files it includes, so the user gets one line naming the cause.
// `chain` holds the files that include this one. Returns the one-line message, or "" when all is well.
std::string options_file_problem(const std::string& path, const std::string& opt, std::vector<std::string>& chain) {
  struct stat st {};
  if (stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    return "options file '" + path + "' (" + opt + ") is a folder; give the path of a file";
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return "cannot read options file '" + path + "' (" + opt + "); check the path";
  char* real = realpath(path.c_str(), nullptr);
  const std::string id = real ? real : path;
  std::free(real);
  for (const std::string& outer : chain)
    if (outer == id) {
      std::fclose(f);
      return "options file '" + path + "' includes itself (through -options_file); remove the loop";
    }
  chain.push_back(id);
  std::string problem;
  char buf[4096];
  for (int line = 1; problem.empty() && std::fgets(buf, sizeof buf, f); ++line) {
    std::string text(buf);
    const std::vector<std::string> w = words(text.substr(0, text.find('#')));  // '#' starts a comment
    const std::string where = "options file '" + path + "' line " + std::to_string(line) + ": ";
    if (w.empty() || w[0] == "alias") continue;
    if (w[0][0] != '-')
      problem = where + "'" + w[0] + "' is not an option; each line holds -name [value], and '#' starts a comment";
    else if (w.size() > 2)
      problem = where + "'" + w[2] + "' follows the value of " + w[0] + "; put each option on a line of its own";
    else if (w.size() == 2 && (w[0] == "-options_file" || w[0] == "-options_file_yaml"))
      problem = w[0] == "-options_file" ? options_file_problem(w[1], w[0], chain) : "";
  }
  std::fclose(f);
  chain.pop_back();
  return problem;
}

// PETSc reads -options_file during initialisation, before a quiet error handler can be installed:
// check the files first so a wrong path or a malformed line gets one line instead of a PETSc traceback.
bool options_files_valid(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string opt = argv[k];
    if (opt != "-options_file" && opt != "-options_file_yaml") continue;
    // Without a file name PETSc prints a 20-line traceback; the next word is a name as PETSc reads it
    // unless it is an option (a '-' not starting a number).
    const char* next = k + 1 < argc ? argv[k + 1] : nullptr;
    if (!next || (next[0] == '-' && !std::isdigit(static_cast<unsigned char>(next[1])) && next[1] != '.')) {
      std::fprintf(stderr,
                   "sph: error: option %s was given without a file name; give the path of an options file "
                   "(e.g. %s cases/taylor_green.opts) or leave it out\n",
                   opt.c_str(), opt.c_str());
      return false;
    }
    std::vector<std::string> chain;
    std::string problem;
    if (opt == "-options_file") problem = options_file_problem(argv[k + 1], opt, chain);
    else if (access(argv[k + 1], R_OK) != 0)  // a YAML file's contents are PETSc's to parse
      problem = "cannot read options file '" + std::string(argv[k + 1]) + "' (" + opt + "); check the path";
    if (!problem.empty()) {
      std::fprintf(stderr, "sph: error: %s\n", problem.c_str());
      return false;
    }
  }
  return true;
}

// Whether this invocation only prints (-help, -version) and runs nothing.
bool only_prints(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "-help" || a == "-h" || a == "--help" || a == "-version") return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (!options_files_valid(argc, argv)) return 1;
  // Printing the help into a closed pipe (sph -help | head) must end quietly, as any printing program
  // does, not in PETSc's crash report: its signal handler, installed while it prints, catches SIGPIPE.
  const bool printing = only_prints(argc, argv);
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
