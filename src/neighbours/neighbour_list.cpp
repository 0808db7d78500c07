#include "src/neighbours/neighbour_list.hpp"

#include <algorithm>
#include <nanoflann.hpp>

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

  offset_.assign(n_query + 1, 0);
  index_.clear();
  std::vector<std::pair<uint32_t, double>> found;
  const nanoflann::SearchParams params(32, 0.0, false);
  const double r2 = radius * radius;  // L2 adaptors compare squared distances
  for (std::size_t i = 0; i < n_query; ++i) {
    found.clear();
    tree.radiusSearch(x[i].data(), r2, found, params);
    const std::size_t start = index_.size();
    for (const auto& f : found)
      if (f.first != i && f.second < r2) index_.push_back(static_cast<int>(f.first));
    std::sort(index_.begin() + start, index_.end());
    offset_[i + 1] = index_.size();
  }
}

template class NeighbourList<1>;
template class NeighbourList<2>;
template class NeighbourList<3>;

}  // namespace sph
