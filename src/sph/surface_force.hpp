#pragma once
// The pressure force on a body from its surface, F = -sum_q p(x_q) a_q n_q over the faces q of a closed
// surface (a_q n_q: the face's area times its outward normal, x_q its centre), and its moment, with
// p(x_q) fitted to the fluid particles by linear moving least squares (src/sph/interpolation.hpp).
// Since sum_q a_q n_q = 0 on a closed surface, a uniform pressure gives no force whatever the particles'
// arrangement, and a linear one gives exactly the weight of the water the surface encloses: the pair
// sums of wall_forces.hpp respond to the pressure's level beside disordered particles
// (docs/verification/body_forces.md).
#include <Eigen/Dense>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"
#include "src/sph/interpolation.hpp"
#include "src/sph/wall_forces.hpp"

namespace sph {

template <int D> struct SurfaceForce {
  Vector<D> force = Vector<D>::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // about the given point (the z component in 2D)
};

// p: the fluid particles' pressure (owned values; every rank gets the whole sum). Faces with no fluid
// particle within the kernel's reach (dry, or wetted by air above a free surface) carry no pressure.
template <int D> SurfaceForce<D> surface_pressure_force(const Particles<D>& P, const Kernel<D>& K,
                                                        const std::vector<Vector<D>>& centre,
                                                        const std::vector<Vector<D>>& area_normal,
                                                        const std::vector<double>& p, const Vector<D>& about) {
  const std::vector<double> pq = probe_fluid(P, K, centre, ProbeInterpolation::Linear, p);
  SurfaceForce<D> out;
  for (std::size_t q = 0; q < centre.size(); ++q) {
    const Vector<D> f = -pq[q] * area_normal[q];
    out.force += f, out.moment += moment_of<D>(Vector<D>(centre[q] - about), f);
  }
  return out;
}

}  // namespace sph
