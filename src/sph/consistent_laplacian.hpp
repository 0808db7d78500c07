#pragma once
// A Laplacian that is consistent on any particle distribution (after Fatehi & Manzari 2011, "Error
// estimation in smoothed particle hydrodynamics and a new scheme for second derivatives", Comput.
// Math. Appl. 61:482; Schwaiger 2008 for the same idea with a scalar normalisation).
//
// The Morris (1997) / Cummins & Rudman (1999) Laplacian 2 sum_j V_j F_ij (f_i - f_j) is exact only
// on symmetric neighbourhoods: on the disordered distributions that particles take as soon as they
// move, its error is O(1) in the particle disorder and does not shrink with h. In the ISPH projection
// that error makes the Laplacian differ from the divergence of the gradient that corrects the
// velocity, so every step leaves a divergence that the next one removes again: an error per step,
// not per unit time, which grows as dt falls (docs/verification/taylor_green.md, "History").
//
// With r = x_j - x_i, e = r / |r| and g_ij = -V_j W'(r) / |r| > 0 (the Morris weight), the operator
//   lap f_i = sum_j w_ij (f_j - f_i),   w_ij = 2 g_ij (e^T A_i e + c_i . e),
// takes a symmetric D x D tensor A_i and a vector c_i per particle, chosen so that the weights'
// first moments vanish and their second moments are twice the identity:
//   sum_j w_ij r = 0,   sum_j w_ij r r^T = 2 I.
// By Taylor's theorem the sum is then exact for every quadratic f on any particle distribution, and
// its error is the third moments times the third derivatives: O(h) on disordered particles, O(h^2)
// where the neighbourhood is symmetric (a lattice: there c = 0, and A = I on a uniform continuum,
// which is Morris' operator). That is D + D(D+1)/2 equations for as many unknowns, solved per
// particle. Where the neighbourhood cannot span the quadratics, or the solution would make a weight
// negative (one-sided neighbourhoods at a free surface), the Morris weights are kept.
//
// Fatehi & Manzari instead keep c = 0 and subtract the first moments times the corrected gradient,
// which leaves an O(disorder^2) error that stops falling where this form keeps converging
// (docs/pressure-solve.md, "Design measurements").
//
// Rows sum to zero (constants are in the null space) but w_ij != w_ji: a PPE built on it is not
// symmetric.
#include <array>
#include <stdexcept>
#include <vector>

#include "src/core/small_inverse.hpp"
#include "src/sph/laplacian_moments.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/surface_nodes.hpp"

