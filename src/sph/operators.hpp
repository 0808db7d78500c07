#pragma once
// SPH differential operators on particle fields (outputs hold one value per owned particle).
// Every operator is the shared pair loop with a small pair formula; V_j = m_j / rho_j.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "src/core/integer_power.hpp"
#include "src/sph/pair_terms.hpp"

namespace sph {

// Pair formulas shared by the operators below and by loops that gather several sums at once
// (gradient_corrected, shift_particles); Vj = m_j / rho_j.
// Term of sum_j V_j (f_j - f_i) grad_i W_ij.
template <int D> inline Vector<D> difference_gradient_term(double Vj, double fi, double fj, const PairGeometry<D>& g) {
  return (Vj * (fj - fi)) * g.gradW;
}
// Term of sum_j V_j grad_i W_ij (u_j - u_i)^T.
template <int D> inline Tensor<D> difference_vector_gradient_term(double Vj, const Vector<D>& ui, const Vector<D>& uj,
                                                                  const PairGeometry<D>& g) {
  return Vj * g.gradW * (uj - ui).transpose();
}
// Term of the moment matrix -sum_j V_j grad_i W_ij r_ij^T = sum_j V_j grad_i W_ij (x_j - x_i)^T.
template <int D> inline Tensor<D> correction_moment_term(double Vj, const PairGeometry<D>& g) {
  return -Vj * g.gradW * g.rij.transpose();
}

// rho_i = sum_j m_j W_ij (self term included).
template <int D>
std::vector<double> density_summation(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
  std::vector<double> rho(P.n_owned);
  for (std::size_t i = 0; i < P.n_owned; ++i) rho[i] = P.m[i] * K.W(0.0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) { rho[i] += P.m[j] * g.W; });
  return rho;
}

// (div u)_i = -(1/rho_i) sum_j m_j u_ij . grad_i W_ij  (exact for uniform u).
template <int D> std::vector<double> divergence(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                                const std::vector<Vector<D>>& u, CallSite at = CallSite()) {
  check_ghosts(nl, u, "the divergence's field", at);
  std::vector<double> div(P.n_owned, 0.0);
  for_each_pair(
      P, nl, K, [&](int i, int j, const PairGeometry<D>& g) { div[i] -= P.m[j] * (u[i] - u[j]).dot(g.gradW); },
      Rows::All, at);
  for (std::size_t i = 0; i < P.n_owned; ++i) div[i] /= P.rho[i];
  return div;
}

// (grad f)_i = sum_j V_j (f_j - f_i) grad_i W_ij  (zero for constant f).
template <int D> std::vector<Vector<D>> gradient_difference(const Particles<D>& P, const NeighbourList<D>& nl,
                                                            const Kernel<D>& K, const std::vector<double>& f,
                                                            CallSite at = CallSite()) {
  check_ghosts(nl, f, "the gradient's field", at);
  return sum_over_pairs(
      P, nl, K, Vector<D>(Vector<D>::Zero()),
      [&](Vector<D>& grad, int i, int j, const PairGeometry<D>& g) {
        grad += difference_gradient_term(P.m[j] / P.rho[j], f[i], f[j], g);
      },
      Rows::All, at);
}

// (grad f)_i = rho_i sum_j m_j (f_i/rho_i^2 + f_j/rho_j^2) grad_i W_ij: the momentum-conserving
// (antisymmetric in i, j) form of Monaghan (1992).
template <int D> std::vector<Vector<D>> gradient_symmetric(const Particles<D>& P, const NeighbourList<D>& nl,
                                                           const Kernel<D>& K, const std::vector<double>& f,
                                                           CallSite at = CallSite()) {
  check_ghosts(nl, f, "the gradient's field", at);
  std::vector<Vector<D>> grad(P.n_owned, Vector<D>::Zero());
  for_each_pair(
      P, nl, K,
      [&](int i, int j, const PairGeometry<D>& g) {
        grad[i] += (P.m[j] * (f[i] / (P.rho[i] * P.rho[i]) + f[j] / (P.rho[j] * P.rho[j]))) * g.gradW;
      },
      Rows::All, at);
  for (std::size_t i = 0; i < P.n_owned; ++i) grad[i] *= P.rho[i];
  return grad;
}

// A moment matrix sum_j V_j grad_i W_ij (x_j - x_i)^T whose symmetric part has its smallest eigenvalue
// below this (1 in the bulk, about 1/2 on a flat free surface) belongs to a sheet or a drop: its inverse
// amplifies noise, so corrected operators are not used there (docs/verification/free_surface.md).
// Marrone et al. (2010) class such particles by the same eigenvalue and threshold.
constexpr double splash_eigenvalue = 0.2;

// True where M's smallest eigenvalue (of its symmetric part) is at least splash_eigenvalue. Gershgorin's
// bound settles the bulk without an eigen-solve.
template <int D> bool moments_resolve(const Tensor<D>& M) {
  const Tensor<D> Ms = 0.5 * (M + M.transpose());
  double bound = Ms(0, 0) - (Ms.row(0).cwiseAbs().sum() - std::abs(Ms(0, 0)));
  for (int a = 1; a < D; ++a) bound = std::min(bound, Ms(a, a) - (Ms.row(a).cwiseAbs().sum() - std::abs(Ms(a, a))));
  if (bound >= splash_eigenvalue) return true;
  const double lambda = Eigen::SelfAdjointEigenSolver<Tensor<D>>(Ms, Eigen::EigenvaluesOnly).eigenvalues()[0];
  return lambda >= splash_eigenvalue;
}

