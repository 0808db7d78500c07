#pragma once
// Helpers for building scenes on a square lattice (core types only).
#include <mpi.h>
#include <petscsys.h>

#include "src/particles/particles.hpp"

namespace sph {

// Keeps this rank's contiguous share of a scene every rank built identically.
template <int D> Particles<D> rank_share(const Particles<D>& all) {
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const std::size_t n = all.n_owned, begin = n * rank / size, end = n * (rank + 1) / size;
  Particles<D> mine;
  for (std::size_t i = begin; i < end; ++i) mine.add(all.x[i], all.v[i], all.m[i], all.rho[i], all.p[i], all.kind[i]);
  return mine;
}

}  // namespace sph
