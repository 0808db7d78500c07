#pragma once
// Free-surface particles: the divergence of position, div r_i = -(1/rho_i) sum_j m_j r_ij . grad_i W_ij,
// equals the dimension D inside the fluid and drops where the support is cut by the surface
// (Lee et al. 2008; Lind et al. 2012 use div r < 1.5 in 2D). Only fluid particles are flagged.
// Wall particles count as neighbours (a fluid particle on a wall is not on the surface), so a fluid
// particle with no fluid neighbour at all (a droplet stuck in a wall corner) is flagged explicitly:
// otherwise it and its wall particles would form a pressure island with no level, a singular block.
//
// Hysteresis: a particle flagged at the last step stays flagged until div r rises past a higher exit
// threshold. With a single threshold a particle whose div r hovers at it switches between p = 0 and
// an interior row from step to step; each switch is a pressure impulse, so that noise came per step,
// not per unit time (dam break nx 40: 3.5x the switches per unit time at half the step), and ISPH
// blew up at small dt where shifting, a rate, removed less disorder per step than the switching made.
#include <vector>

#include "src/sph/pair_loop.hpp"

namespace sph {

template <int D> double default_free_surface_threshold() { return D == 1 ? 0.75 : D == 2 ? 1.5 : 2.4; }
// Exit threshold: 40 % of the way from the entry threshold to the interior value D (1.7 in 2D).
template <int D> double default_free_surface_exit_threshold(double threshold) { return threshold + 0.4 * (D - threshold); }

template <int D>
std::vector<double> position_divergence(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
  std::vector<double> div(P.n_owned, 0.0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) { div[i] -= P.m[j] * g.rij.dot(g.gradW); });
  for (std::size_t i = 0; i < P.n_owned; ++i) div[i] /= P.rho[i];
  return div;
}

// 1 for fluid particles on the free surface, 0 otherwise (one entry per owned particle). With
// `previous` (the last step's flags, nonzero = on the surface), a flagged particle stays flagged while
// div r < exit_threshold.
template <int D>
std::vector<char> free_surface_particles(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                         double threshold, double exit_threshold = 0.0,
                                         const std::vector<double>* previous = nullptr) {
  const std::vector<double> div = position_divergence(P, nl, K);
  std::vector<char> has_fluid(P.n_owned, 0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>&) { has_fluid[i] |= P.kind[j] == kFluid; });
  std::vector<char> surface(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const bool stays = previous && (*previous)[i] != 0.0 && div[i] < exit_threshold;
    surface[i] = P.kind[i] == kFluid && (div[i] < threshold || stays || !has_fluid[i]);
  }
  return surface;
}

// 1 for owned particles with a free-surface particle among their neighbours (or on it); `surface`
// holds owned and ghost values.
template <int D>
std::vector<char> near_free_surface(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                    const std::vector<double>& surface) {
  std::vector<char> near(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i) near[i] = surface[i] != 0.0;
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>&) { near[i] |= surface[j] != 0.0; });
  return near;
}

}  // namespace sph