// Kernel-gradient correction L_i = (sum_j V_j grad_i W_ij (x_j - x_i)^T)^{-1} (Bonet & Lok 1999):
// with it, sum_j V_j (f_j - f_i) L_i grad_i W_ij is exact for linear f on any particle distribution.
// Where the moment matrix is singular (isolated particles) the identity is used.
template <int D> Tensor<D> correction_from_moments(const Tensor<D>& M) {
  const double det = M.determinant();
  return std::abs(det) > 1e-8 * integer_power(M.norm(), D) ? Tensor<D>(M.inverse()) : Tensor<D>(Tensor<D>::Identity());
}

// The moment matrices sum_j V_j grad_i W_ij (x_j - x_i)^T, inverted.
template <int D>
std::vector<Tensor<D>> correction_matrices(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
  std::vector<Tensor<D>> M(P.n_owned, Tensor<D>::Zero());
  for_each_pair(P, nl, K,
                [&](int i, int j, const PairGeometry<D>& g) { M[i] += correction_moment_term(P.m[j] / P.rho[j], g); });
  for (auto& Mi : M) Mi = correction_from_moments(Mi);
  return M;
}

template <int D> std::vector<Vector<D>> gradient_corrected(const Particles<D>& P, const NeighbourList<D>& nl,
                                                           const Kernel<D>& K, const std::vector<Tensor<D>>& L,
                                                           const std::vector<double>& f) {
  std::vector<Vector<D>> grad = gradient_difference(P, nl, K, f);
  for (std::size_t i = 0; i < P.n_owned; ++i) grad[i] = L[i] * grad[i];
  return grad;
}

// Per particle, the moment matrix M and the uncorrected gradient sum g of f, from one pair loop, handed
// to done(i, M, g) while the particle is visited: stored for every particle they were the largest array
// of ISPH's velocity correction, its memory peak (docs/performance.md, "Memory per particle").
template <int D, class Done> void for_each_gradient_sum(const Particles<D>& P, const NeighbourList<D>& nl,
                                                        const Kernel<D>& K, const std::vector<double>& f, Rows rows,
                                                        Done&& done, CallSite at = CallSite()) {
  check_ghosts(nl, f, "the gradient's field", at);
  for_each_particle_pairs(
      P, nl, K,
      [&](std::size_t i, auto&& visit_pairs) {
        Tensor<D> M = Tensor<D>::Zero();
        Vector<D> grad = Vector<D>::Zero();
        visit_pairs([&](int ii, int j, const PairGeometry<D>& g) {
          const double Vj = P.m[j] / P.rho[j];
          M += correction_moment_term(Vj, g);
          grad += difference_gradient_term(Vj, f[ii], f[j], g);
        });
        done(i, M, grad);
      },
      rows, at);
}

// The same, with the correction matrices gathered in the same pair loop (bitwise the same result, one
// pair loop instead of two) for callers that need no other corrected quantity.
template <int D> std::vector<Vector<D>> gradient_corrected(const Particles<D>& P, const NeighbourList<D>& nl,
                                                           const Kernel<D>& K, const std::vector<double>& f,
                                                           Rows rows = Rows::All, CallSite at = CallSite()) {
  std::vector<Vector<D>> grad(P.n_owned, Vector<D>::Zero());
  for_each_gradient_sum(
      P, nl, K, f, rows,
      [&](std::size_t i, const Tensor<D>& M, const Vector<D>& g) { grad[i] = correction_from_moments(M) * g; }, at);
  return grad;
}

// Corrected gradient of a vector field: G_i(a, b) = d u_b / d x_a.
template <int D> std::vector<Tensor<D>> vector_gradient_corrected(const Particles<D>& P, const NeighbourList<D>& nl,
                                                                  const Kernel<D>& K, const std::vector<Tensor<D>>& L,
                                                                  const std::vector<Vector<D>>& u,
                                                                  CallSite at = CallSite()) {
  check_ghosts(nl, u, "the gradient's field", at);
  std::vector<Tensor<D>> G(P.n_owned, Tensor<D>::Zero());
  for_each_pair(
      P, nl, K,
      [&](int i, int j, const PairGeometry<D>& g) {
        G[i] += difference_vector_gradient_term(P.m[j] / P.rho[j], u[i], u[j], g);
      },
      Rows::All, at);
  for (std::size_t i = 0; i < P.n_owned; ++i) G[i] = L[i] * G[i];
  return G;
}

// Morris et al. (1997) Laplacian: (lap f)_i = 2 sum_j V_j (f_i - f_j) F_ij.
template <int D, class T> std::vector<T> laplacian_morris(const Particles<D>& P, const NeighbourList<D>& nl,
                                                          const Kernel<D>& K, const std::vector<T>& f,
                                                          CallSite at = CallSite()) {
  check_ghosts(nl, f, "the Laplacian's field", at);
  std::vector<T> lap(P.n_owned, T(f.empty() ? T() : f[0] * 0.0));
  for_each_pair(
      P, nl, K,
      [&](int i, int j, const PairGeometry<D>& g) {
        lap[i] += (2.0 * P.m[j] / P.rho[j] * morris_factor(g, K.h())) * (f[i] - f[j]);
      },
      Rows::All, at);
  return lap;
}

}  // namespace sph
