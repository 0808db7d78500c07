#pragma once
// The viscous traction on each face of a body's surface, for the surface files: the wall particles'
// viscous pair forces (wall_forces.hpp) spread onto the faces near where they act, so that the faces'
// shear integrates to the force_<body>_viscous columns exactly, plus the stress's part that the pair
// sums' Laplacian form leaves out, mu (grad u)^T n = -mu w x n on the wall of a body turning at w
// (zero force, the torque -2 mu V w that WallGroups::forces adds). The pair sums rather than a fit of
// the velocity gradient at each face: they carry the scheme's own momentum balance at the wall
// (docs/verification/body_forces.md, "The shear on the faces").
#include <mpi.h>
#include <petscsys.h>

#include <Eigen/Dense>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/sph/wall_forces.hpp"

namespace sph {

// Per face (centre, area times outward unit normal), the viscous force per unit area of the given wall
// particles' forces (this rank's; every rank gets the whole sum). Each particle's force goes to the
// faces within the kernel's reach of where it acts that face its fluid (n . towards_fluid > 0: a thin
// plate's two faces take their own sides' forces), in proportion to area times W; with no such face
// in reach, to the nearest facing face, or the nearest face. So the faces' forces sum to the particles'.
template <int D> std::vector<Vector<D>> spread_shear(const std::vector<WallParticleShear<D>>& forces,
                                                     const Kernel<D>& K, const std::vector<Vector<D>>& centre,
                                                     const std::vector<Vector<D>>& area_normal) {
  const std::size_t n = centre.size();
  std::vector<double> sum(n * D, 0.0);
  std::vector<double> weight(n);
  const double reach = K.support_radius();
  for (const WallParticleShear<D>& f : forces) {
    double total = 0.0;
    long nearest = -1;
    double nearest_r = 0.0;
    bool nearest_facing = false;
    for (std::size_t q = 0; q < n; ++q) {
      const double r = (centre[q] - f.at).norm();
      const bool facing = area_normal[q].dot(f.towards_fluid) > 0.0;
      weight[q] = facing && r < reach ? area_normal[q].norm() * K.W(r) : 0.0;
      total += weight[q];
      if (nearest < 0 || (facing && !nearest_facing) || (facing == nearest_facing && r < nearest_r))
        nearest = static_cast<long>(q), nearest_r = r, nearest_facing = facing;
    }
    if (!(total > 0.0)) {
      if (nearest < 0) continue;
      for (std::size_t q = 0; q < n; ++q) weight[q] = 0.0;
      weight[static_cast<std::size_t>(nearest)] = total = 1.0;
    }
    for (std::size_t q = 0; q < n; ++q)
      if (weight[q] > 0.0)
        for (int a = 0; a < D; ++a) sum[q * D + a] += weight[q] / total * f.force[a];
  }
  MPI_Allreduce(MPI_IN_PLACE, sum.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<Vector<D>> traction(n, Vector<D>::Zero());
  for (std::size_t q = 0; q < n; ++q) {
    const double area = area_normal[q].norm();
    if (area > 0.0)
      for (int a = 0; a < D; ++a) traction[q][a] = sum[q * D + a] / area;
  }
  return traction;
}

// The stress's part mu (grad u)^T n that the pair sums leave out, per face of a body turning at w
// (about z in 2D): on a no-slip wall grad u is the body's rotation there (its velocity relative to
// the wall varies only along the normal, and incompressibility leaves no normal stretch), so the part
// is -mu w x n. It exerts no force on a closed surface and the torque -2 mu V w.
template <int D> void add_rotation_shear(std::vector<Vector<D>>& traction, const std::vector<Vector<D>>& area_normal,
                                         const Eigen::Vector3d& w, double mu) {
  for (std::size_t q = 0; q < traction.size(); ++q) {
    const double area = area_normal[q].norm();
    if (!(area > 0.0)) continue;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n.head<D>() = area_normal[q] / area;
    traction[q] -= mu * Vector<D>(w.cross(n).template head<D>());
  }
}

}  // namespace sph
