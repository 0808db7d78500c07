#pragma once
// Contact that keeps a free body (src/boundary/free_body.hpp) out of the walls and the other bodies:
// a linear spring-dashpot on each pair of a free body's particle and another solid's particle closer
// than the lattice spacing dx (the particles of two solids that touch are dx apart), pushing along the
// line between them. The fluid between two solids keeps them apart until it is squeezed out; what the
// pairs then feel is this force. Each pair's stiffness is a particle's share m of its body's mass
// ringing at omega, k = m omega^2, critically damped, with omega^2 = |g| / (0.01 dx): a body resting on
// its lowest row of particles sinks its rows times 1 % of dx into what it rests on. While any pair is
// within 1.5 dx the step is held to a twentieth of the period 2 pi / omega (contact_step), so the
// contact is resolved. docs/verification/free_bodies.md, "Contact".
#include <mpi.h>
#include <petscsys.h>

#include <cmath>
#include <vector>

#include "src/boundary/moving_bodies.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/particles/particles.hpp"
#include "src/sph/wall_forces.hpp"

namespace sph {

template <int D> struct ContactLoad {
  std::vector<Vector<D>> force;         // per body (zero on bodies that are not free)
  std::vector<Eigen::Vector3d> moment;  // per body, about its centre of mass
  bool near = false;                    // some pair within 1.5 dx: the step is held (contact_step)
};

// The contact's ringing rate omega, sqrt(|g| / (0.01 dx)); without gravity 10 / dx, as fast for dx = 0.01.
inline double contact_rate(double gravity, double dx) {
  return gravity > 0.0 ? std::sqrt(gravity / (0.01 * dx)) : 10.0 / dx;
}
// The longest step that resolves the contact: a twentieth of its period.
inline double contact_step(double gravity, double dx) { return 2.0 * M_PI / (20.0 * contact_rate(gravity, dx)); }

// P: positions and velocities with fresh ghosts. Reduced over all ranks.
template <int D> ContactLoad<D> body_contact(const Particles<D>& P, const NeighbourList<D>& list,
                                             const MovingBodies<D>& bodies, double dx, double gravity) {
  const std::size_t n_bodies = bodies.count();
  ContactLoad<D> out{std::vector<Vector<D>>(n_bodies, Vector<D>::Zero()),
                     std::vector<Eigen::Vector3d>(n_bodies, Eigen::Vector3d::Zero())};
  const double rate = contact_rate(gravity, dx);
  int near = 0;
  // A particle's share of its body's mass; another solid's wall particles are as heavy as the pair needs.
  auto particle_mass = [&](std::size_t i) {
    const FreeBody<D>* f = bodies.free_of(P, i);
    return f && f->particles > 0 ? f->mass / static_cast<double>(f->particles) : 0.0;
  };
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const FreeBody<D>* f = bodies.free_of(P, i);
    if (!f) continue;
    const int b = bodies.body_of(P, i);
    const double mi = particle_mass(i);
    for (const int* it = list.begin(i); it != list.end(i); ++it) {
      const std::size_t j = static_cast<std::size_t>(*it);
      if (P.kind[j] != kWall || bodies.body_of(P, j) == b) continue;
      const Vector<D> r = P.x[i] - P.x[j];
      const double d = r.norm();
      near |= d < 1.5 * dx;
      if (d >= dx || d == 0.0) continue;
      const double mj = particle_mass(j);
      const double m = mj > 0.0 ? mi * mj / (mi + mj) : mi;  // two free bodies: their reduced mass
      const double k = m * rate * rate, c = 2.0 * std::sqrt(k * m);
      const Vector<D> e = r / d;
      const double push = std::max(0.0, k * (dx - d) - c * (P.v[i] - P.v[j]).dot(e));
      const Vector<D> fi = push * e;
      out.force[static_cast<std::size_t>(b)] += fi;
      out.moment[static_cast<std::size_t>(b)] += moment_of<D>(Vector<D>(P.x[i] - f->centre), fi);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &near, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  out.near = near != 0;
  for (std::size_t b = 0; b < n_bodies; ++b) {
    MPI_Allreduce(MPI_IN_PLACE, out.force[b].data(), D, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, out.moment[b].data(), 3, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  }
  return out;
}

}  // namespace sph
