#pragma once
// Fluid that leaves the box (-box_exit auto, the default, or remove): splashes thrown over an open
// tank's walls are taken out of the run instead of stopping it, and counted; fluid that went through a
// wall still stops the run under auto. The owned particles beyond a side that is not
// periodic go, with the solver's per-particle arrays; the others keep their order.
#include <mpi.h>

#include <algorithm>
#include <vector>

#include "src/core/domain.hpp"
#include "src/neighbours/neighbour_list.hpp"
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

// Whether fluid particle i, outside the box, went through a wall rather than over an open side: where
// it crossed the box's side (its place clipped to the box) lies in a wall, within half a spacing of a
// wall particle along every axis (a wall particle's lattice cell; 0.6 dx for round-off). A particle
// thrown over a wall's top crosses at least its gap to the wall above the top layer.
template <int D>
bool left_through_wall(const Particles<D>& P, const NeighbourList<D>& nl, const Domain<D>& domain, std::size_t i,
                       double dx) {
  Vector<D> crossing = P.x[i];
  for (int a = 0; a < D; ++a) crossing[a] = std::clamp(crossing[a], domain.lo[a], domain.hi[a]);
  for (const int* j = nl.begin(i); j != nl.end(i); ++j)
    if (P.kind[*j] != kFluid && (crossing - P.x[*j]).cwiseAbs().maxCoeff() <= 0.6 * dx) return true;
  return false;
}

// Removes the owned fluid particles outside the box that did not go through a wall (-box_exit auto), or
// all of them (`through_walls_too`, -box_exit remove). The others stay for the health check to stop at.
template <int D>
RemovedFluid remove_fluid_outside(Particles<D>& P, const NeighbourList<D>& nl, const Domain<D>& domain, double dx,
                                  bool through_walls_too) {
  std::vector<char> gone(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    gone[i] = P.kind[i] == kFluid && domain.outside(P.x[i]) &&
              (through_walls_too || !left_through_wall(P, nl, domain, i, dx));
  return remove_particles_if(P, [&](std::size_t i) { return gone[i] != 0; });
}

// Whether any rank owns fluid outside the box. Collective.
template <int D> bool fluid_outside(const Particles<D>& P, const Domain<D>& domain) {
  int any = 0;
  for (std::size_t i = 0; i < P.n_owned && !any; ++i) any = P.kind[i] == kFluid && domain.outside(P.x[i]);
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return any != 0;
}

}  // namespace sph
