#pragma once
// The pressure force on a body from its surface, F = -sum_q p(x_q) a_q n_q over the faces q of a closed
// surface (a_q n_q: the face's area times its outward normal, x_q its centre), and its moment, with
// p(x_q) fitted to the fluid particles by linear moving least squares (src/sph/interpolation.hpp).
// Since sum_q a_q n_q = 0 on a closed surface, a uniform pressure gives no force whatever the particles'
// arrangement, and a linear one gives exactly the weight of the water the surface encloses: the pair
// sums of wall_forces.hpp respond to the pressure's level beside disordered particles
// (docs/verification/body_forces.md).
#include <mpi.h>
#include <petscsys.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/neighbours/screens.hpp"
#include "src/particles/particles.hpp"
#include "src/sph/interpolation.hpp"
#include "src/sph/wall_forces.hpp"

namespace sph {

template <int D> struct SurfaceForce {
  Vector<D> force = Vector<D>::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // about the given point (the z component in 2D)
  std::vector<double> face_pressure;                 // per face, the pressure its force was taken with
};

// p: the fluid particles' pressure (owned values; every rank gets the whole sum). Faces with no fluid
// particle within the kernel's reach (dry, or wetted by air above a free surface) carry no pressure.
// The faces are gathered in cubes of side h, one fit a cube at its faces' area-weighted centre, and
// each face takes that fit's linear function at its own centre (exact for a linear pressure as the
// fit is): a contour drawn at a quarter spacing has some 16 faces a cube in 3D, each of which would
// otherwise cost a fit of its own. With thin plates (screens), a fit takes only the fluid seen from
// just outside its faces, and faces that look at different sides of a plate are fitted apart: a
// plate's two faces hold the pressures of their own sides. With a free surface (p = 0 there, air
// beyond) a face holds no tension: a fit reaches 2h beyond the water, and its linear extrapolation
// there, negative, would count air as suction, face by face as the faces come within reach.
template <int D>
SurfaceForce<D> surface_pressure_force(const Particles<D>& P, const Kernel<D>& K, const std::vector<Vector<D>>& centre,
                                       const std::vector<Vector<D>>& area_normal, const std::vector<double>& p,
                                       const Vector<D>& about, const Screens<D>* screens = nullptr,
                                       bool free_surface = false) {
  const double h = K.h();
  const bool screened = screens && screens->any();
  const double off = 1e-6 * h;  // how far outside its face a fit looks from
  auto outside = [&](const Vector<D>& x, const Vector<D>& n) {
    const double norm = n.norm();
    return norm > 0.0 ? Vector<D>(x + (off / norm) * n) : x;
  };
  std::map<std::pair<std::array<long, D>, std::vector<int>>, std::size_t> bin_of_cube;
  std::vector<std::size_t> bin(centre.size());
  std::vector<Vector<D>> fit_at, outward;  // per bin: sum of |a| x, then the centre; sum of a n
  std::vector<double> weight;
  for (std::size_t q = 0; q < centre.size(); ++q) {
    std::array<long, D> cube;
    for (int a = 0; a < D; ++a) cube[a] = static_cast<long>(std::floor(centre[q][a] / h));
    std::vector<int> view;
    if (screened) view = screens->view(outside(centre[q], area_normal[q]));
    const auto [it, added] = bin_of_cube.emplace(std::make_pair(cube, std::move(view)), fit_at.size());
    if (added) fit_at.push_back(Vector<D>::Zero()), outward.push_back(Vector<D>::Zero()), weight.push_back(0.0);
    bin[q] = it->second;
    const double w = area_normal[q].norm();
    fit_at[bin[q]] += w * centre[q], outward[bin[q]] += area_normal[q], weight[bin[q]] += w;
  }
  for (std::size_t b = 0; b < fit_at.size(); ++b)
    if (weight[b] > 0.0) fit_at[b] /= weight[b];
  std::vector<Vector<D>> slope;
  std::vector<double> value;
  std::vector<char> linear;
  if (screened) {
    std::vector<Vector<D>> eye(fit_at.size());
    for (std::size_t b = 0; b < fit_at.size(); ++b) eye[b] = outside(fit_at[b], outward[b]);
    const auto sees = [&](std::size_t b, int i) { return screens->see(eye[b], -1, P.x[i], P.id[i]); };
    value = probe_fluid(P, K, fit_at, ProbeInterpolation::Linear, p, &slope, sees, &linear);
  } else {
    value = probe_fluid(P, K, fit_at, ProbeInterpolation::Linear, p, &slope, detail::SeesEveryParticle{}, &linear);
  }
  // With a free surface, how wet each face is: 1 with a fluid particle within h of it (a wetted face
  // has its fluid some dx/2 off, a little more beside a curved wall), 0 with none within 3h/2 (air),
  // linear between; and a face whose fit could not be linear (one row of particles in reach) is dry.
  // So faces leave the sum continuously as the water leaves them: a face at the fits' reach flipped
  // between a linear fit and Shepard's value from one step to the next in still water.
  std::vector<double> wet(centre.size(), 1.0);
  if (free_surface) {
    std::vector<double> nearest(centre.size(), 1.5 * h);
    const detail::FluidCells<D> cells(P, centre, 1.5 * h);
    std::vector<int> near;
    for (std::size_t q = 0; q < centre.size(); ++q) {
      const Vector<D> eye = outside(centre[q], area_normal[q]);
      cells.candidates(centre[q], near);
      for (const int i : near)
        if (!screened || screens->see(eye, -1, P.x[i], P.id[i]))
          nearest[q] = std::min(nearest[q], (P.x[i] - centre[q]).norm());
    }
    MPI_Allreduce(MPI_IN_PLACE, nearest.data(), static_cast<int>(nearest.size()), MPI_DOUBLE, MPI_MIN,
                  PETSC_COMM_WORLD);
    for (std::size_t q = 0; q < centre.size(); ++q)
      wet[q] = linear[bin[q]] ? std::clamp((1.5 * h - nearest[q]) / (0.5 * h), 0.0, 1.0) : 0.0;
  }
  SurfaceForce<D> out;
  out.face_pressure.resize(centre.size());
  for (std::size_t q = 0; q < centre.size(); ++q) {
    const std::size_t b = bin[q];
    double pq = value[b] + slope[b].dot(centre[q] - fit_at[b]);
    if (free_surface) pq = wet[q] * std::max(pq, 0.0);
    out.face_pressure[q] = pq;
    const Vector<D> f = -pq * area_normal[q];
    out.force += f, out.moment += moment_of<D>(Vector<D>(centre[q] - about), f);
  }
  return out;
}

}  // namespace sph