namespace sph {

// The operator set a solver uses (-isph_operators, -wcsph_operators): the consistent forms of this file with the
// corrected divergence, or the classic SPH forms (Morris Laplacian, plain divergence).
enum class OperatorSet { Consistent, Classic };
inline const char* const operator_set_names[] = {"consistent", "classic"};

// Per-particle factors of the consistent Laplacian (see above).
template <int D> struct LaplacianCorrection {
  Tensor<D> A = Tensor<D>::Identity();  // weight of the direction e e^T
  Vector<D> c = Vector<D>::Zero();      // weight of the direction e
};

// w_ij of one pair, given i's factors (r = x_j - x_i = -rij).
template <int D>
inline double consistent_laplacian_coefficient(const LaplacianCorrection<D>& f, double Vj, const PairGeometry<D>& g) {
  const Vector<D> e = -g.rij / g.r;
  return 2.0 * Vj * (-g.dWdr_r) * (e.dot(f.A * e) + f.c.dot(e));
}

namespace detail {
// Where each entry of a particle's system (below) lies among its distinct moments: entry (p, q) is
// factor * moment[index] of the array `kind` (0: g s e^2, 1: g s e^3, 2: g s^2 e^3, 3: g s^2 e^4).
template <int D> struct LaplacianSystemLayout {
  static constexpr int m = D * (D + 1) / 2, n = m + D;
  std::array<std::array<int, n>, n> kind{}, index{};
  std::array<std::array<double, n>, n> factor{};
  constexpr LaplacianSystemLayout() {
    const Monomials<D, 2> quadratic;
    const Monomials<D, 3> cubic;
    const Monomials<D, 4> quartic;
    for (int p = 0; p < n; ++p)
      for (int q = 0; q < n; ++q) {
        const bool linear_row = p >= m, linear_column = q >= m;
        const auto& pa = quadratic.axes[linear_row ? 0 : p];
        const auto& qa = quadratic.axes[linear_column ? 0 : q];
        factor[p][q] = linear_column || qa[0] == qa[1] ? 1.0 : 2.0;
        if (linear_row && linear_column) kind[p][q] = 0, index[p][q] = quadratic.index_unsorted({p - m, q - m});
        else if (linear_row) kind[p][q] = 1, index[p][q] = cubic.index_unsorted({p - m, qa[0], qa[1]});
        else if (linear_column) kind[p][q] = 2, index[p][q] = cubic.index_unsorted({pa[0], pa[1], q - m});
        else kind[p][q] = 3, index[p][q] = quartic.index_unsorted({pa[0], pa[1], qa[0], qa[1]});
      }
  }
};

// The unknowns (A_ab for a <= b, then c_a) and the moment conditions (the second moments k <= l, then
// the first moments) of one particle, as a square system S z = rhs with
//   S = sum_j g_j psi_j phi_j^T,  phi = (c_ab e_a e_b for a <= b, e_a),  psi = (s^2 e_a e_b, s e_a),
// c_ab = 1 on the diagonal and 2 off it; e = (x_j - x_i) / |x_j - x_i| and s = |x_j - x_i| in units of
// the support radius (keeps the system well scaled), so r = s e. Its entries are the distinct
// moments of laplacian_moments.hpp. The second-moment conditions come first: on a near-lattice
// neighbourhood the odd moments nearly vanish, S is then close to block diagonal with a dominant
// diagonal, and partial pivoting seldom swaps rows. With the first moments first the leading diagonal
// entries were odd moments, near zero: every particle's inverse swapped rows, near-ties between
// symmetric rows making each swap a mispredicted branch (2D: 140 ns an inverse against 90).
template <int D> struct LaplacianSystem {
  static constexpr int m = D * (D + 1) / 2, n = m + D;
  using Vec = Eigen::Matrix<double, n, 1>;
  Eigen::Matrix<double, n, n> S;

  explicit LaplacianSystem(const LaplacianMoments<D>& moments) {
    constexpr LaplacianSystemLayout<D> layout;
    const double* arrays[4] = {moments.gs2.data(), moments.gs3.data(), moments.gss3.data(), moments.gss4.data()};
    for (int p = 0; p < n; ++p)
      for (int q = 0; q < n; ++q) S(p, q) = layout.factor[p][q] * arrays[layout.kind[p][q]][layout.index[p][q]];
  }
  // Returns false (and leaves f as it is) when the moments are degenerate.
  bool solve(LaplacianCorrection<D>& f) const {
    Vec rhs = Vec::Zero();
    int q = 0;
    for (int a = 0; a < D; ++a)
      for (int b = a; b < D; ++b, ++q) rhs(q) = a == b ? 1.0 : 0.0;  // sum_j 2 g e^T.. r r = 2 I -> I after /2
    // The exact 1-norm condition number from the inverse: a singular or near-singular S (a
    // neighbourhood that cannot span the quadratics) shows as rcond < 1e-10 or NaN. Partial pivoting
    // and the exact inverse cost less than full pivoting and Eigen's iterative rcond estimate
    // (docs/performance.md, "Design measurements").
    Eigen::Matrix<double, n, n, Eigen::RowMajor> inv;
    if (!invert_partial_pivot<n>(S, inv)) return false;
    const double rcond = 1.0 / (S.cwiseAbs().colwise().sum().maxCoeff() * inv.cwiseAbs().colwise().sum().maxCoeff());
    if (!(rcond >= 1e-10)) return false;
    const Vec z = inv * rhs;
    q = 0;
    for (int a = 0; a < D; ++a)
      for (int b = a; b < D; ++b, ++q) f.A(a, b) = f.A(b, a) = z(q);
    for (int a = 0; a < D; ++a) f.c(a) = z(m + a);
    return true;
  }
};

// The kernel-gradient moment matrix sum_j V_j grad_i W_ij (x_j - x_i)^T = sum_j g_ij r r^T, over R^2,
// read off the degree-4 moments: sum_j g s^2 e_a e_b = sum_c sum_j g s^2 e_a e_b e_c e_c, as |e| = 1.
template <int D> Tensor<D> moment_matrix_over_R2(const LaplacianMoments<D>& moments) {
  static const std::array<std::array<std::array<int, D>, D>, D> index = [] {
    constexpr Monomials<D, 4> m4;
    std::array<std::array<std::array<int, D>, D>, D> t{};
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b)
        for (int c = 0; c < D; ++c) t[a][b][c] = m4.index_unsorted({a, b, c, c});
    return t;
  }();
  Tensor<D> M = Tensor<D>::Zero();
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b)
      for (int c = 0; c < D; ++c) M(a, b) += moments.gss4[index[a][b][c]];
  return M;
}

