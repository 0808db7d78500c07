#pragma once
// Keeps fluid particles out of the walls by the walls' geometry, not by the pressure their particles
// exert: a fluid particle found behind a wall's face is put back on the face, and its velocity into the
// wall (relative to the wall's) is removed. A wall of dummy particles stops the fluid only through the
// ripple of the kernel sum over its lattice; a kernel whose sum is flat over the lattice (the one that
// keeps WCSPH's square lattice stable) puts no barrier there, and fluid seeps between the wall's
// particles (docs/verification/free_surface.md, "The quintic spline's stable window"). The same
// constraint on a level set is SPHinXsys' "bounding"; here the face is found from the wall particles:
//   a wall particle w, with its unit normal n_w into the fluid (AdamiWall::normals), has its face
//   dx/2 beyond it, so particle i lies depth_w = dx/2 - (x_i - x_w) . n_w behind that face;
//   i is behind the walls' face when the largest depth_w over the wall particles within dx of it is
//   positive and the walls hold more than half of its kernel sum (sum_w V_w W_iw > 1/2: a flat face
//   has exactly one half, by the lattice's mirror symmetry about it), and is moved by that depth along
//   that n_w.
// Either test alone is wrong at corners: the walls' share of the kernel sum exceeds one half in front of
// a concave corner's faces, and a convex corner's diagonal normal gives a positive depth in front of
// its faces. The largest depth, not the nearest particle's: inside a wall's lattice, at the centre of a
// cell, the wall particles of two layers are equally near, and only the outer layer's depth is right.
#include <limits>
#include <vector>

#include "src/boundary/adami_wall.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

// Puts the owned fluid particles found behind a wall's face back on it (positions and velocities).
// Needs current ghosts (positions, masses, densities, velocities); returns how many were moved, over
// all ranks.
template <int D> long bound_to_walls(Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K, double dx) {
  const NeighbourList<D>& nl = nh.list();
  std::vector<Vector<D>> normal = AdamiWall<D>::normals(P, nl, K, AdamiWall<D>::stencil(P, nl, K));
  nh.halo().update(normal);
  struct Contact {
    double wall_share = 0.0, depth = -std::numeric_limits<double>::infinity();
    int wall = -1;  // the wall particle whose face is the deepest behind
  };
  const std::vector<Contact> contact = sum_over_pairs(
      P, nl, K, Contact{},
      [&](Contact& c, int, int w, const PairGeometry<D>& g) {
        if (P.kind[w] == kFluid) return;
        c.wall_share += P.m[w] / P.rho[w] * g.W;
        const double depth = 0.5 * dx - g.rij.dot(normal[w]);
        if (g.r < dx && normal[w].squaredNorm() > 0.0 && depth > c.depth) c.depth = depth, c.wall = w;
      },
      Rows::Fluid);
  long moved = 0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const Contact& c = contact[i];
    if (P.kind[i] != kFluid || c.wall < 0 || c.depth <= 0.0 || c.wall_share <= 0.5) continue;
    const Vector<D>& n = normal[c.wall];
    P.x[i] += c.depth * n;
    const double approach = (P.v[i] - P.v[c.wall]).dot(n);
    if (approach < 0.0) P.v[i] -= approach * n;
    ++moved;
  }
  MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_LONG, MPI_SUM, PETSC_COMM_WORLD);
  return moved;
}

}  // namespace sph
