#pragma once
// Taking owned particles out of a run: fluid that left the box (src/run/box_exit.hpp), outlet
// particles past their buffer (src/boundary/open_boundaries.hpp).
#include <mpi.h>
#include <petscsys.h>

#include <cstddef>

#include "src/particles/global_indices.hpp"
#include "src/particles/particles.hpp"

namespace sph {

struct RemovedFluid {
  long long count = 0;  // particles, all ranks
  double mass = 0.0;
};

// Removes the owned particles for which gone(i) holds, with their rows of the declared fields, and
// renumbers the rest; drops the ghosts (the caller rebuilds its neighbourhood). Collective.
template <int D, class Gone> RemovedFluid remove_particles_if(Particles<D>& P, const Gone& gone) {
  RemovedFluid removed;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (gone(i)) {
      ++removed.count, removed.mass += P.m[i];
      continue;
    }
    if (kept != i) {
      P.x[kept] = P.x[i], P.v[kept] = P.v[i], P.m[kept] = P.m[i], P.rho[kept] = P.rho[i], P.p[kept] = P.p[i];
      P.kind[kept] = P.kind[i], P.id[kept] = P.id[i];
      P.fields.copy_row(kept, i);
    }
    ++kept;
  }
  P.n_owned = kept;
  P.set_ghost_count(0);
  assign_global_indices(P);
  MPI_Allreduce(MPI_IN_PLACE, &removed.count, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &removed.mass, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return removed;
}

}  // namespace sph