// One particle's factors from its recorded pairs (the first pairs.size; `padded` from pairs.padded());
// Morris' (A = I, c = 0) where the system is degenerate, the particle is a sheet or a drop
// (moments_resolve: its near-singular system amplifies noise; docs/verification/free_surface.md), or a
// weight would be negative.
template <int D>
LaplacianCorrection<D> solve_laplacian_factors(const LaplacianPairs<D>& pairs, std::size_t padded, double inv_R) {
  LaplacianCorrection<D> f;
  const LaplacianMoments<D> moments = sum_laplacian_moments(pairs, padded);
  if (!moments_resolve<D>(moment_matrix_over_R2(moments) / (inv_R * inv_R))) return {};
  if (!LaplacianSystem<D>(moments).solve(f)) return {};
  // Keep the weights positive, as Morris' are: a negative weight (a one-sided neighbourhood, at a
  // free surface) makes the PPE row lose its diagonal dominance, and the dam break blew up.
  for (std::size_t k = 0; k < pairs.size; ++k) {
    const Vector<D> e = pairs.direction(k);
    if (!(e.dot(f.A * e) + f.c.dot(e) > 0.0)) return {};
  }
  return {f.A * (inv_R * inv_R), f.c * (inv_R * inv_R)};
}
}  // namespace detail

// The factors of every owned particle, from one pass over each particle's pairs.
template <int D> std::vector<LaplacianCorrection<D>> laplacian_corrections(const Particles<D>& P,
                                                                           const NeighbourList<D>& nl,
                                                                           const Kernel<D>& K, Rows rows = Rows::All) {
  std::vector<LaplacianCorrection<D>> out(P.n_owned);
  const double inv_R = 1.0 / K.support_radius();
  for_each_particle_pairs(
      P, nl, K,
      [&](std::size_t i, auto&& visit_pairs) {
        LaplacianPairs<D>& pairs = laplacian_pair_buffer<D>();
        // Moments of g_ij (the factor 2 of w and of the condition cancel); r scaled by 1 / R, so the
        // solution is A R^2 and c R: scaled back in solve_laplacian_factors.
        visit_pairs([&](int, int j, const PairGeometry<D>& g) {
          pairs.add(-g.rij / g.r, g.r * inv_R, P.m[j] / P.rho[j] * (-g.dWdr_r));
        });
        out[i] = detail::solve_laplacian_factors(pairs, pairs.padded(), inv_R);
      },
      rows);
  return out;
}

