#pragma once
// The rows of the pressure Poisson matrix, assembled straight into compressed sparse rows split as
// PETSc's MPIAIJ matrix keeps them (ppe_matrix.hpp copies them into the matrix). Each row depends
// only on its own particle's neighbours, so rows are counted, filled
// and sorted by the OpenMP threads of the pair loops, and every row is bitwise the same on any thread
// count. The equations are described in pressure_poisson.hpp.
#include <petscsys.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "src/boundary/wall_model.hpp"
#include "src/sph/consistent_laplacian.hpp"
#include "src/sph/pair_terms.hpp"

namespace sph {

// Coefficient c_ij of the Cummins & Rudman (1999) pressure Laplacian (the classic operator set)
//   div(grad p / rho)_i = sum_j c_ij (p_i - p_j),  c_ij = m_j 8 / (rho_i + rho_j)^2 F_ij.
inline double ppe_pair_coefficient(double mj, double rho_i, double rho_j, double F) {
  const double s = rho_i + rho_j;
  return 8.0 * mj * F / (s * s);
}

// The walls' impact condition (-ppe_wall_impact): the predicted velocity (fluid: u*, walls: their own;
// owned and ghost particles), the walls' unit normals into the fluid (owned), which fluid particles can
// impact (owned and ghost), and the projection's tau.
template <int D> struct WallImpact {
  const std::vector<Vector<D>>* velocity;
  const std::vector<Vector<D>>* normal;
  const std::vector<double>* surface;  // owned and ghost: nonzero on the fluid's surface particles
  double tau;
};

struct PpeRows {
  // This rank's rows split as MPIAIJ keeps them: the "diagonal" block of the columns this rank owns
  // (local column indices) and the "off-diagonal" rest (global indices). Row i is [di[i], di[i + 1]).
  // Columns are ascending within a row.
  std::vector<PetscInt> di, dj, oi, oj;
  std::vector<PetscScalar> da, oa;
  std::vector<double> rhs;  // right-hand side of wall rows (the body-force head), 0 elsewhere
  // Wall rows with no fluid in reach (p_w = 0, seen by nobody): the only rows of a closed domain's
  // matrix that a constant pressure does not satisfy, so they lie outside its null vector.
  std::vector<char> isolated;

  // Rows of the owned particles of P. Fluid rows hold the consistent Laplacian when `consistent`
  // holds its factors, else Cummins & Rudman's; wall and inlet rows hold the Adami extrapolation (with
  // wall_acceleration, per owned particle, where bodies move); rows flagged
  // in `dirichlet` hold only their diagonal (outlet rows their pressure, P.p, on the right-hand side).
  template <int D>
  void build(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, const Vector<D>& body_force,
             const std::vector<char>& dirichlet, const std::vector<LaplacianCorrection<D>>* consistent = nullptr,
             const SurfaceNodes<D>* nodes = nullptr, const WallImpact<D>* impact = nullptr,
             const std::vector<Vector<D>>* wall_acceleration = nullptr, const WallContinuation<D>* walls = nullptr);
  // Gives the rows' storage back (their capacity too).
  void release() { *this = PpeRows(); }

