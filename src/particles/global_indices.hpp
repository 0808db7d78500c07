#pragma once
// Global numbering of particles across ranks.
#include <petscsys.h>

#include "src/particles/particles.hpp"

namespace sph {

// Gives owned particles contiguous global indices, rank by rank (PETSc's row ownership), and particles
// without a permanent label (id < 0: new ones) the same number as their label.
template <int D> void assign_global_indices(Particles<D>& P) {
  GlobalIndex n = static_cast<GlobalIndex>(P.n_owned), first = 0, total = 0;
  MPI_Exscan(&n, &first, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(&n, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) first = 0;  // MPI_Exscan leaves rank 0's result undefined
  P.first_gid = first;
  P.n_global = total;
  P.id.resize(P.gid.size(), -1);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    P.gid[i] = first + static_cast<GlobalIndex>(i);
    if (P.id[i] < 0) P.id[i] = P.gid[i];
  }
}

}  // namespace sph
