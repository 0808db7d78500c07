#pragma once
// Shared-memory threads per MPI rank (OpenMP): the pair loops, the neighbour search and hypre's
// BoomerAMG all use omp_get_max_threads(). The default fills the cores this rank may run on, shared
// with the other ranks on the same node, so an MPI run does not oversubscribe (OpenMP's own default,
// every core per rank, made hypre's set-up 10x slower on 2 ranks of a 2-core machine).
namespace sph {

// Sets the thread count for the rest of the run and returns it. requested > 0: that many;
// requested == 0: OMP_NUM_THREADS when set, else the CPUs in this process's affinity mask divided by
// the ranks on this node (at least 1). Collective on PETSC_COMM_WORLD.
int configure_threads(int requested);

// Threads the pair loops use now (1 in a build without OpenMP).
int max_threads();

}  // namespace sph
