#pragma once
// The pressure force on a body from its surface, F = -sum_q p(x_q) a_q n_q over the faces q of a closed
// surface (a_q n_q: the face's area times its outward normal, x_q its centre), and its moment, with
// p(x_q) fitted to the fluid particles by linear moving least squares (src/sph/interpolation.hpp).
// Since sum_q a_q n_q = 0 on a closed surface, a uniform pressure gives no force whatever the particles'
// arrangement, and a linear one gives exactly the weight of the water the surface encloses: the pair
// sums of wall_forces.hpp respond to the pressure's level beside disordered particles
// (docs/verification/body_forces.md).
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>
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
// The faces are gathered in cubes of side h, one fit a cube at its faces' area-weighted centre, and
// each face takes that fit's linear function at its own centre (exact for a linear pressure as the
// fit is): a contour drawn at a quarter spacing has some 16 faces a cube in 3D, each of which would
// otherwise cost a fit of its own.
template <int D> SurfaceForce<D> surface_pressure_force(const Particles<D>& P, const Kernel<D>& K,
                                                        const std::vector<Vector<D>>& centre,
                                                        const std::vector<Vector<D>>& area_normal,
                                                        const std::vector<double>& p, const Vector<D>& about) {
  const double h = K.h();
  std::map<std::array<long, D>, std::size_t> bin_of_cube;
  std::vector<std::size_t> bin(centre.size());
  std::vector<Vector<D>> fit_at;  // per bin: sum of |a| x, then the centre
  std::vector<double> weight;
  for (std::size_t q = 0; q < centre.size(); ++q) {
    std::array<long, D> cube;
    for (int a = 0; a < D; ++a) cube[a] = static_cast<long>(std::floor(centre[q][a] / h));
    const auto [it, added] = bin_of_cube.emplace(cube, fit_at.size());
    if (added) fit_at.push_back(Vector<D>::Zero()), weight.push_back(0.0);
    bin[q] = it->second;
    const double w = area_normal[q].norm();
    fit_at[bin[q]] += w * centre[q], weight[bin[q]] += w;
  }
  for (std::size_t b = 0; b < fit_at.size(); ++b)
    if (weight[b] > 0.0) fit_at[b] /= weight[b];
  std::vector<Vector<D>> slope;
  const std::vector<double> value = probe_fluid(P, K, fit_at, ProbeInterpolation::Linear, p, &slope);
  SurfaceForce<D> out;
  for (std::size_t q = 0; q < centre.size(); ++q) {
    const std::size_t b = bin[q];
    const double pq = value[b] + slope[b].dot(centre[q] - fit_at[b]);
    const Vector<D> f = -pq * area_normal[q];
    out.force += f, out.moment += moment_of<D>(Vector<D>(centre[q] - about), f);
  }
  return out;
}

}  // namespace sph
