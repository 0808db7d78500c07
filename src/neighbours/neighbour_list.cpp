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

// The query points are searched a run of consecutive points at a time: one tree search around the
// run's bounding box, its radius widened by the box's half-diagonal, finds every point within `radius`
// of any point of the run, and each point of the run then keeps the candidates within `radius` by a
// distance test. The points are ordered along a space-filling curve (partition_along_curve), so a run
// is a compact patch and the candidates are mostly the points' own neighbours: one tree descent for up
// to kMaxRun points instead of one each. A run ends where its box would grow beyond the search radius,
// so scattered points (an unordered start) fall back to short runs, down to one point, not to long
// candidate lists. The lists are exact whatever the runs are: the same neighbours in the same (index)
// order, in about half the time of a search per point or less (docs/performance.md, "Design measurements").
template <int D> void NeighbourList<D>::build(const std::vector<Vector<D>>& x, std::size_t n_query, double radius) {
  using Cloud = PointCloud<D>;
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, D, uint32_t>;
  constexpr std::size_t kMaxRun = 32;
  radius_ = radius;
  Cloud cloud{x};
  Tree tree(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));

  const double r2 = radius * radius;
  const nanoflann::SearchParams params(32, 0.0, false);
  build_compressed_rows_per_thread(n_query, offset_, index_, [&] {
    // Where the thread's current run ends, and the run's candidates in increasing index order.
    return [&, run_end = std::size_t(0), candidates = std::vector<int>(),
            found = std::vector<std::pair<uint32_t, double>>()](std::size_t i, std::vector<int>& out) mutable {
      if (i >= run_end) {
        Vector<D> lo = x[i], hi = x[i];
        std::size_t k = i + 1;
        for (; k < n_query && k - i < kMaxRun; ++k) {
          const Vector<D> lo_k = lo.cwiseMin(x[k]), hi_k = hi.cwiseMax(x[k]);
          if ((hi_k - lo_k).squaredNorm() > 4.0 * r2) break;
          lo = lo_k, hi = hi_k;
        }
        run_end = k;
        const Vector<D> centre = 0.5 * (lo + hi);
        // Every point within `radius` of a point of the run lies within radius + half-diagonal of the
        // centre; the margin covers the rounding of the distances the tree compares.
        const double reach = (radius + 0.5 * (hi - lo).norm()) * (1.0 + 1e-12);
        found.clear();
        tree.radiusSearch(centre.data(), reach * reach, found, params);
        candidates.resize(found.size());
        for (std::size_t c = 0; c < found.size(); ++c) candidates[c] = static_cast<int>(found[c].first);
        std::sort(candidates.begin(), candidates.end());
      }
      // Every candidate is written and only a neighbour advances the end (no branch to mispredict).
      const std::size_t start = out.size();
      out.resize(start + candidates.size());
      int* const dst = out.data() + start;
      const Vector<D> xi = x[i];
      const Vector<D>* const xd = x.data();
      std::size_t n = 0;
      for (const int j : candidates) {
        dst[n] = j;
        n += static_cast<std::size_t>((static_cast<std::size_t>(j) != i) & ((xi - xd[j]).squaredNorm() < r2));
      }
      out.resize(start + n);
    };
  });
}

template class NeighbourList<1>;
template class NeighbourList<2>;
template class NeighbourList<3>;

}  // namespace sph
