#pragma once
// The one neighbour loop of the code. Schemes supply the physics of a single i-j pair as a callable;
// the loop supplies the pair geometry (separation, kernel value and gradient), evaluated at current
// positions (lists may hold skin neighbours outside the support: those are skipped here).
#include "src/kernels/kernel.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D> struct PairGeometry {
  Vector<D> rij;      // x_i - x_j
  double r;        // |x_i - x_j| > 0
  double W;        // W(r, h)
  double dWdr;     // dW/dr
  Vector<D> gradW;    // grad_i W_ij
};

// f(i, j, geometry) for every owned particle i and neighbour j with 0 < r_ij < support.
template <int D, class PairFn>
void for_each_pair(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, PairFn&& f) {
  const double rc2 = K.support_radius() * K.support_radius();
  PairGeometry<D> g;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    for (const int* it = nl.begin(i); it != nl.end(i); ++it) {
      const int j = *it;
      g.rij = P.x[i] - P.x[j];
      const double r2 = g.rij.squaredNorm();
      if (r2 >= rc2 || r2 == 0.0) continue;
      g.r = std::sqrt(r2);
      g.W = K.W(g.r);
      g.dWdr = K.dWdr(g.r);
      g.gradW = (g.dWdr / g.r) * g.rij;
      f(static_cast<int>(i), j, g);
    }
  }
}

}  // namespace sph
