#pragma once
// Checks on bodies whose motion the program follows whatever it does: a body carried out of the box
// stops the run (its particles would leave the neighbour search's box and the walls' reach), and a body
// whose prescribed motion drives it through a fixed wall is named in a warning (its particles and the
// wall's overlap; the fluid between them is squeezed out or trapped). Both collective.
#include <mpi.h>
#include <petscsys.h>

#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "src/boundary/moving_bodies.hpp"
#include "src/core/domain.hpp"
#include "src/core/error.hpp"
#include "src/neighbours/neighbour_list.hpp"

namespace sph {

// The name of body b for messages (its index where the case gives no names).
inline std::string body_label(const std::vector<std::string>& names, int b) {
  return b >= 0 && static_cast<std::size_t>(b) < names.size() ? "'" + names[static_cast<std::size_t>(b)] + "'"
                                                              : "number " + std::to_string(b);
}

// Throws when a particle of a moving body lies outside the box's non-periodic sides.
template <int D> void check_bodies_in_box(const Particles<D>& P, const Domain<D>& domain, const MovingBodies<D>& bodies,
                                          const std::vector<std::string>& names, double t) {
  if (!bodies.any()) return;
  int out = std::numeric_limits<int>::max();  // the lowest body index outside
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (bodies.moves(P, i) && domain.outside(P.x[i])) out = std::min(out, bodies.body_of(P, i));
  MPI_Allreduce(MPI_IN_PLACE, &out, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (out == std::numeric_limits<int>::max()) return;
  std::ostringstream msg;
  msg << "body " << body_label(names, out) << " left the box [";
  for (int a = 0; a < D; ++a) msg << (a ? ", " : "") << domain.lo[a] << ", " << domain.hi[a];
  msg << "] at t = " << t << ": "
      << (bodies.free_body(static_cast<std::size_t>(out))
              ? "the fluid carried it out; enlarge the scene's box"
              : "its prescribed motion carries it out; enlarge the scene's box, or change the motion or -t_end");
  throw Error(msg.str());
}

// The bodies with prescribed motion that have a particle closer than half a spacing to a fixed wall's
// (a wall's face lies half a spacing from its particles, so the two solids overlap), as a mask by body
// index; on the current lists, so pairs that came within reach since the last rebuild may be missed.
template <int D> std::vector<int> bodies_in_fixed_walls(const Particles<D>& P, const NeighbourList<D>& nl,
                                                        const MovingBodies<D>& bodies, double dx) {
  std::vector<int> inside(bodies.count(), 0);
  if (!bodies.any() || inside.empty()) return inside;
  const double r2 = 0.25 * dx * dx;
  const std::size_t rows = std::min(P.n_owned, nl.size());
  for (std::size_t i = 0; i < rows; ++i) {
    if (!bodies.motion_of(P, i)) continue;
    for (const int* j = nl.begin(i); j != nl.end(i); ++j) {
      const auto k = static_cast<std::size_t>(*j);
      if (P.kind[k] == kWall && !bodies.moves(P, k) && (P.x[k] - P.x[i]).squaredNorm() < r2) {
        inside[static_cast<std::size_t>(bodies.body_of(P, i))] = 1;
        break;
      }
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, inside.data(), static_cast<int>(inside.size()), MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return inside;
}

}  // namespace sph
