#pragma once
// The one neighbour loop of the code. Schemes supply the physics of a single i-j pair as a callable;
// the loop supplies the pair geometry (separation, kernel value and gradient), evaluated at current
// positions (lists may hold skin neighbours outside the support: those are skipped here).
#include <algorithm>
#include <cmath>
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/neighbours/ghost_check.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D> struct PairGeometry {
  Vector<D> rij;    // x_i - x_j
  double r;         // |x_i - x_j| > 0
  double W;         // W(r, h)
  double dWdr;      // dW/dr
  double dWdr_r;    // dW/dr / r (< 0): the radial factor of the gradient, divided once per pair
  Vector<D> gradW;  // grad_i W_ij = dWdr_r r_ij
};

// Whether a listed neighbour at squared distance r2 forms a pair: inside the support (rc2 its square)
// and not at the particle's own position. Both tests are evaluated (&, not &&): no branch.
inline bool in_support(double r2, double rc2) { return (r2 < rc2) & (r2 != 0.0); }

// Which owned particles a loop visits. A wall particle's own values are extrapolated from the fluid
// (Adami et al. 2012) or prescribed, never computed from an operator, so a loop whose results only
// fluid particles read can skip the walls' pairs: in a 3D cavity with four wall layers the walls are
// two thirds of the particles. Skipped particles keep the loop's zero. Rows::Walls: the walls' own
// loops (their extrapolation stencils), the inlets' buffers' too (extrapolates_pressure).
enum class Rows { All, Fluid, Walls };

inline bool visited(Rows rows, int kind) {
  return rows == Rows::All || (rows == Rows::Fluid ? kind == kFluid : extrapolates_pressure(kind));
}

namespace detail {
// One particle's pairs, gathered before the physics sees them: the separations of the listed
// neighbours inside the support, then their distances and kernel values in loops of their own. The
// square root, the kernel and the division of each pair are then independent of the physics that
// consumes them, and the compiler can vectorise those loops (one pair at a time, the physics waited on
// each pair's square root and divisions). One scratch per thread, so that a particle allocates nothing.
template <int D> struct PairBatch {
  std::vector<int> j;
  std::vector<Vector<D>> rij;
  std::vector<double> r, W, dWdr, dWdr_r;
  std::size_t size = 0;  // pairs gathered (the vectors keep the largest list's length)

  // Fills the batch with i's pairs (0 < r < support, rc2 the support's square), in list order.
  void gather(std::size_t i, const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, double rc2) {
    const std::size_t listed = nl.count(i);
    if (j.size() < listed)
      j.resize(listed), rij.resize(listed), r.resize(listed), W.resize(listed), dWdr.resize(listed),
          dWdr_r.resize(listed);
    const Vector<D> xi = P.x[i];
    std::size_t n = 0;
    // Every candidate is written and only a pair advances n: a branch on the support test was
    // mispredicted for the third of the list that lies in the skin. The destinations are local
    // pointers: through the vectors, each store could alias their data pointers, which were then
    // reloaded at every candidate.
    const Vector<D>* const x = P.x.data();
    int* const jd = j.data();
    Vector<D>* const rd = rij.data();
    double* const r2d = r.data();
    for (const int *it = nl.begin(i), *end = nl.end(i); it != end; ++it) {
      const int k = *it;
      const Vector<D> d = xi - x[k];
      const double r2 = d.squaredNorm();
      jd[n] = k, rd[n] = d, r2d[n] = r2;
      n += static_cast<std::size_t>(in_support(r2, rc2));
    }
    size = n;
    for (std::size_t k = 0; k < n; ++k) r[k] = std::sqrt(r[k]);
    K.evaluate(n, r.data(), W.data(), dWdr.data());
    for (std::size_t k = 0; k < n; ++k) dWdr_r[k] = dWdr[k] / r[k];
  }
};

// The thread's batch, shared by every loop of dimension D, and whether a loop is filling it now.
template <int D> struct PairBatchSlot {
  PairBatch<D> batch;
  bool in_use = false;
};
template <int D> PairBatchSlot<D>& pair_batch_slot() {
  thread_local PairBatchSlot<D> slot;
  return slot;
}

template <int D, class PairFn>
[[gnu::flatten]] inline void visit_batch(std::size_t i, const PairBatch<D>& b, PairFn& f) {
  PairGeometry<D> g;
  for (std::size_t k = 0; k < b.size; ++k) {
    g.rij = b.rij[k];
    g.r = b.r[k];
    g.W = b.W[k];
    g.dWdr = b.dWdr[k];
    g.dWdr_r = b.dWdr_r[k];
    g.gradW = g.dWdr_r * g.rij;
    f(static_cast<int>(i), b.j[k], g);
  }
}

// f(i, j, geometry) for the neighbours j of one particle i, in list order. A pair function that visits
// another particle's pairs gets a batch of its own (the thread's batch is in use).
template <int D, class PairFn> inline void pairs_of(std::size_t i, const Particles<D>& P, const NeighbourList<D>& nl,
                                                    const Kernel<D>& K, double rc2, PairFn& f) {
  PairBatchSlot<D>& slot = pair_batch_slot<D>();
  PairBatch<D>& batch = slot.batch;
  bool& in_use = slot.in_use;
  if (in_use) {
    PairBatch<D> own;
    own.gather(i, P, nl, K, rc2);
    visit_batch(i, own, f);
    return;
  }
  struct Lease {
    bool& flag;
    explicit Lease(bool& f) : flag(f) { flag = true; }
    ~Lease() { flag = false; }
  } lease(in_use);
  batch.gather(i, P, nl, K, rc2);
  visit_batch(i, batch, f);
}
}  // namespace detail