// The consistent Laplacian of a vector field at one particle, gathered in a pair loop that does other
// work too (WCSPH's rates), without the factors computed beforehand: lap f_i = sum_j w_ij (f_j - f_i) is
// linear in (A, c), so the loop sums the moments sum_j 2 g_ij e_a e_b (f_j - f_i) (a <= b) and
// sum_j 2 g_ij e_a (f_j - f_i) beside the factors' system, and the factors are applied once after it.
// The same operator as laplacian_corrections + consistent_laplacian_coefficient, to round-off, in one
// pass over the pairs instead of two.
template <int D> struct FusedConsistentLaplacian {
  LaplacianPairs<D>* pairs;

  explicit FusedConsistentLaplacian(LaplacianPairs<D>& buffer) : pairs(&buffer) {}
  void add(double Vj, const PairGeometry<D>& g, double inv_R, const Vector<D>& df) {
    const double gij = Vj * (-g.dWdr_r);
    pairs->add(-g.rij / g.r, g.r * inv_R, gij, (2.0 * gij) * df);
  }
  // The Laplacian; `factors`, if given, receives the factors it was applied with (those of
  // laplacian_corrections, bitwise: the same moments summed in the same order).
  Vector<D> finish(double inv_R, LaplacianCorrection<D>* factors = nullptr) const {
    const std::size_t padded = pairs->padded();
    const LaplacianCorrection<D> f = detail::solve_laplacian_factors(*pairs, padded, inv_R);
    if (factors) *factors = f;
    const detail::LaplacianFieldMoments<D> moments = detail::sum_laplacian_field_moments(*pairs, padded);
    Vector<D> lap = moments.first.transpose() * f.c;
    int q = 0;
    for (int a = 0; a < D; ++a)
      for (int b = a; b < D; ++b, ++q) lap += ((a == b ? 1.0 : 2.0) * f.A(a, b)) * moments.second[q];
    return lap;
  }
};

// lap f_i = sum_j w_ij (f_j - f_i) for scalar or vector fields.
template <int D, class T>
std::vector<T> laplacian_consistent(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                    const std::vector<LaplacianCorrection<D>>& c, const std::vector<T>& f,
                                    Rows rows = Rows::All, CallSite at = CallSite()) {
  check_ghosts(nl, f, "the Laplacian's field", at);
  return sum_over_pairs(
      P, nl, K, T(f.empty() ? T() : f[0] * 0.0),
      [&](T& lap, int i, int j, const PairGeometry<D>& g) {
        lap += consistent_laplacian_coefficient(c[i], P.m[j] / P.rho[j], g) * (f[j] - f[i]);
      },
      rows, at);
}

// The consistent Laplacian of a vector field with each particle's factors gathered in the same pass
// (FusedConsistentLaplacian): the operator of laplacian_corrections + laplacian_consistent, to
// round-off, in one pass over the pairs instead of two. `factors`, if given, receives every owned
// particle's factors (Morris' where a row is not visited), as laplacian_corrections gives them.
template <int D> std::vector<Vector<D>> laplacian_consistent_one_pass(
    const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, const std::vector<Vector<D>>& f,
    Rows rows = Rows::All, std::vector<LaplacianCorrection<D>>* factors = nullptr, CallSite at = CallSite()) {
  check_ghosts(nl, f, "the Laplacian's field", at);
  std::vector<Vector<D>> out(P.n_owned, Vector<D>::Zero());
  if (factors) factors->assign(P.n_owned, LaplacianCorrection<D>());
  const double inv_R = 1.0 / K.support_radius();
  for_each_particle_pairs(
      P, nl, K,
      [&](std::size_t i, auto&& visit_pairs) {
        FusedConsistentLaplacian<D> lap(laplacian_pair_buffer<D>());
        visit_pairs([&](int, int j, const PairGeometry<D>& g) {
          lap.add(P.m[j] / P.rho[j], g, inv_R, Vector<D>(f[j] - f[i]));
        });
        out[i] = lap.finish(inv_R, factors ? &(*factors)[i] : nullptr);
      },
      rows, at);
  return out;
}

