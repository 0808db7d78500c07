#pragma once
// Free-surface particles: the divergence of position, div r_i = -(1/rho_i) sum_j m_j r_ij . grad_i W_ij,
// equals the dimension D inside the fluid and drops where the support is cut by the surface
// (Lee et al. 2008; Lind et al. 2012 use div r < 1.5 in 2D). Only fluid particles are flagged.
// Wall particles count as neighbours (a fluid particle on a wall is not on the surface), so a fluid
// particle with no fluid neighbour at all (a droplet stuck in a wall corner) is flagged explicitly:
// otherwise it and its wall particles would form a pressure island with no level, a singular block.
#include <vector>

#include "src/sph/pair_loop.hpp"

namespace sph {

template <int D> double default_free_surface_threshold() { return D == 1 ? 0.75 : D == 2 ? 1.5 : 2.4; }

template <int D>
std::vector<double> position_divergence(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
  std::vector<double> div(P.n_owned, 0.0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) { div[i] -= P.m[j] * g.rij.dot(g.gradW); });
  for (std::size_t i = 0; i < P.n_owned; ++i) div[i] /= P.rho[i];
  return div;
}

// 1 for fluid particles on the free surface, 0 otherwise (one entry per owned particle).
template <int D>
std::vector<char> free_surface_particles(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                         double threshold) {
  const std::vector<double> div = position_divergence(P, nl, K);
  std::vector<char> has_fluid(P.n_owned, 0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>&) { has_fluid[i] |= P.kind[j] == kFluid; });
  std::vector<char> surface(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    surface[i] = P.kind[i] == kFluid && (div[i] < threshold || !has_fluid[i]);
  return surface;
}

}  // namespace sph