// f(i, j, geometry) for every owned particle i and neighbour j with 0 < r_ij < support, with the
// particles i shared among OpenMP threads. Contract: f writes only to entries of i (it may read
// anything) and does not throw. Each i's pairs still run in list order on one thread, so every sum
// is bitwise the same on any thread count.
template <int D, class PairFn> void for_each_pair(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                                  PairFn&& f, Rows rows = Rows::All, CallSite at = CallSite()) {
  check_particle_ghosts(P, nl, at);
  const double rc2 = K.support_radius() * K.support_radius();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(P.n_owned);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    if (visited(rows, P.kind[i])) detail::pairs_of(static_cast<std::size_t>(i), P, nl, K, rc2, f);
}

// f(i, visit_pairs) for every owned particle i, threaded like for_each_pair, where visit_pairs(pf) runs
// pf(i, j, geometry) over i's pairs in list order (as often as f likes): for sums that live only as
// long as one particle's computation (moment matrices solved on the spot), kept in f's locals.
template <int D, class ParticleFn> void for_each_particle_pairs(const Particles<D>& P, const NeighbourList<D>& nl,
                                                                const Kernel<D>& K, ParticleFn&& f,
                                                                Rows rows = Rows::All, CallSite at = CallSite()) {
  check_particle_ghosts(P, nl, at);
  const double rc2 = K.support_radius() * K.support_radius();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(P.n_owned);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    if (!visited(rows, P.kind[ii])) continue;
    f(ii, [&](auto&& pair_fn) { detail::pairs_of(ii, P, nl, K, rc2, pair_fn); });
  }
}

// Per-particle sums: out[i] = zero + the f(sum, i, j, geometry) contributions of i's pairs, in list
// order, threaded like for_each_pair. The sum lives in a local while i's pairs are visited, so it stays
// in registers instead of being stored to out[i] at every pair (docs/performance.md, "Design
// measurements"). Acc may be a struct of several sums.
template <int D, class Acc, class SumFn>
std::vector<Acc> sum_over_pairs(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, const Acc& zero,
                                SumFn&& f, Rows rows = Rows::All, CallSite at = CallSite()) {
  check_particle_ghosts(P, nl, at);
  std::vector<Acc> out(P.n_owned, zero);
  const double rc2 = K.support_radius() * K.support_radius();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(P.n_owned);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (!visited(rows, P.kind[static_cast<std::size_t>(i)])) continue;
    Acc sum = zero;
    auto add = [&](int ii, int j, const PairGeometry<D>& g) { f(sum, ii, j, g); };
    detail::pairs_of(static_cast<std::size_t>(i), P, nl, K, rc2, add);
    out[static_cast<std::size_t>(i)] = sum;
  }
  return out;
}

