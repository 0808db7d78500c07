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
#include "src/particles/particles.hpp"
#include "src/particles/remove_particles.hpp"

namespace sph {

// Whether fluid particle i, outside the box, went through a wall rather than over an open side: where
// it crossed the box's side (its place clipped to the box) lies in a wall, within half a spacing of a
// wall particle along every axis (a wall particle's lattice cell, to round-off). A particle thrown over
// a wall's top crosses at least its gap to the wall above the top layer; one that climbed a wall's face
// to the box's top crosses just beside the wall's cells, so the cells take no margin beyond round-off.
template <int D> bool left_through_wall(const Particles<D>& P, const NeighbourList<D>& nl, const Domain<D>& domain,
                                        std::size_t i, double dx) {
  Vector<D> crossing = P.x[i];
  for (int a = 0; a < D; ++a) crossing[a] = std::clamp(crossing[a], domain.lo[a], domain.hi[a]);
  const double cell = (0.5 + 1e-9) * dx;
  for (const int* j = nl.begin(i); j != nl.end(i); ++j)
    if (P.kind[*j] == kWall && (crossing - P.x[*j]).cwiseAbs().maxCoeff() <= cell) return true;
  return false;
}

// Removes the owned fluid particles outside the box that did not go through a wall (-box_exit auto), or
// all of them (`through_walls_too`, -box_exit remove). The others stay for the health check to stop at.
template <int D> RemovedFluid remove_fluid_outside(Particles<D>& P, const NeighbourList<D>& nl, const Domain<D>& domain,
                                                   double dx, bool through_walls_too) {
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
