#pragma once
// Per-step pruned neighbour lists for variable smoothing lengths. The shared Verlet list is built with
// the largest support in the scene (kappa h_max + skin), which is ~(h_max/h_min)^D times too long for
// the particles with small h (8x in a 1D Sod tube, 20x in a 2D one). Once per step, after the drift,
// this keeps for each owned i only the candidates j with
//   r_ij < reach(i, j) = max(reach_i, reach_j),   reach_k = margin * kappa * h_k,
// which holds every pair the gather (r < kappa h_i) and the symmetric force loop (r < kappa max(h_i, h_j))
// need as long as no smoothing length grows by more than the margin within the step: the solver checks
// that and prunes again otherwise. Same CSR layout and index order as NeighbourList.
#include <algorithm>
#include <vector>

#include "src/neighbours/compressed_rows.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/particles/particles.hpp"

namespace sph::compressible {

template <int D> class PrunedPairs {
 public:
  // h holds owned and ghost smoothing lengths (ghosts filled by the halo).
  void build(const Particles<D>& P, const NeighbourList<D>& nl, const std::vector<double>& h, double kappa,
             double margin) {
    const std::size_t n = P.n_owned;
    halo_ = nl.halo();
    reach_.resize(n);
    for (std::size_t i = 0; i < n; ++i) reach_[i] = margin * kappa * h[i];
    build_compressed_rows(n, offset_, index_, [&](std::size_t i, std::vector<int>& out) {
      for (const int* it = nl.begin(i); it != nl.end(i); ++it) {
        const int j = *it;
        const double reach = std::max(reach_[i], margin * kappa * h[j]);
        if ((P.x[i] - P.x[j]).squaredNorm() < reach * reach) out.push_back(j);
      }
    });
  }

  const int* begin(std::size_t i) const { return index_.data() + offset_[i]; }
  const int* end(std::size_t i) const { return index_.data() + offset_[i + 1]; }
  std::size_t size() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  std::size_t total() const { return index_.size(); }
  std::size_t count(std::size_t i) const { return offset_[i + 1] - offset_[i]; }
  // Radius within which i's list is complete.
  double reach(std::size_t i) const { return reach_[i]; }
  // The halo whose ghost slots the indices past the owned particles refer to (the full list's).
  const Halo<D>* halo() const { return halo_; }

 private:
  std::vector<std::size_t> offset_;
  std::vector<int> index_;
  std::vector<double> reach_;
  const Halo<D>* halo_ = nullptr;
};

}  // namespace sph::compressible
