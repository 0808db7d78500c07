#pragma once
// The force the fluid exerts on groups of wall particles (a body, or the walls), split into its
// pressure and viscous parts, and its moment: the counterpart, by Newton's third law, of the
// momentum-conserving pair forces the fluid feels from those walls,
//   pressure  F_w = -m_w sum_f m_f (p_f / rho_f^2 + p_w / rho_w^2) grad_w W_wf
//   viscous   F_w =  m_w sum_f m_f (mu_w + mu_f) / (rho_w rho_f) F_wf (u~_w - u_f)   (Morris et al. 1997)
// with the wall's pressure as its scheme left it (Adami et al. 2012's extrapolation) and u~_w its
// no-slip mirror velocity. For WCSPH's symmetric pressure gradient and Morris viscosity these are the
// scheme's own pair forces; for ISPH's corrected operators the same sums are the SPH form of the
// surface integral of the stress, consistent to the same order (docs/verification/body_forces.md).
#include <mpi.h>
#include <petscsys.h>

#include <Eigen/Dense>
#include <vector>

#include "src/boundary/wall_model.hpp"
#include "src/sph/pair_loop.hpp"
#include "src/sph/pair_terms.hpp"

namespace sph {

// One group's force and its moment about the group's reference point (the z component in 2D), each
// pair's force acting at the pair's midpoint.
template <int D> struct GroupForce {
  Vector<D> pressure = Vector<D>::Zero(), viscous = Vector<D>::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();           // of both parts
  Eigen::Vector3d pressure_moment = Eigen::Vector3d::Zero();  // of the pressure part alone
  Vector<D> total() const { return pressure + viscous; }
};

// r x F, with 2D vectors in the z = 0 plane.
template <int D> Eigen::Vector3d moment_of(const Vector<D>& r, const Vector<D>& f) {
  Eigen::Vector3d r3 = Eigen::Vector3d::Zero(), f3 = Eigen::Vector3d::Zero();
  r3.head<D>() = r, f3.head<D>() = f;
  return r3.cross(f3);
}

// One owned wall particle's viscous force, where it acts (its pairs' midpoints, weighted as the
// force is) and the direction of the fluid that exerts it (the kernel-weighted mean of the directions
// to its fluid neighbours): for spreading it onto a body's surface (surface_shear.hpp).
template <int D> struct WallParticleShear {
  int group = -1;
  Vector<D> force = Vector<D>::Zero(), at = Vector<D>::Zero(), towards_fluid = Vector<D>::Zero();
};

// Forces on groups 0..n_groups-1 of owned wall particles (group[i] < 0: in none), reduced over all
// ranks. p, rho: the pressure and density with current ghost values; nu: the kinematic viscosity (0: no
// viscous part); about[g]: group g's moment reference point. shear (if given): each owned wall
// particle's viscous force in a group, on this rank.
template <int D>
std::vector<GroupForce<D>> wall_group_forces(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                             const std::vector<double>& p, const std::vector<double>& rho,
                                             const std::vector<int>& group, double nu,
                                             const std::vector<Vector<D>>& about, const WallModel<D>* walls = nullptr,
                                             std::vector<WallParticleShear<D>>* shear = nullptr) {
  const std::size_t n_groups = about.size();
  check_ghosts(nl, p, "the wall forces' pressure");
  check_ghosts(nl, rho, "the wall forces' density");
  // Per wall particle, in one pass over its fluid pairs: the pressure force, the viscous sums, with the
  // Shepard averages that the wall's velocity needs (WallModel::viscous_velocity's, without gathering a
  // stencil), and the moments. Each pair's force acts halfway between its two particles, where the
  // wall meets the fluid: taken at the wall particle, the lever arm of a turning cylinder's viscous
  // torque was short by the depth of its layers (docs/verification/body_forces.md).
  struct Sums {
    Vector<D> pressure = Vector<D>::Zero(), viscous_u = Vector<D>::Zero(), shepard_u = Vector<D>::Zero(),
              shepard_r = Vector<D>::Zero(), viscous_arm = Vector<D>::Zero();
    Eigen::Vector3d pressure_moment = Eigen::Vector3d::Zero(), viscous_moment_u = Eigen::Vector3d::Zero();
    double viscous_weight = 0.0, shepard_weight = 0.0;
  };
  const double h = K.h();
  const std::vector<Sums> sums = sum_over_pairs(
      P, nl, K, Sums{},
      [&](Sums& s, int w, int f, const PairGeometry<D>& g) {
        if (P.kind[f] != kFluid || group[w] < 0) return;
        const Vector<D> arm = P.x[w] - 0.5 * g.rij - about[static_cast<std::size_t>(group[w])];
        const Vector<D> pressure = (-P.m[w] * P.m[f] * (p[f] / (rho[f] * rho[f]) + p[w] / (rho[w] * rho[w]))) * g.gradW;
        s.pressure += pressure, s.pressure_moment += moment_of<D>(arm, pressure);
        if (nu > 0.0) {
          const double k = P.m[f] * (rho[w] * nu + rho[f] * nu) / (rho[w] * rho[f]) * morris_factor(g, h);
          s.viscous_u += k * P.v[f], s.viscous_weight += k;
          s.viscous_arm += k * arm, s.viscous_moment_u += k * moment_of<D>(arm, Vector<D>(P.v[f]));
          s.shepard_u += g.W * P.v[f], s.shepard_r += g.W * g.rij, s.shepard_weight += g.W;
        }
      },
      Rows::Walls);
  std::vector<GroupForce<D>> out(n_groups);
  for (std::size_t w = 0; w < P.n_owned; ++w) {
    if (P.kind[w] != kWall || group[w] < 0) continue;
    const Sums& s = sums[w];
    GroupForce<D>& F = out[static_cast<std::size_t>(group[w])];
    F.pressure += s.pressure, F.moment += s.pressure_moment, F.pressure_moment += s.pressure_moment;
    if (s.shepard_weight > 0.0) {
      // The wall's velocity as the viscous term sees it (the scheme's wall model; without one, Adami's mirror).
      const Vector<D> u_f = s.shepard_u / s.shepard_weight, r = s.shepard_r / s.shepard_weight;
      const Vector<D> mirror = walls ? walls->wall_velocity(P, w, u_f, r) : Vector<D>(2.0 * P.v[w] - u_f);
      // sum_f m_w k_f (mirror - u_f), and its moment about the pairs' midpoints.
      const Vector<D> viscous = P.m[w] * (s.viscous_weight * mirror - s.viscous_u);
      F.viscous += viscous;
      F.moment += P.m[w] * (moment_of<D>(s.viscous_arm, mirror) - s.viscous_moment_u);
      if (shear && s.viscous_weight != 0.0)
        shear->push_back({group[w], viscous,
                          Vector<D>(about[static_cast<std::size_t>(group[w])] + s.viscous_arm / s.viscous_weight),
                          Vector<D>(-s.shepard_r / s.shepard_weight)});
    }
  }
  std::vector<double> flat;
  for (const GroupForce<D>& F : out) {
    flat.insert(flat.end(), F.pressure.data(), F.pressure.data() + D);
    flat.insert(flat.end(), F.viscous.data(), F.viscous.data() + D);
    flat.insert(flat.end(), F.moment.data(), F.moment.data() + 3);
    flat.insert(flat.end(), F.pressure_moment.data(), F.pressure_moment.data() + 3);
  }
  MPI_Allreduce(MPI_IN_PLACE, flat.data(), static_cast<int>(flat.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double* v = flat.data();
  for (GroupForce<D>& F : out) {
    for (int a = 0; a < D; ++a) F.pressure[a] = *v++;
    for (int a = 0; a < D; ++a) F.viscous[a] = *v++;
    for (int a = 0; a < 3; ++a) F.moment[a] = *v++;
    for (int a = 0; a < 3; ++a) F.pressure_moment[a] = *v++;
  }
  return out;
}

}  // namespace sph
