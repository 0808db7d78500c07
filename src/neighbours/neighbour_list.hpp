#pragma once
// Fixed-radius neighbour lists from a nanoflann k-d tree, in compressed-row form.
// Queries are the owned particles; candidates are owned and ghost particles, so periodic images and
// (on several ranks) halo particles are found by the same plain Euclidean search.
#include <vector>

#include "src/core/types.hpp"

namespace sph {

template <int D> class Halo;

template <int D> class NeighbourList {
 public:
  // Lists, for each of the first n_query points, every other point closer than `radius`,
  // in increasing index order (deterministic loops, reproducible sums).
  void build(const std::vector<Vector<D>>& x, std::size_t n_query, double radius);
  // Drops the pairs (i, j) for which keep(i, j) is false, keeping the order of the rest.
  template <class Keep> void filter(Keep&& keep) {
    std::size_t out = 0;
    for (std::size_t i = 0; i + 1 < offset_.size(); ++i) {
      const std::size_t begin = offset_[i], end = offset_[i + 1];
      offset_[i] = out;
      for (std::size_t k = begin; k < end; ++k)
        if (keep(i, index_[k])) index_[out++] = index_[k];
    }
    if (!offset_.empty()) offset_.back() = out;
    index_.resize(out);
  }

  std::size_t size() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  const int* begin(std::size_t i) const { return index_.data() + offset_[i]; }
  const int* end(std::size_t i) const { return index_.data() + offset_[i + 1]; }
  std::size_t count(std::size_t i) const { return offset_[i + 1] - offset_[i]; }
  std::size_t total() const { return index_.size(); }
  double radius() const { return radius_; }
  // The halo whose ghost slots the indices past the owned particles refer to (null: a list built on
  // its own), so that a pair loop can check that those slots are fresh (ghost_check.hpp).
  const Halo<D>* halo() const { return halo_; }
  void set_halo(const Halo<D>* halo) { halo_ = halo; }

 private:
  std::vector<std::size_t> offset_;
  std::vector<int> index_;
  double radius_ = 0.0;
  const Halo<D>* halo_ = nullptr;
};

}  // namespace sph
