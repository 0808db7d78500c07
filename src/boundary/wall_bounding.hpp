#pragma once
// Keeps fluid particles out of the walls by the walls' geometry, not by the pressure their particles
// exert: a fluid particle found behind a wall's face is put back on the face, and its velocity into the
// wall (relative to the wall's) is removed. A wall of dummy particles stops the fluid only through the
// ripple of the kernel sum over its lattice; a kernel whose sum is flat over the lattice (the one that
// keeps WCSPH's square lattice stable) puts no barrier there, and fluid seeps between the wall's
// particles (docs/verification/free_surface.md, "The quintic spline's stable window"). The same
// constraint on a level set is SPHinXsys' "bounding"; here the face is found from the wall particles:
//   a wall particle w, with its unit normal n_w into the fluid (AdamiWall::face_normals), has its face
//   dx/2 beyond it, so particle i lies depth_w = dx/2 - (x_i - x_w) . n_w behind that face;
//   i is behind the walls' face when the largest depth_w over the wall particles within dx of it is
//   positive and either the walls hold more than half of its kernel sum (sum_w V_w W_iw > 1/2: a flat
//   face has exactly one half, by the lattice's mirror symmetry about it) or a wall particle is nearer
//   than dx/2 (inside that particle's cell: the fluid_in_walls diagnostic's test); it is moved by that
//   depth along that n_w.
// The depth alone is wrong at a convex corner, whose diagonal normal gives a positive depth in front of
// its faces; the share alone at a concave corner, where it exceeds one half in front of the faces, and
// behind a convex body's face, where it is below one half (a cylinder a few dx across). The largest
// depth, not the nearest particle's: inside a wall's lattice, at the centre of a cell, the wall
// particles of two layers are equally near, and only the outer layer's depth is right.
#include <algorithm>
#include <limits>
#include <vector>

#include "src/boundary/adami_wall.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

// Puts the owned fluid particles found behind a wall's face back on it (positions and velocities),
// with the walls' face normals kept from one neighbour-list rebuild to the next (fixed walls keep
// theirs), so that a step costs one pass over the fluid's pairs and not another over the walls'
// (docs/verification/free_surface.md, "A wall that holds without the ripple"). The normals weigh the
// walls by their mass over rho0, not by their current density: they depend on the walls' places alone,
// whenever they are taken, and a restart, which rebuilds the lists, resumes bit for bit.
template <int D> class WallBounding {
 public:
  // Needs current ghosts (positions, masses, densities, velocities) and leaves them current. walls_moved:
  // moving bodies, whose normals turn with them. Returns how many particles were moved, over all ranks.
  long apply(Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K, double dx, double rho0, bool walls_moved) {
    if (walls_moved || nh.rebuilds() != built_) {
      normal_ = AdamiWall<D>::face_normals(P, nh.list(), K, [&](int j) { return P.m[j] / rho0; });
      nh.halo().update(normal_);
      built_ = nh.rebuilds();
    }
    const long moved = bound(P, nh.list(), K, dx);
    if (moved > 0) nh.update(P);  // the ghosts of the particles moved, for what reads them next (the walls' pressure)
    return moved;
  }

 private:
  long bound(Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, double dx) const {
    struct Contact {
      double wall_share = 0.0, depth = -std::numeric_limits<double>::infinity(),
             nearest = std::numeric_limits<double>::infinity();
      int wall = -1;  // the wall particle whose face is the deepest behind
    };
    const std::vector<Contact> contact = sum_over_pairs(
        P, nl, K, Contact{},
        [&](Contact& c, int, int w, const PairGeometry<D>& g) {
          if (P.kind[w] != kWall) return;
          c.wall_share += P.m[w] / P.rho[w] * g.W;
          c.nearest = std::min(c.nearest, g.r);
          const double depth = 0.5 * dx - g.rij.dot(normal_[w]);
          if (g.r < dx && normal_[w].squaredNorm() > 0.0 && depth > c.depth) c.depth = depth, c.wall = w;
        },
        Rows::Fluid);
    long moved = 0;
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      const Contact& c = contact[i];
      const bool behind = c.wall_share > 0.5 || c.nearest < 0.5 * dx;
      if (P.kind[i] != kFluid || c.wall < 0 || c.depth <= 0.0 || !behind) continue;
      const Vector<D>& n = normal_[c.wall];
      P.x[i] += c.depth * n;
      const double approach = (P.v[i] - P.v[c.wall]).dot(n);
      if (approach < 0.0) P.v[i] -= approach * n;
      ++moved;
    }
    MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_LONG, MPI_SUM, PETSC_COMM_WORLD);
    return moved;
  }

  std::vector<Vector<D>> normal_;  // the walls' face normals, owned and ghosts
  long built_ = -1;                // at this count of the neighbourhood's rebuilds
};

}  // namespace sph