// (div u)_i = tr(L_i sum_j V_j grad_i W_ij (u_j - u_i)^T), with the correction matrices gathered in
// the same pair loop: exact for linear u on any distribution, unlike the plain divergence, whose
// error is O(1) in the particle disorder. Of up to two fields at once (ISPH's source reads the
// divergences of u* and u^n at the same positions): one pass over the pairs and one moment matrix for
// both, each result bitwise that of a pass of its own (the same terms in the same order).
template <int D>
std::vector<std::vector<double>> divergences_corrected(const Particles<D>& P, const NeighbourList<D>& nl,
                                                       const Kernel<D>& K,
                                                       const std::vector<const std::vector<Vector<D>>*>& u,
                                                       Rows rows = Rows::All, const SurfaceNodes<D>* nodes = nullptr,
                                                       CallSite at = CallSite()) {
  constexpr std::size_t max_fields = 2;
  if (u.empty() || u.size() > max_fields) throw std::logic_error("divergences_corrected: one or two fields");
  for (const auto* field : u) check_ghosts(nl, *field, "the divergence's field", at);
  const std::size_t nf = u.size();
  // Each particle's sums live only while it is visited: stored for every particle they were the
  // largest array of the projection's correction pass, its memory peak (docs/performance.md, "Memory
  // per particle").
  std::vector<std::vector<double>> div(nf, std::vector<double>(P.n_owned, 0.0));
  for_each_particle_pairs(
      P, nl, K,
      [&](std::size_t i, auto&& visit_pairs) {
        Tensor<D> M = Tensor<D>::Zero();
        std::array<Tensor<D>, max_fields> G{Tensor<D>::Zero(), Tensor<D>::Zero()};
        visit_pairs([&](int ii, int j, const PairGeometry<D>& g) {
          const double Vj = P.m[j] / P.rho[j];
          M += correction_moment_term(Vj, g);
          for (std::size_t f = 0; f < nf; ++f) G[f] += difference_vector_gradient_term(Vj, (*u[f])[ii], (*u[f])[j], g);
        });
        // A surface node moves with its particle: it adds to the moments only.
        const Tensor<D> L =
            nodes && nodes->is_splash(i)
                ? Tensor<D>(Tensor<D>::Identity())
                : correction_from_moments(nodes && nodes->has(i) ? Tensor<D>(M + nodes->moment_term(i)) : M);
        for (std::size_t f = 0; f < nf; ++f) div[f][i] = (L * G[f]).trace();
      },
      rows, at);
  return div;
}

template <int D> std::vector<double> divergence_corrected(const Particles<D>& P, const NeighbourList<D>& nl,
                                                          const Kernel<D>& K, const std::vector<Vector<D>>& u,
                                                          Rows rows = Rows::All) {
  return divergences_corrected(P, nl, K, {&u}, rows)[0];
}

// The factors of the particles with a free-surface node (src/sph/surface_nodes.hpp), refitted with the
// node as one more neighbour (p = 0 there), so that their rows stay exact for quadratic fields that
// vanish at the surface; the others are left as they are.
template <int D> void add_surface_nodes(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                        const SurfaceNodes<D>& nodes, std::vector<LaplacianCorrection<D>>& factors) {
  const double inv_R = 1.0 / K.support_radius();
  for_each_particle_pairs(
      P, nl, K,
      [&](std::size_t i, auto&& visit_pairs) {
        if (!nodes.has(i)) return;
        LaplacianPairs<D>& pairs = laplacian_pair_buffer<D>();
        visit_pairs([&](int, int j, const PairGeometry<D>& g) {
          pairs.add(-g.rij / g.r, g.r * inv_R, P.m[j] / P.rho[j] * (-g.dWdr_r));
        });
        pairs.add(nodes.normal[i], nodes.distance * inv_R, nodes.node_weight(i));
        factors[i] = detail::solve_laplacian_factors(pairs, pairs.padded(), inv_R);
      },
      Rows::Fluid);
}

// The node's weight w_is in i's consistent Laplacian (consistent_laplacian_coefficient for the node).
template <int D>
double surface_node_coefficient(const LaplacianCorrection<D>& f, const SurfaceNodes<D>& nodes, std::size_t i) {
  const Vector<D>& e = nodes.normal[i];
  return 2.0 * nodes.node_weight(i) * (e.dot(f.A * e) + f.c.dot(e));
}

}  // namespace sph