 private:
  template <int D> void lay_out(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                const std::vector<char>& dirichlet);
  template <int D> void add_pairs(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                  const Vector<D>& body_force, const std::vector<char>& dirichlet,
                                  const std::vector<LaplacianCorrection<D>>* consistent, const WallImpact<D>* impact,
                                  const std::vector<Vector<D>>* wall_acceleration, const WallContinuation<D>* walls);
  template <int D> void finish_rows(const Particles<D>& P, const Kernel<D>& K, const std::vector<char>& dirichlet,
                                    const std::vector<LaplacianCorrection<D>>* consistent,
                                    const SurfaceNodes<D>* nodes);
  std::vector<PetscInt> dlen_, olen_;  // entries filled per row
  std::vector<double> head_;           // wall rows: sum over fluid neighbours of W_wf rho_f head_wf
};

namespace detail {

// Sorts entries [begin, begin + length) by column and adds up repeated columns (periodic images of one
// particle); returns the new length.
inline PetscInt sort_and_merge(PetscInt* col, PetscScalar* val, PetscInt length,
                               std::vector<std::pair<PetscInt, PetscScalar>>& scratch) {
  scratch.clear();
  for (PetscInt k = 0; k < length; ++k) scratch.emplace_back(col[k], val[k]);
  std::sort(scratch.begin(), scratch.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  PetscInt out = -1;
  for (const auto& [c, v] : scratch) {
    if (out >= 0 && col[out] == c) val[out] += v;
    else col[++out] = c, val[out] = v;
  }
  return out + 1;
}

// Closes the gaps merging left at row ends (row r filled [ptr[r], ptr[r] + length[r])), in place.
inline void close_gaps(std::vector<PetscInt>& ptr, const std::vector<PetscInt>& length, std::vector<PetscInt>& col,
                       std::vector<PetscScalar>& val) {
  PetscInt out = 0;
  for (std::size_t r = 0; r + 1 < ptr.size(); ++r) {
    const PetscInt from = ptr[r];
    ptr[r] = out;
    for (PetscInt k = from; k < from + length[r]; ++k, ++out) col[out] = col[k], val[out] = val[k];
  }
  ptr.back() = out;
}

}  // namespace detail

namespace detail {

// Row i has an entry for neighbour j: fluid rows for every neighbour, wall rows for fluid ones,
// one-entry rows for none. A periodic image of i itself has none (p_i - p_i = 0).
template <int D> bool ppe_has_entry(const Particles<D>& P, const std::vector<char>& dirichlet, int i, int j) {
  if (P.gid[j] == P.gid[i]) return false;
  if (extrapolates_pressure(P.kind[i])) return P.kind[j] == kFluid;
  return !dirichlet[i];
}

// Whether particle j's column lies in this rank's diagonal block.
template <int D> bool owned_column(const Particles<D>& P, int j) {
  const PetscInt first = P.first_gid, end = first + static_cast<PetscInt>(P.n_owned);
  return P.gid[j] >= first && P.gid[j] < end;
}

}  // namespace detail

template <int D>
void PpeRows::build(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, const Vector<D>& body_force,
                    const std::vector<char>& dirichlet, const std::vector<LaplacianCorrection<D>>* consistent,
                    const SurfaceNodes<D>* nodes, const WallImpact<D>* impact,
                    const std::vector<Vector<D>>* wall_acceleration, const WallContinuation<D>* walls) {
  lay_out(P, nl, K, dirichlet);
  add_pairs(P, nl, K, body_force, dirichlet, consistent, impact, wall_acceleration, walls);
  finish_rows(P, K, dirichlet, consistent, nodes);
}

// Counts each row's entries, then lays the rows out: the diagonal comes first in its row until the
// rows are sorted.
template <int D> void PpeRows::lay_out(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                       const std::vector<char>& dirichlet) {
  const std::size_t n = P.n_owned;
  const PetscInt first = P.first_gid;
  dlen_.assign(n, 1), olen_.assign(n, 0);
  for_each_pair_index(P, nl, K, [&](int i, int j) {
    if (detail::ppe_has_entry(P, dirichlet, i, j)) ++(detail::owned_column(P, j) ? dlen_[i] : olen_[i]);
  });
  di.resize(n + 1), oi.resize(n + 1);
  di[0] = oi[0] = 0;
  for (std::size_t i = 0; i < n; ++i) di[i + 1] = di[i] + dlen_[i], oi[i + 1] = oi[i] + olen_[i];
  // One spare entry: PETSc is handed valid pointers even when a block is empty.
  dj.resize(di[n] + 1), da.resize(di[n] + 1), oj.resize(oi[n] + 1), oa.resize(oi[n] + 1);
  rhs.assign(n, 0.0), head_.assign(n, 0.0), isolated.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) dj[di[i]] = P.gid[i] - first, da[di[i]] = 0.0, dlen_[i] = 1, olen_[i] = 0;
}

// Fluid rows: c_ij off the diagonal, -sum_j c_ij on it; row i is div(grad p / rho)_i times -m_i.
// Wall rows keep their diagonal (the scale of a fluid row, from Cummins & Rudman's coefficients)
// and, for now, the kernel weights W_wf of their fluid neighbours.
template <int D> void PpeRows::add_pairs(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                         const Vector<D>& body_force, const std::vector<char>& dirichlet,
                                         const std::vector<LaplacianCorrection<D>>* consistent,
                                         const WallImpact<D>* impact, const std::vector<Vector<D>>* wall_acceleration,
                                         const WallContinuation<D>* walls) {
  const PetscInt first = P.first_gid;
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) {
    if (P.gid[j] == P.gid[i]) return;
    const double c = consistent && P.kind[i] == kFluid
                         ? -P.m[i] / P.rho[i] * consistent_laplacian_coefficient((*consistent)[i], P.m[j] / P.rho[j], g)
                         : P.m[i] * ppe_pair_coefficient(P.m[j], P.rho[i], P.rho[j], morris_factor(g, K.h()));
    da[di[i]] -= c;
    if (!detail::ppe_has_entry(P, dirichlet, i, j)) return;
    const double value = extrapolates_pressure(P.kind[i]) ? g.W : c;
    if (detail::owned_column(P, j)) dj[di[i] + dlen_[i]] = P.gid[j] - first, da[di[i] + dlen_[i]++] = value;
    else oj[oi[i] + olen_[i]] = P.gid[j], oa[oi[i] + olen_[i]++] = value;
    if (extrapolates_pressure(P.kind[i])) {
      // The fluid's pressure continued to the wall (the wall model's WallContinuation); a moving body's wall rows
      // take its acceleration, g - a_w (Adami et al. 2012).
      const Vector<D> g_eff = wall_acceleration ? Vector<D>(body_force - (*wall_acceleration)[i]) : body_force;
      double head =
          walls && !walls->normal.empty()
              ? walls->head(static_cast<std::size_t>(i), static_cast<std::size_t>(j), g_eff, g.rij, P.rho[j]) / P.rho[j]
              : g_eff.dot(g.rij);
      // A surface particle predicted to move towards the wall at u_n (beyond the closing kick's tau g,
      // which the hydrostatic head holds) needs the normal pressure gradient rho u_n / tau to stop.
      if (impact && (*impact->surface)[j] != 0.0) {
        const Vector<D>& n = (*impact->normal)[i];
        const double u_n = ((*impact->velocity)[j] - impact->tau * body_force - (*impact->velocity)[i]).dot(n);
        head += std::min(u_n, 0.0) * g.rij.dot(n) / impact->tau;
      }
      head_[i] += g.W * P.rho[j] * head;
    }
  });
}

