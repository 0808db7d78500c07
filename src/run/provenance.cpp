#include "src/run/provenance.hpp"

#include <petscpkg_version.h>
#include <petscsys.h>
#include <sched.h>
#include <unistd.h>
#include <vtkVersion.h>

#include <thread>

#include "src/run/run_identity.hpp"

namespace sph {

namespace {

std::string shell_quoted(const std::string& arg) {
  if (!arg.empty() &&
      arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_=./:,+@%") ==
          std::string::npos)
    return arg;
  std::string out = "'";
  for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string hypre_version() {
#if defined(PETSC_HAVE_HYPRE)
  return std::to_string(PETSC_PKG_HYPRE_VERSION_MAJOR) + "." + std::to_string(PETSC_PKG_HYPRE_VERSION_MINOR) + "." +
         std::to_string(PETSC_PKG_HYPRE_VERSION_SUBMINOR);
#else
  return "none (PETSc built without hypre)";
#endif
}

std::string mpi_library() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int len = 0;
  MPI_Get_library_version(text, &len);
  std::string s(text, static_cast<std::size_t>(len));
  const auto end = s.find_first_of(",\n");  // the first clause names library and version
  return s.substr(0, end);
}

}  // namespace

std::string command_line() {
  int argc = 0;
  char** argv = nullptr;
  if (PetscGetArgs(&argc, &argv) != 0) return "";
  std::string line;
  for (int k = 0; k < argc; ++k) line += (k ? " " : "") + shell_quoted(argv[k]);
  return line;
}

nlohmann::json provenance(int threads_per_rank) {
  PetscMPIInt ranks = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  cpu_set_t mask;
  const int cores_usable = sched_getaffinity(0, sizeof mask, &mask) == 0 ? CPU_COUNT(&mask) : -1;
  char host[256] = "";
  gethostname(host, sizeof host - 1);
  const std::string petsc = std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR) + "." +
                            std::to_string(PETSC_VERSION_SUBMINOR);
  return {{"command_line", command_line()},
          {"options", options_database()},
          {"version", program_version()},
          {"petsc", petsc},
          {"hypre", hypre_version()},
          {"vtk", vtkVersion::GetVTKVersion()},
          {"mpi", mpi_library()},
          {"mpi_ranks", ranks},
          {"threads_per_rank", threads_per_rank},
          {"cores", {{"online", std::thread::hardware_concurrency()}, {"usable_by_rank_0", cores_usable}}},
          {"host", host}};
}

}  // namespace sph