// f(i, j) for the same pairs, without evaluating the kernel (to count them), threaded like for_each_pair.
template <int D, class IndexFn> void for_each_pair_index(const Particles<D>& P, const NeighbourList<D>& nl,
                                                         const Kernel<D>& K, IndexFn&& f, CallSite at = CallSite()) {
  check_particle_ghosts(P, nl, at);
  const double rc2 = K.support_radius() * K.support_radius();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(P.n_owned);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    for (const int* it = nl.begin(i); it != nl.end(i); ++it)
      if (in_support((P.x[i] - P.x[*it]).squaredNorm(), rc2)) f(static_cast<int>(i), *it);
}

// The same pairs on one thread, i ascending: for callers that build output in order (matrix rows,
// compressed stencils) or write to shared state.
template <int D, class PairFn> void for_each_pair_in_order(const Particles<D>& P, const NeighbourList<D>& nl,
                                                           const Kernel<D>& K, PairFn&& f, Rows rows = Rows::All,
                                                           CallSite at = CallSite()) {
  check_particle_ghosts(P, nl, at);
  const double rc2 = K.support_radius() * K.support_radius();
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (visited(rows, P.kind[i])) detail::pairs_of(i, P, nl, K, rc2, f);
}

// ---------------------------------------------------------------------------------------------------
// Variable smoothing lengths: every particle k has its own kernel kernels[k] (the compressible
// solver's grad-h SPH). Lists (a NeighbourList, or any begin(i)/end(i) over neighbour indices) must
// hold every pair within the supports in use.

// For owned particle i: f(j, r_ij, r) for every neighbour j with 0 < r < support of K (i's own kernel),
// the "gather" view used by the density / smoothing-length iteration. Called once per particle, it
// checks no ghosts: its caller checks those it reads, once, before its loop.
template <int D, class List, class Fn> inline void for_each_gather_neighbour(const Particles<D>& P, const List& nl,
                                                                             std::size_t i, const Kernel<D>& K,
                                                                             Fn&& f) {
  const double rc2 = K.support_radius() * K.support_radius();
  for (const int* it = nl.begin(i); it != nl.end(i); ++it) {
    const int j = *it;
    const Vector<D> rij = P.x[i] - P.x[j];
    const double r2 = rij.squaredNorm();
    if (r2 >= rc2 || r2 == 0.0) continue;
    f(j, rij, std::sqrt(r2));
  }
}

// Geometry of a pair seen with both smoothing lengths: kernels and their radial derivatives at h_i and
// at h_j (each zero outside its own support).
template <int D> struct VariableHPair {
  Vector<D> rij;  // x_i - x_j
  double r;       // |r_ij| > 0
  double Wi, Wj, dWi, dWj;
  Vector<D> gradWi() const { return (dWi / r) * rij; }  // grad_i W(r_ij, h_i)
  Vector<D> gradWj() const { return (dWj / r) * rij; }  // grad_i W(r_ij, h_j)
  double dW_mean() const { return 0.5 * (dWi + dWj); }
  Vector<D> gradW_mean() const { return (dW_mean() / r) * rij; }  // symmetric in i, j
};

// f(i, j, pair) for every owned i and neighbour j within the larger of the two supports ("scatter +
// gather", what the symmetric force needs). kernels[k] is particle k's kernel (owned and ghosts).
template <int D, class List, class Fn> void for_each_variable_h_pair(const Particles<D>& P, const List& nl,
                                                                     const std::vector<Kernel<D>>& kernels, Fn&& f,
                                                                     CallSite at = CallSite()) {
  check_particle_ghosts(P, nl, at);
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(P.n_owned);
  // Threads share the particles i; f writes only to entries of i (as for sph::for_each_pair).
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    VariableHPair<D> g;
    const Kernel<D>& Ki = kernels[i];
    const double rci = Ki.support_radius();
    for (const int* it = nl.begin(i); it != nl.end(i); ++it) {
      const int j = *it;
      const Kernel<D>& Kj = kernels[j];
      const double rc = std::max(rci, Kj.support_radius());
      g.rij = P.x[i] - P.x[j];
      const double r2 = g.rij.squaredNorm();
      if (r2 >= rc * rc || r2 == 0.0) continue;
      g.r = std::sqrt(r2);
      g.Wi = Ki.W(g.r), g.dWi = Ki.dWdr(g.r);
      g.Wj = Kj.W(g.r), g.dWj = Kj.dWdr(g.r);
      f(static_cast<int>(i), j, g);
    }
  }
}

}  // namespace sph