// Each row finished by its kind (wall rows scaled and given their head, surface rows their node,
// Dirichlet rows their diagonal), then sorted by column with repeated columns merged.
template <int D>
void PpeRows::finish_rows(const Particles<D>& P, const Kernel<D>& K, const std::vector<char>& dirichlet,
                          const std::vector<LaplacianCorrection<D>>* consistent, const SurfaceNodes<D>* nodes) {
  auto surface_row = [&](int i) { return nodes && nodes->has(static_cast<std::size_t>(i)); };
  const std::ptrdiff_t rows = static_cast<std::ptrdiff_t>(P.n_owned);
  int merged = 0;  // some row had repeated columns
#pragma omp parallel reduction(| : merged)
  {
    std::vector<std::pair<PetscInt, PetscScalar>> scratch;
#pragma omp for schedule(static)
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
      const std::size_t i = static_cast<std::size_t>(r);
      PetscScalar* d = &da[di[i]];
      PetscScalar* o = &oa[oi[i]];
      const double diag = d[0];
      if (extrapolates_pressure(P.kind[i])) {
        // Adami et al. (2012), scaled like a fluid row: s (p_w - sum_f w_f p_f) = s sum_f w_f rho_f head_f
        double sumW = 0.0;
        for (PetscInt k = 1; k < dlen_[i]; ++k) sumW += d[k];
        for (PetscInt k = 0; k < olen_[i]; ++k) sumW += o[k];

        // No fluid in reach (or only at the support's edge, where W is 0): p_w = 0, seen by nobody.
        const double scale = sumW > 0.0 ? -diag / sumW : 0.0;
        for (PetscInt k = 1; k < dlen_[i]; ++k) d[k] *= scale;
        for (PetscInt k = 0; k < olen_[i]; ++k) o[k] *= scale;
        if (sumW > 0.0) rhs[i] = diag * head_[i] / sumW;
        else d[0] = 1.0, isolated[i] = 1;
      } else if (surface_row(i) && !dirichlet[i]) {
        // The node as one more neighbour (p_s = 0 adds nothing to the right-hand side).
        d[0] += consistent ? P.m[i] / P.rho[i] * surface_node_coefficient((*consistent)[i], *nodes, i)
                           : -P.m[i] * 2.0 * nodes->volume[i] / P.rho[i] * nodes->morris_factor(K.h());
      } else if (dirichlet[i]) {
        d[0] = diag > 0.0 ? diag : 1.0;
        if (P.kind[i] == kOutlet) rhs[i] = d[0] * P.p[i];  // an outlet holds its pressure
      }
      const PetscInt dn = detail::sort_and_merge(&dj[di[i]], d, dlen_[i], scratch);
      const PetscInt on = detail::sort_and_merge(&oj[oi[i]], o, olen_[i], scratch);
      merged |= dn < dlen_[i] || on < olen_[i];
      dlen_[i] = dn, olen_[i] = on;
    }
  }
  if (merged) detail::close_gaps(di, dlen_, dj, da), detail::close_gaps(oi, olen_, oj, oa);
}

}  // namespace sph
