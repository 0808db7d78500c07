#pragma once
// The kernel (Shepard) average of a per-particle field, sum_j V_j W_ij f_j / sum_j V_j W_ij (i
// included): the field's resolved-scale part, so that f - average is the part that varies on the
// particle scale. Three schemes separate scales with it: particle-scale shifting (src/sph/shifting.hpp),
// ISPH's PPE source under -ppe_particle_divergence_rate (solvers/isph/isph_solver.cpp) and WCSPH's
// particle-scale density diffusion (-density_diffusion particle, solvers/wcsph/wcsph_solver.hpp).
#include <vector>

#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

template <class T> struct KernelAverage {
  std::vector<T> average;      // per owned particle; f_i itself where not interior
  std::vector<char> interior;  // 1: the kernel support holds fluid particles only
};

// Averages only where the support is all fluid: next to a wall or a free surface (a surface particle
// among the neighbours, `surface` the owned particles' flags, may be null) the support is cut and the
// resolved part of a field is the boundary's own signal, so there the average is f_i and f - average
// vanishes. With `average_cut_by_surface`, a support that a free surface cuts (walls or not) is
// averaged over its fluid particles all the same: where a scheme's surface particles carry the field
// (ISPH's surface nodes) keeping f_i there would leave all of its particle-scale noise in place. f holds
// the owned particles' values and grows to cover the ghosts.
template <int D, class T> KernelAverage<T> kernel_average_in_fluid(const Particles<D>& P, Neighbourhood<D>& nh,
                                                                   const Kernel<D>& K, std::vector<T>& f,
                                                                   const std::vector<char>* surface,
                                                                   bool average_cut_by_surface = false) {
  f.resize(P.size());
  nh.halo().update(f);
  std::vector<double> boundary(P.size(), 0.0);  // 1: a wall particle, 2: a free-surface particle
  for (std::size_t i = 0; i < P.n_owned; ++i)
    boundary[i] = P.kind[i] != kFluid ? 1.0 : surface && (*surface)[i] ? 2.0 : 0.0;
  nh.halo().update(boundary);
  KernelAverage<T> result{std::vector<T>(f.begin(), f.begin() + P.n_owned), std::vector<char>(P.n_owned, 0)};
  const double W0 = K.W(0.0);
  for_each_particle_pairs(P, nh.list(), K, [&](std::size_t i, auto&& visit_pairs) {
    if (boundary[i] == 1.0 || (boundary[i] == 2.0 && !average_cut_by_surface)) return;
    const double w_i = P.m[i] / P.rho[i] * W0;
    T sum = w_i * f[i];
    double weight = w_i;
    bool interior = boundary[i] == 0.0, cut_by_surface = boundary[i] == 2.0;
    visit_pairs([&](int, int j, const PairGeometry<D>& g) {
      interior = interior && boundary[j] == 0.0;
      cut_by_surface = cut_by_surface || boundary[j] == 2.0;
      if (boundary[j] == 1.0) return;  // walls carry no fluid field
      const double w = P.m[j] / P.rho[j] * g.W;
      sum += w * f[j], weight += w;
    });
    if (interior) result.average[i] = sum / weight, result.interior[i] = 1;
    else if (cut_by_surface && average_cut_by_surface) result.average[i] = sum / weight;
  });
  f.resize(P.n_owned);
  return result;
}

}  // namespace sph
