#pragma once
// Vorticity of the fluid for output (-output_fields vorticity): curl u from the Bonet & Lok corrected
// velocity gradient over fluid neighbours only, G_i = L_i sum_j V_j grad_i W_ij (u_j - u_i)^T, so it is
// exact for a linear velocity field (solid rotation, shear) up to a wall or a free surface; wall
// particles' prescribed velocities are not the fluid's velocity there and would bias it. Walls get 0.
#include <array>
#include <vector>

#include "src/sph/operators.hpp"

namespace sph {

// Components: 2D one (z), 3D three (x, y, z); one value per owned particle each.
template <int D> std::vector<std::vector<double>> fluid_vorticity(const Particles<D>& P, const NeighbourList<D>& nl,
                                                                  const Kernel<D>& K) {
  std::vector<Tensor<D>> M(P.n_owned, Tensor<D>::Zero()), G(P.n_owned, Tensor<D>::Zero());
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) {
    if (P.kind[i] != kFluid || P.kind[j] != kFluid) return;
    const double Vj = P.m[j] / P.rho[j];
    M[i] += correction_moment_term(Vj, g);
    G[i] += difference_vector_gradient_term(Vj, P.v[i], P.v[j], g);
  });
  constexpr int components = D == 3 ? 3 : 1;
  std::vector<std::vector<double>> w(components, std::vector<double>(P.n_owned, 0.0));
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;
    const Tensor<D> du = correction_from_moments(M[i]) * G[i];  // du(a, b) = d u_b / d x_a
    if constexpr (D == 2) w[0][i] = du(0, 1) - du(1, 0);
    if constexpr (D == 3) {
      w[0][i] = du(1, 2) - du(2, 1);
      w[1][i] = du(2, 0) - du(0, 2);
      w[2][i] = du(0, 1) - du(1, 0);
    }
  }
  return w;
}

}  // namespace sph
