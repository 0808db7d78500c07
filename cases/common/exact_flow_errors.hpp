#pragma once
// Error norms of a periodic incompressible flow against an exact solution u_e(x, t), p_e(x, t) whose
// velocity decays uniformly with amplitude `amp` (Taylor-Green, Beltrami). Reduced over all ranks:
//   l1_velocity       mean |u - u_e| / amp
//   linf_velocity     max |u - u_e| / amp
//   decay_rel         |max |u| - amp| / amp        (amp: the exact max |u|)
//   amplitude_rel     a - 1, a the least-squares amplitude of u against u_e: a decay rate that is off
//   l1_velocity_shape mean |u - a u_e| / amp: a distorted flow, once the amplitude is fitted
//   l1_pressure       mean |(p - mean p) - (p_e - mean p_e)| / (rho0 amp^2 / 2)
#include <mpi.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "src/particles/particles.hpp"

namespace sph {

template <int D, class VelocityFn, class PressureFn>
std::map<std::string, double> exact_flow_errors(const Particles<D>& P, double amp, double rho0, VelocityFn&& velocity,
                                                PressureFn&& pressure) {
  // sums: |du|, count, p, p_exact, u . u_exact, |u_exact|^2 ; maxima: |du|, |u|
  double sum[6] = {0, 0, 0, 0, 0, 0}, mx[2] = {0, 0};
  std::vector<double> p_exact(P.n_owned);
  std::vector<Vector<D>> u_exact(P.n_owned);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    // A local copy of the position: the store to u_exact could alias P.x for all the compiler knows,
    // and the exact fields' shared trigonometry was then evaluated again for the pressure.
    const Vector<D> x = P.x[i];
    u_exact[i] = velocity(x);
    const double du = (P.v[i] - u_exact[i]).norm();
    p_exact[i] = pressure(x);
    sum[0] += du, sum[1] += 1.0, sum[2] += P.p[i], sum[3] += p_exact[i];
    sum[4] += P.v[i].dot(u_exact[i]), sum[5] += u_exact[i].squaredNorm();
    mx[0] = std::max(mx[0], du), mx[1] = std::max(mx[1], P.v[i].norm());
  }
  MPI_Allreduce(MPI_IN_PLACE, sum, 6, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, mx, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  const double mean_p = sum[2] / sum[1], mean_pe = sum[3] / sum[1];
  const double a = sum[5] > 0 ? sum[4] / sum[5] : 1.0;
  double local[2] = {0, 0};  // |p - p_exact| after the means, |u - a u_exact|
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    local[0] += std::abs((P.p[i] - mean_p) - (p_exact[i] - mean_pe));
    local[1] += (P.v[i] - a * u_exact[i]).norm();
  }
  MPI_Allreduce(MPI_IN_PLACE, local, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double p_scale = 0.5 * rho0 * amp * amp;
  return {{"l1_velocity", sum[0] / sum[1] / amp},         {"linf_velocity", mx[0] / amp},
          {"decay_rel", std::abs(mx[1] - amp) / amp},     {"amplitude_rel", a - 1.0},
          {"l1_velocity_shape", local[1] / sum[1] / amp}, {"l1_pressure", local[0] / sum[1] / p_scale}};
}

}  // namespace sph
