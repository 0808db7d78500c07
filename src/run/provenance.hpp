#pragma once
// Where a run's results came from, for summary.json: the command line and the options database, the
// program's version (git describe at build time), the versions of PETSc, hypre, VTK and MPI, and the
// ranks, threads and cores it ran on.
#include <nlohmann/json.hpp>
#include <string>

namespace sph {

// Defined in the build's generated version.cpp (cmake/version.cmake).
const char* program_version();

// The command line as typed (shell-quoted where needed).
std::string command_line();

// Collective on PETSC_COMM_WORLD (counts the ranks).
nlohmann::json provenance(int threads_per_rank);

}  // namespace sph
