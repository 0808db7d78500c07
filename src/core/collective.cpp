#include "src/core/collective.hpp"

#include <petscsys.h>

#include "src/core/error.hpp"

namespace sph {

void broadcast_from_root(std::string& text) {
  unsigned long n = text.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, PETSC_COMM_WORLD);
  text.resize(n);
  if (n) MPI_Bcast(text.data(), static_cast<int>(n), MPI_CHAR, 0, PETSC_COMM_WORLD);
}

void throw_if_root_failed(std::string error) {
  broadcast_from_root(error);
  if (!error.empty()) throw Error(error);
}

}  // namespace sph
