#pragma once
// Generalised wall boundary condition of Adami, Hu & Adams (2012, JCP 231:7057) for fixed layers of
// dummy wall particles (kind kWall), shared by every solver. For each wall particle w, from its fluid
// neighbours f (Shepard-weighted):
//   pressure   p_w = [sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf] / sum_f W_wf
//   velocity   u_w = 2 v_w - sum_f u_f W_wf / sum_f W_wf     (no-slip: used in the viscous term only;
//                                                               the ISPH pressure source and the WCSPH
//                                                               continuity equation see sliding walls
//                                                               at rest, moving bodies at v_w)
// (a free-slip wall particle, MovingBodies::free_slip, takes u_w = the Shepard average of u_f instead:
// no shear), where v_w is the wall's prescribed velocity (kept in Particles::v; a moving lid has
// v_w != 0) and a_w its acceleration (a moving body's, src/boundary/moving_bodies.hpp; zero for fixed walls). Wall
// particles with no fluid neighbour keep p = 0 and u_w = v_w; no fluid particle sees them.
#include <vector>

#include "src/boundary/moving_bodies.hpp"
#include "src/boundary/wall_model.hpp"
#include "src/boundary/wall_pressure.hpp"
#include "src/core/physics.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

template <int D> struct AdamiWall {
  // Shepard weights of wall particle w: the fluid neighbours f and W_wf / sum_f W_wf.
  struct Stencil {
    std::vector<std::size_t> offset{0};
    std::vector<int> fluid;
    std::vector<double> weight;
    std::vector<Vector<D>> r_wf;  // x_w - x_f
  };

  // Builds the stencils of all owned wall particles (entries for fluid particles are empty).
  static Stencil stencil(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
    Stencil s;
    s.offset.assign(P.n_owned + 1, 0);
    std::vector<double> sum(P.n_owned, 0.0);
    std::size_t current = 0;
    for_each_pair_in_order(
        P, nl, K,
        [&](int w, int f, const PairGeometry<D>& g) {
          // A neighbour at the edge of the support can weigh exactly 0 (r / h rounds to the support): it
          // adds nothing, and a wall whose only fluid neighbours were such would divide 0 by 0
          // (docs/verification/dam_break.md, "Design measurements").
          if (P.kind[f] != kFluid || g.W == 0.0) return;
          while (current < static_cast<std::size_t>(w)) s.offset[++current] = s.fluid.size();
          s.fluid.push_back(f);
          s.weight.push_back(g.W);
          s.r_wf.push_back(g.rij);
          sum[w] += g.W;
        },
        Rows::Walls);
    while (current < P.n_owned) s.offset[++current] = s.fluid.size();
    for (std::size_t w = 0; w < P.n_owned; ++w)
      for (std::size_t k = s.offset[w]; k < s.offset[w + 1]; ++k) s.weight[k] /= sum[w];
    return s;
  }

  // The walls' unit normals, into the fluid, from the walls alone: -grad of the walls' own kernel sum,
  // sum over wall neighbours j of V_j grad_w W_wj (volume(j) = V_j), which points into the wall body on
  // its first layers (the layers that fluid particles reach). Zero where that sum vanishes (the middle
  // of a thin wall) and on fluid particles. Owned particles.
  template <class Volume> static std::vector<Vector<D>> face_normals(const Particles<D>& P, const NeighbourList<D>& nl,
                                                                     const Kernel<D>& K, Volume&& volume) {
    std::vector<Vector<D>> n = sum_over_pairs(
        P, nl, K, Vector<D>(Vector<D>::Zero()),
        [&](Vector<D>& sum, int, int j, const PairGeometry<D>& pg) {
          if (P.kind[j] == kWall) sum += volume(j) * pg.gradW;
        },
        Rows::Walls);
    const double scale = 1e-3 / K.h();  // |grad| of an exposed wall face is O(1/h)
    for (Vector<D>& g : n) g = g.norm() > scale ? Vector<D>(-g.normalized()) : Vector<D>(Vector<D>::Zero());
    return n;
  }

  // The walls' unit normals into the fluid, for owned wall particles with fluid in reach (zero
  // elsewhere): the face normals; where they vanish (the middle of a thin wall, or of a wall cut to the
  // layers the kernel needs) the normal lines of the wall neighbours, sum_j W_wj n_j (n_j . t), each
  // turned towards this particle's fluid t (the direction to the Shepard centroid of its fluid), and
  // t itself where no neighbour has a face. Without the neighbours' lines a deep layer beside a lone
  // particle took the direction to that particle as the wall's normal.
  static std::vector<Vector<D>> normals(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                        const Stencil& s) {
    std::vector<Vector<D>> face = face_normals(P, nh.list(), K, [&](int j) { return P.m[j] / P.rho[j]; });
    nh.halo().update(face);
    std::vector<Vector<D>> towards(P.n_owned, Vector<D>::Zero());
    for (std::size_t w = 0; w < P.n_owned; ++w)
      for (std::size_t k = s.offset[w]; k < s.offset[w + 1]; ++k) towards[w] -= s.weight[k] * s.r_wf[k];
    const std::vector<Vector<D>> borrowed = sum_over_pairs(
        P, nh.list(), K, Vector<D>(Vector<D>::Zero()),
        [&](Vector<D>& sum, int w, int j, const PairGeometry<D>& pg) {
          if (P.kind[j] == kWall && face[w].squaredNorm() == 0.0) sum += pg.W * face[j] * face[j].dot(towards[w]);
        },
        Rows::Walls);
    std::vector<Vector<D>> n(P.n_owned, Vector<D>::Zero());
    for (std::size_t w = 0; w < P.n_owned; ++w) {
      if (P.kind[w] != kWall || s.offset[w] == s.offset[w + 1]) continue;
      const Vector<D>& choice = face[w].squaredNorm() > 0.0 ? face[w]
                                : borrowed[w].norm() > 0.0  ? borrowed[w]
                                                            : towards[w];
      if (choice.norm() > 0.0) n[w] = choice.normalized();
    }
    return n;
  }

  // How a wall particle continues the fluid's pressure to its own place: from each fluid neighbour f,
  // p_f + grad p . r_wf. Across the wall the momentum balance gives grad p . n = rho (g - a_w) . n,
  // since the fluid's normal acceleration is the wall's; along the wall the fluid accelerates on its
  // own, so the change there is the fluid's own pressure gradient, not rho g . t as in Adami et al.
  // (2012), who take the fluid to accelerate with the wall along it too. A lone particle on a side wall
  // then feels no hydrostatic column that is not there; the price is the fluid's own pressure error,
  // carried into the walls (-wall_pressure continued; docs/verification/free_surface.md, "Walls that
  // continue the fluid's own pressure"). Empty: Adami's relation as published.
  using Continuation = WallContinuation<D>;

  // The fluid's own pressure gradient (of `pressure`, owned and ghost values) at every fluid particle
  // with a wall in reach, from its fluid neighbours alone: B^-1 sum_j V_j (p_j - p_i) grad W_ij with
  // B = sum_j V_j grad W_ij (x_j - x_i)^T, exact for a linear field. B^-1 is taken as
  // B^T (B B^T + eps^2)^-1, so what the neighbours cannot resolve (all of it for a lone particle, the
  // normal of a row) is zero, continuously. Zero elsewhere; owned and ghost particles.
  static std::vector<Vector<D>> fluid_pressure_gradient(const Particles<D>& P, const Neighbourhood<D>& nh,
                                                        const Kernel<D>& K, const std::vector<double>& pressure) {
    struct Sums {
      Tensor<D> B = Tensor<D>::Zero();
      Vector<D> b = Vector<D>::Zero();
      bool wall = false;
    };
    const std::vector<Sums> sums = sum_over_pairs(
        P, nh.list(), K, Sums(),
        [&](Sums& s, int i, int j, const PairGeometry<D>& pg) {
          if (P.kind[j] != kFluid) {
            s.wall |= P.kind[j] == kWall;
            return;
          }
          const double V = P.m[j] / P.rho[j];
          s.B -= V * pg.gradW * pg.rij.transpose();
          s.b += V * (pressure[j] - pressure[i]) * pg.gradW;
        },
        Rows::Fluid);
    constexpr double eps2 = 1e-6;  // against B ~ I in the bulk, I / 2 at a surface
    std::vector<Vector<D>> G(P.n_owned, Vector<D>::Zero());
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (sums[i].wall) {
        const Tensor<D>& B = sums[i].B;
        G[i] = B.transpose() * (B * B.transpose() + eps2 * Tensor<D>::Identity()).inverse() * sums[i].b;
      }
    nh.halo().update(G);
    return G;
  }

  // The continuation of the walls of P, the fluid's gradient taken from `pressure`.
  static Continuation continuation(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                   const std::vector<double>& pressure, const Stencil& s) {
    return {normals(P, nh, K, s), fluid_pressure_gradient(P, nh, K, pressure)};
  }
  static Continuation continuation(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                   const std::vector<double>& pressure) {
    return continuation(P, nh, K, pressure, stencil(P, nh.list(), K));
  }

  // Wall pressure from the fluid (for explicit schemes; ISPH puts the same relation into its matrix),
  // and an inlet buffer's (src/boundary/open_boundaries.hpp).
  // acceleration: per owned particle, the walls' own a_w (moving bodies); null: every wall at rest.
  static void extrapolate_pressure(const Stencil& s, const Continuation& c, Particles<D>& P,
                                   const Vector<D>& body_force, const std::vector<Vector<D>>* acceleration = nullptr) {
    for (std::size_t w = 0; w < P.n_owned; ++w) {
      if (!extrapolates_pressure(P.kind[w])) continue;
      const Vector<D> g =
          acceleration && !acceleration->empty() ? Vector<D>(body_force - (*acceleration)[w]) : body_force;
      double p = 0.0;
      for (std::size_t k = s.offset[w]; k < s.offset[w + 1]; ++k) {
        const int f = s.fluid[k];
        p += s.weight[k] * (P.p[f] + c.head(w, static_cast<std::size_t>(f), g, s.r_wf[k], P.rho[f]));
      }
      P.p[w] = p;
    }
  }

  // The same from the neighbourhood alone (-wall_pressure continued: the fluid's gradient from its
  // current pressure).
  static void extrapolate_pressure(Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                   const Vector<D>& body_force, const std::vector<Vector<D>>* acceleration = nullptr,
                                   WallPressure model = WallPressure::Adami) {
    const Stencil s = stencil(P, nh.list(), K);
    const Continuation c = model == WallPressure::Continued ? continuation(P, nh, K, P.p, s) : Continuation();
    extrapolate_pressure(s, c, P, body_force, acceleration);
  }

  // Velocity seen by the viscous term: the fluid's own, and the no-slip mirror on walls, for the
  // velocity field v (P.v by default; walls keep their prescribed P.v). A turning body's mirror takes
  // its velocity where the wall meets the fluid (mirror_velocity), not at the particle inside it.
  static std::vector<Vector<D>> viscous_velocity(const Stencil& s, const Particles<D>& P,
                                                 const std::vector<Vector<D>>* field = nullptr,
                                                 const MovingBodies<D>* bodies = nullptr) {
    const std::vector<Vector<D>>& v = field ? *field : P.v;
    std::vector<Vector<D>> u(v.begin(), v.begin() + P.n_owned);
    for (std::size_t w = 0; w < P.n_owned; ++w) {
      if (P.kind[w] != kWall || s.offset[w] == s.offset[w + 1]) continue;
      Vector<D> avg = Vector<D>::Zero(), r = Vector<D>::Zero();
      for (std::size_t k = s.offset[w]; k < s.offset[w + 1]; ++k)
        avg += s.weight[k] * v[s.fluid[k]], r += s.weight[k] * s.r_wf[k];
      u[w] = mirror_velocity(P, w, avg, r, bodies);
    }
    return u;
  }

  // The same over the neighbourhood's pairs, with the ghosts' values: what a pair loop reads.
  static std::vector<Vector<D>> viscous_velocity(const Neighbourhood<D>& nh, const Kernel<D>& K, const Particles<D>& P,
                                                 const std::vector<Vector<D>>* field, const MovingBodies<D>* bodies) {
    std::vector<Vector<D>> u = viscous_velocity(stencil(P, nh.list(), K), P, field, bodies);
    nh.halo().update(u);
    return u;
  }

  // Adami's mirror 2 v_w - u_f of wall particle w, u_f the Shepard average of the fluid's velocity and
  // r the same average of x_w - x_f; u_f itself on a free-slip wall. A rigid rotation's velocity changes
  // across the wall: taken at the particle, w x r_w, it would put the no-slip point inside the body, and a
  // turning cylinder dragged half the torque along (docs/verification/body_forces.md); it is taken
  // halfway to the fluid instead.
  static Vector<D> mirror_velocity(const Particles<D>& P, std::size_t w, const Vector<D>& u_f, const Vector<D>& r,
                                   const MovingBodies<D>* bodies) {
    if (bodies && bodies->free_slip(P, w)) return u_f;
    if (!bodies) return 2.0 * P.v[w] - u_f;
    const PrescribedMotion<D>* m = bodies->motion_of(P, w);
    if (bodies->free_of(P, w) || (m && m->spin != PrescribedMotion<D>::Type::Fixed))
      return 2.0 * bodies->point_velocity(P, w, Vector<D>(P.x[w] - 0.5 * r)) - u_f;
    return 2.0 * P.v[w] - u_f;
  }
};

}  // namespace sph
