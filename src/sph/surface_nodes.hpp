#pragma once
// Free-surface nodes: the free-surface condition p = 0 held where the surface is, not at the surface
// particles themselves.
//
// A surface particle i keeps its own continuity equation (a particle in a jet that hits a wall or
// another body of water must be stopped by its pressure, as in the bulk); its kernel support, cut by
// the surface, is completed by one virtual neighbour, the node s_i at x_i + d n_i on the outward
// normal n_i, d = dx/2 (the surface lies half a spacing beyond the outermost particles), where p = 0.
// The node's volume makes the kernel-gradient sum complete: V_s grad_i W_is = -sum_j V_j grad_i W_ij,
// so the node carries exactly the support the surface removed (zero in the bulk, where the sum
// vanishes). The corrected gradient and divergence of a surface particle see the node as one more
// neighbour (its pressure 0; its velocity the particle's own, so it adds no divergence), and so does
// its PPE row: the operators stay consistent with each other, which the projection needs.
#include <Eigen/Eigenvalues>
#include <vector>

#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

template <int D> struct SurfaceNodes {
  std::vector<Vector<D>> normal;  // outward unit normal n_i of a surface particle; zero elsewhere
  std::vector<double> volume;     // V_s; zero where i has no node
  std::vector<char> splash;       // 1: too few neighbours for a consistent operator (a sheet, a drop): p = 0
  double distance = 0.0;          // d: from a surface particle to its node
  double gradW = 0.0;             // -dW/dr at d: |grad_i W_is|

  bool empty() const { return normal.empty(); }
  bool has(std::size_t i) const { return !normal.empty() && volume[i] > 0.0; }
  bool is_splash(std::size_t i) const { return !splash.empty() && splash[i]; }
  // The node's terms of the moment matrix sum_j V_j grad_i W_ij (x_j - x_i)^T and of the gradient sum
  // sum_j V_j (f_j - f_i) grad_i W_ij for f_s = 0.
  Tensor<D> moment_term(std::size_t i) const {
    return (volume[i] * gradW * distance) * normal[i] * normal[i].transpose();
  }
  Vector<D> gradient_term(std::size_t i, double fi) const { return (-volume[i] * gradW * fi) * normal[i]; }
  // g_is = V_s |W'(d)| / d, the node's Morris weight (consistent_laplacian.hpp).
  double node_weight(std::size_t i) const { return volume[i] * gradW / distance; }
  // F_is of the Morris Laplacian (pair_terms.hpp, morris_factor) for the node.
  double morris_factor(double h) const {
    return -distance * gradW / (distance * distance + morris_eta_over_h * morris_eta_over_h * h * h);
  }
};

// The nodes of the particles flagged in `surface` (owned particles), at distance d.
template <int D> SurfaceNodes<D> surface_nodes(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                               const std::vector<char>& surface, double d) {
  const NeighbourList<D>& nl = nh.list();
  SurfaceNodes<D> nodes;
  nodes.distance = d;
  nodes.gradW = -K.dWdr(d);
  struct Sums {
    Vector<D> gradC;
    Tensor<D> M;
  };
  const std::vector<Sums> sum = sum_over_pairs(
      P, nl, K, Sums{Vector<D>::Zero(), Tensor<D>::Zero()},
      [&](Sums& s, int, int j, const PairGeometry<D>& g) {
        s.gradC += (P.m[j] / P.rho[j]) * g.gradW;
        s.M += correction_moment_term(P.m[j] / P.rho[j], g);
      },
      Rows::Fluid);
  // Wall particles above the free surface are no part of the fluid's support: a first normal from all
  // neighbours, then the kernel-gradient sum again, twice, without the walls beyond the surface that the
  // last normal gives. Otherwise a surface particle on a side wall that rises above the water has its
  // normal tilted away from the wall (by 2.5 degrees at 40 particles a unit, still 0.6 after one pass),
  // and its node pushed it off the wall by a spacing in t = 20.
  std::vector<Vector<D>> first(P.n_owned, Vector<D>::Zero());
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (surface[i] && sum[i].gradC.norm() > 0.0) first[i] = -sum[i].gradC.normalized();
  std::vector<Vector<D>> gradC;
  for (int pass = 0; pass < 2; ++pass) {
    gradC = sum_over_pairs(
        P, nl, K, Vector<D>(Vector<D>::Zero()),
        [&](Vector<D>& s, int i, int j, const PairGeometry<D>& g) {
          if (P.kind[j] != kFluid && first[i].dot(-g.rij) > d) return;
          s += (P.m[j] / P.rho[j]) * g.gradW;
        },
        Rows::Fluid);
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (surface[i] && gradC[i].norm() > 0.0) first[i] = -gradC[i].normalized();
  }
  nodes.normal.assign(P.n_owned, Vector<D>::Zero());
  nodes.volume.assign(P.n_owned, 0.0);
  nodes.splash.assign(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (!surface[i]) continue;
    const double length = gradC[i].norm();
    if (length > 0.0) nodes.normal[i] = -gradC[i] / length;  // sum_j V_j grad_i W_ij points into the fluid
    // A sheet or a drop (moments_resolve): no node, and its corrected operators are not used.
    if (!moments_resolve(sum[i].M)) {
      nodes.splash[i] = 1;
      continue;
    }
    if (length > 0.0 && nodes.gradW > 0.0) nodes.volume[i] = length / nodes.gradW;
  }
  return nodes;
}

// The corrected gradient (gradient_corrected) with each surface particle's node as one more neighbour;
// sheets and drops (SurfaceNodes::splash) take the uncorrected sum, their moment matrix being near
// singular.
template <int D> std::vector<Vector<D>> gradient_corrected(const Particles<D>& P, const NeighbourList<D>& nl,
                                                           const Kernel<D>& K, const std::vector<double>& f, Rows rows,
                                                           const SurfaceNodes<D>& nodes, CallSite at = CallSite()) {
  std::vector<Vector<D>> grad(P.n_owned, Vector<D>::Zero());
  for_each_gradient_sum(
      P, nl, K, f, rows,
      [&](std::size_t i, Tensor<D> M, Vector<D> g) {
        if (nodes.has(i)) M += nodes.moment_term(i), g += nodes.gradient_term(i, f[i]);
        grad[i] = nodes.is_splash(i) ? g : Vector<D>(correction_from_moments(M) * g);
      },
      at);
  return grad;
}

}  // namespace sph
