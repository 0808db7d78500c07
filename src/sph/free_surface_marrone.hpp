#pragma once
// Free-surface detection by Marrone et al. (2010), "Fast free-surface detection and level-set function
// definition in SPH solvers", J. Comput. Phys. 229: the moment matrix's smallest eigenvalue sorts most
// particles, and a scan of the region outside each doubtful one decides the rest.
//
// lambda_i, the smallest eigenvalue of M_i = sum_j V_j grad_i W_ij (x_j - x_i)^T (1 inside the fluid, about
// 0.5 on a flat surface, near 0 on a drop or a sheet): lambda <= 0.2 is surface, lambda > 0.75 interior.
// Between the two, i is on the surface unless a neighbour (fluid or wall) lies in the umbrella beyond it:
// with n_i the outward normal -L_i sum_j V_j grad_i W_ij and T = x_i + h n_i, a neighbour j covers i when
//   |x_j - x_i| >= sqrt(2) h and |x_j - T| < h, or
//   |x_j - x_i| <  sqrt(2) h and |n . (x_j - T)| + |(x_j - T) - (n . (x_j - T)) n| < h.
// div r, the other test, reads the support's volume alone and flags particles inside a disordered
// fluid whose support holds a gap; the scan asks whether there is fluid beyond the particle.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "src/sph/operators.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

namespace marrone {
inline constexpr double surface_eigenvalue = 0.2;    // at or below: on the surface
inline constexpr double interior_eigenvalue = 0.75;  // above: inside the fluid
}  // namespace marrone

// Marrone's scan: for each owned particle i with doubtful[i], whether a neighbour (fluid or wall) lies in
// the umbrella beyond it, along its unit outward normal[i]. 1: covered (inside the fluid).
template <int D> std::vector<char> umbrellas_covered(const Particles<D>& P, const NeighbourList<D>& nl,
                                                     const Kernel<D>& K, const std::vector<char>& doubtful,
                                                     const std::vector<Vector<D>>& normal) {
  const double h = K.h(), sqrt2h = std::sqrt(2.0) * h;
  std::vector<char> covered(P.n_owned, 0);
  for_each_pair(P, nl, K, [&](int i, int, const PairGeometry<D>& g) {
    if (!doubtful[i] || covered[i]) return;
    const Vector<D>& nrm = normal[i];
    const Vector<D> to_T = -g.rij - h * nrm;  // x_j - T, with T = x_i + h n
    const double along = nrm.dot(to_T);
    const bool in_umbrella = g.r >= sqrt2h ? to_T.norm() < h : std::abs(along) + (to_T - along * nrm).norm() < h;
    if (in_umbrella) covered[i] = 1;
  });
  return covered;
}

// 1 for fluid particles on the free surface, 0 otherwise (one entry per owned particle). With `previous`
// (the last step's flags, nonzero = on the surface), a flagged particle stays flagged while its
// eigenvalue is not above the interior's.
template <int D> std::vector<char> marrone_surface_particles(const Particles<D>& P, const NeighbourList<D>& nl,
                                                             const Kernel<D>& K,
                                                             const std::vector<double>* previous = nullptr) {
  struct Sums {
    Tensor<D> M;
    Vector<D> gradC;
    bool fluid;
  };
  const std::vector<Sums> sums = sum_over_pairs(
      P, nl, K, Sums{Tensor<D>::Zero(), Vector<D>::Zero(), false},
      [&](Sums& s, int, int j, const PairGeometry<D>& g) {
        const double Vj = P.m[j] / P.rho[j];
        s.M += correction_moment_term(Vj, g);
        s.gradC += Vj * g.gradW;
        s.fluid |= P.kind[j] == kFluid;
      },
      Rows::Fluid);
  const std::size_t n = P.n_owned;
  std::vector<char> surface(n, 0), doubtful(n, 0);
  std::vector<Vector<D>> normal(n, Vector<D>::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] != kFluid) continue;
    if (!sums[i].fluid) {  // a particle with no fluid neighbour (a drop alone, one stuck on a wall)
      surface[i] = 1;
      continue;
    }
    const Tensor<D> Ms = 0.5 * (sums[i].M + sums[i].M.transpose());
    const double lambda = Eigen::SelfAdjointEigenSolver<Tensor<D>>(Ms, Eigen::EigenvaluesOnly).eigenvalues()[0];
    if (lambda <= marrone::surface_eigenvalue) surface[i] = 1;
    if (lambda <= marrone::surface_eigenvalue || lambda > marrone::interior_eigenvalue) continue;
    if (previous && (*previous)[i] != 0.0) {
      surface[i] = 1;
      continue;
    }
    const Vector<D> nu = -(correction_from_moments(sums[i].M) * sums[i].gradC);
    if (nu.norm() == 0.0) continue;  // a symmetric support has no outside to scan: inside
    normal[i] = nu.normalized();
    doubtful[i] = 1;
  }
  const std::vector<char> covered = umbrellas_covered(P, nl, K, doubtful, normal);
  for (std::size_t i = 0; i < n; ++i)
    if (doubtful[i] && !covered[i]) surface[i] = 1;
  return surface;
}

}  // namespace sph
