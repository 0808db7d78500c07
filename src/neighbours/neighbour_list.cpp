#include "src/neighbours/neighbour_list.hpp"

#include <algorithm>
#include <nanoflann.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sph {

namespace {
// nanoflann dataset adaptor over a vector of positions.
template <int D> struct PointCloud {
  const std::vector<Vector<D>>& pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return pts[i][dim]; }
  template <class BBox> bool kdtree_get_bbox(BBox&) const { return false; }
};
}  // namespace

template <int D>
void NeighbourList<D>::build(const std::vector<Vector<D>>& x, std::size_t n_query, double radius) {
  using Cloud = PointCloud<D>;
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, D,
                                                   uint32_t>;
  radius_ = radius;
  Cloud cloud{x};
  Tree tree(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));

  // Each thread searches a contiguous block of query points into its own buffer; the blocks are then
  // joined in order, so the lists are the same on any thread count.
  offset_.assign(n_query + 1, 0);
  std::vector<std::vector<int>> block_index;
  const double r2 = radius * radius;  // L2 adaptors compare squared distances
#pragma omp parallel
  {
    int thread = 0, threads = 1;
#ifdef _OPENMP
    thread = omp_get_thread_num();
    threads = omp_get_num_threads();
#endif
#pragma omp single
    block_index.resize(threads);  // implicit barrier: every thread sees the resized vector
    const std::size_t lo = n_query * thread / threads, hi = n_query * (thread + 1) / threads;
    std::vector<int>& index = block_index[thread];
    std::vector<std::pair<uint32_t, double>> found;
    const nanoflann::SearchParams params(32, 0.0, false);
    for (std::size_t i = lo; i < hi; ++i) {
      found.clear();
      tree.radiusSearch(x[i].data(), r2, found, params);
      const std::size_t start = index.size();
      for (const auto& f : found)
        if (f.first != i && f.second < r2) index.push_back(static_cast<int>(f.first));
      std::sort(index.begin() + start, index.end());
      offset_[i + 1] = index.size() - start;  // the count; prefix-summed below
    }
  }
  for (std::size_t i = 0; i < n_query; ++i) offset_[i + 1] += offset_[i];
  index_.clear();
  index_.reserve(offset_[n_query]);
  for (const auto& b : block_index) index_.insert(index_.end(), b.begin(), b.end());
}

template class NeighbourList<1>;
template class NeighbourList<2>;
template class NeighbourList<3>;

}  // namespace sph
