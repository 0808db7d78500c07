#pragma once
// The boundary model of the walls: what a scheme's step asks of its wall particles (and inlets',
// which take their pressure from the fluid as walls do), behind one interface. A scheme holds the
// model its options chose and calls only these; a new wall treatment is a new class and a name in
// make_wall_model (src/boundary/adami_wall_model.hpp), not an edit of each scheme's step
// (docs/developer.md, "Add a boundary model").
#include <mpi.h>
#include <petscsys.h>

#include <memory>
#include <string>
#include <vector>

#include "src/boundary/moving_bodies.hpp"
#include "src/kernels/kernel.hpp"
#include "src/neighbours/neighbourhood.hpp"

namespace sph {

// How a wall particle's pressure continues a fluid neighbour's: p_w = sum_f w_wf (p_f + head(w, f)).
// Explicit schemes evaluate it; ISPH's wall rows hold it as an equation.
template <int D> struct WallContinuation {
  std::vector<Vector<D>> normal;    // owned walls' n into the fluid (empty or zero: rho g_eff . r whole)
  std::vector<Vector<D>> gradient;  // fluid particles' own pressure gradient, owned and ghost

  // The head from fluid neighbour f to wall w, rho_f g_eff . r_wf along the normal and the fluid's own
  // gradient along the wall; inlets, and walls with no normal, take rho_f g_eff . r_wf whole.
  double head(std::size_t w, std::size_t f, const Vector<D>& g_eff, const Vector<D>& r_wf, double rho_f) const {
    if (w >= normal.size() || normal[w].squaredNorm() == 0.0) return rho_f * g_eff.dot(r_wf);
    const Vector<D>& n = normal[w];
    const double across = n.dot(r_wf);
    return rho_f * g_eff.dot(n) * across + gradient[f].dot(r_wf - across * n);
  }
};

template <int D> class WallModel {
 public:
  // bodies: the case's moving bodies and free-slip walls (Discretisation::bodies, which outlives the model).
  explicit WallModel(const MovingBodies<D>& bodies) : bodies_(&bodies) {}
  virtual ~WallModel() = default;
  // The model's name, as -wall_pressure chooses it and summary.json's "models" reports it.
  virtual std::string name() const = 0;

  // Explicit schemes: the pressure of the owned walls and inlets (P.p) continued from the fluid's,
  // each wall of a moving body with g - a_w in place of g.
  virtual void extrapolate_pressure(Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                    const Vector<D>& body_force) const = 0;
  // Implicit schemes: the relation the pressure equation's wall rows hold, the fluid's own gradient
  // (where the model uses it) taken from `pressure` (owned and ghost values).
  virtual WallContinuation<D> continuation(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                           const std::vector<double>& pressure) const = 0;
  // The velocity field the viscous term reads: `field` on the fluid, the walls' condition (no-slip
  // mirror, free slip) on them; owned and ghost values.
  virtual std::vector<Vector<D>> viscous_velocity(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                                  const std::vector<Vector<D>>& field) const = 0;
  // The same for one owned wall particle w, from the Shepard averages of its fluid neighbours'
  // velocity u_f and of x_w - x_f: what the force on a wall group reads (src/sph/wall_forces.hpp).
  virtual Vector<D> wall_velocity(const Particles<D>& P, std::size_t w, const Vector<D>& u_f,
                                  const Vector<D>& r) const = 0;
  // Unit normals into the fluid of the owned walls with fluid in reach (zero elsewhere).
  virtual std::vector<Vector<D>> normals(const Particles<D>& P, const Neighbourhood<D>& nh,
                                         const Kernel<D>& K) const = 0;

  // The walls' motion, whatever the model: a wall particle of a moving body (prescribed or free) moves
  // with it, the other walls keep their place (a sliding lid's velocity is along it).
  // Whether some wall moves.
  bool moving() const { return bodies_->any(); }
  // The velocity of wall particle i (owned or ghost) that the continuity equation and the pressure
  // source see: a moving body's (P.v), zero on walls that keep their place.
  Vector<D> continuity_velocity(const Particles<D>& P, std::size_t i) const {
    return bodies_->moves(P, i) ? Vector<D>(P.v[i]) : Vector<D>::Zero();
  }
  // The same for every particle, owned and ghost (zero on the fluid); P.v's ghosts must be fresh.
  std::vector<Vector<D>> continuity_velocities(const Particles<D>& P) const {
    return bodies_->wall_velocities(P, Vector<D>::Zero());
  }
  // The acceleration of wall particle i (owned or ghost): a moving body's at its place, else zero.
  Vector<D> acceleration(const Particles<D>& P, std::size_t i) const {
    return bodies_->point_acceleration(P, i, P.x[i]);
  }
  // The owned walls' accelerations (empty when no wall moves).
  std::vector<Vector<D>> accelerations(const Particles<D>& P) const {
    return bodies_->accelerations(P, bodies_->time());
  }

 protected:
  const MovingBodies<D>& bodies() const { return *bodies_; }

 private:
  const MovingBodies<D>* bodies_;
};

// True when any rank holds wall particles.
template <int D> bool has_walls(const Particles<D>& P) {
  int any = 0;
  for (std::size_t i = 0; i < P.n_owned && !any; ++i) any = P.kind[i] == kWall;
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return any != 0;
}

}  // namespace sph
