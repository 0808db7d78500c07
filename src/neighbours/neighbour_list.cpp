#include "src/neighbours/neighbour_list.hpp"

#include <algorithm>
#include <nanoflann.hpp>

#include "src/neighbours/compressed_rows.hpp"

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

  const double r2 = radius * radius;  // L2 adaptors compare squared distances
  const nanoflann::SearchParams params(32, 0.0, false);
  build_compressed_rows(n_query, offset_, index_, [&](std::size_t i, std::vector<int>& out) {
    thread_local std::vector<std::pair<uint32_t, double>> found;
    found.clear();
    tree.radiusSearch(x[i].data(), r2, found, params);
    const std::size_t start = out.size();
    for (const auto& f : found)
      if (f.first != i && f.second < r2) out.push_back(static_cast<int>(f.first));
    std::sort(out.begin() + start, out.end());
  });
}

template class NeighbourList<1>;
template class NeighbourList<2>;
template class NeighbourList<3>;

}  // namespace sph
