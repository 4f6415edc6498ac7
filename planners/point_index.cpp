#include "planners/point_index.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

// nanoflann 1.4.3 copies a never-built tree's uninitialized bounding box when
// it sets up its sub-trees (harmless: a tree's box is computed when it is
// built, before any query reads it); GCC warns about that copy at -O2.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <nanoflann.hpp>
#pragma GCC diagnostic pop
#else
#include <nanoflann.hpp>
#endif

namespace campo {
namespace {

/// The indexed points as nanoflann's dataset: a view of the caller's array,
/// no copy (RRT* keeps its points apart from the rest of its nodes, 16 bytes
/// a node, because nanoflann reads them in its leaf scans in an order
/// unrelated to the ids, where cache misses dominate the query time). Counts
/// the coordinates nanoflann reads, which is its work: two per distance it
/// computes in a query, and the bounding boxes and splits of the trees it
/// rebuilds as points arrive.
struct PointCloud {
  const std::vector<Eigen::Vector2d>& points;
  std::size_t indexed = 0;  ///< points[0, indexed) are in nanoflann's trees
  mutable std::uint64_t reads = 0;

  std::size_t kdtree_get_point_count() const { return indexed; }
  double kdtree_get_pt(std::size_t id, std::size_t axis) const {
    ++reads;
    return points[id][static_cast<Eigen::Index>(axis)];
  }
  /// No precomputed box: nanoflann computes it from the points.
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};

/// A nanoflann result set: the at most k nearest points within sqrt(limit)
/// of the query, ties to the lower id, as (squared distance, id) pairs in a
/// buffer reused across queries. nanoflann's own KNNResultSet keeps, among
/// equal distances, the one found first, and once full it never offers a
/// point tied with the k-th (it offers only dist < worstDist()), so which of
/// two tied nodes is kept would depend on how the trees happen to be built;
/// RRT* breaks ties by the lower id, as its lattice and hand-written k-d tree
/// did. The pairs stay unordered until k are in: the k(n) cap seldom binds,
/// so most near queries never pay for a heap.
class NearestWithin {
 public:
  using DistanceType = double;
  using IndexType = std::uint32_t;

  void reset(std::size_t k, double limit) {
    k_ = k;
    limit_ = limit;
    items_.clear();
    items_.reserve(k);
    update_worst();
  }

  /// Called by nanoflann for a point nearer than worstDist().
  bool addPoint(double d2, IndexType id) {
    if (d2 > limit_ || k_ == 0) return true;
    const std::pair<double, int> item{d2, static_cast<int>(id)};
    if (items_.size() < k_) {
      items_.push_back(item);
      if (items_.size() == k_) {
        std::make_heap(items_.begin(), items_.end());  // the k-th, items_.front(), bounds the rest
        update_worst();
      }
    } else if (item < items_.front()) {
      std::pop_heap(items_.begin(), items_.end());
      items_.back() = item;
      std::push_heap(items_.begin(), items_.end());
      update_worst();
    }
    return true;  // search on
  }

  /// nanoflann offers a point only below this and searches a cell only when
  /// it may hold a point within it: a hair above the true bound (1e-9
  /// relative, at least one ulp), so that a point tied with the k-th still
  /// reaches addPoint, which decides by id, and that rounding in nanoflann's
  /// incremental cell distances cannot skip one. It costs a few more offers.
  double worstDist() const { return worst_; }
  bool full() const { return items_.size() == k_; }
  std::size_t size() const { return items_.size(); }
  /// (squared distance, id), in no particular order.
  const std::vector<std::pair<double, int>>& items() const { return items_; }

 private:
  void update_worst() {
    if (k_ == 0) {
      worst_ = -1.0;
      return;
    }
    const double bound = items_.size() < k_ ? limit_ : std::min(limit_, items_.front().first);
    worst_ = bound * (1.0 + 1e-9) + std::numeric_limits<double>::denorm_min();
  }

  std::size_t k_ = 0;
  double limit_ = 0.0;
  double worst_ = -1.0;
  std::vector<std::pair<double, int>> items_;
};

}  // namespace

struct PointIndex::Impl {
  using Index =
      nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 2>;
  /// Leaves of up to this many points are scanned, not split (nanoflann's
  /// default is 10; 16 measured a little faster for RRT*, docs/PERFORMANCE.md).
  static constexpr std::size_t kLeafSize = 16;

  Impl(const std::vector<Eigen::Vector2d>& points, std::size_t capacity)
      : max_points(std::max<std::size_t>(capacity, 1)),
        cloud{points},
        index(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize), max_points) {}

  /// Throws unless the array holds at most max_points points: nanoflann
  /// would index a tree past the end of its table.
  void check_size() const {
    if (cloud.points.size() > max_points) {
      throw std::logic_error("PointIndex: " + std::to_string(cloud.points.size()) + " points, more than the " +
                             std::to_string(max_points) + " it was made for");
    }
  }

  /// Hands nanoflann every whole kBufferSize points of the buffer.
  void index_full_buffers() {
    while (cloud.points.size() - cloud.indexed >= kBufferSize) {
      const std::uint64_t before = cloud.reads;
      const auto first = static_cast<std::uint32_t>(cloud.indexed);
      cloud.indexed += kBufferSize;
      index.addPoints(first, static_cast<std::uint32_t>(cloud.indexed - 1));
      build_reads += cloud.reads - before;
    }
  }

  void search(const Eigen::Vector2d& q, std::size_t k, double limit) {
    result.reset(k, limit);
    // The largest tree first: the one most likely to hold the nearest points,
    // whose bound then lets nanoflann skip more of the smaller ones.
    const nanoflann::SearchParams params;
    const auto& trees = index.getAllIndices();
    if (cloud.indexed > 0) {
      for (auto tree = trees.rbegin(); tree != trees.rend(); ++tree) tree->findNeighbors(result, q.data(), params);
    }
    const std::vector<Eigen::Vector2d>& points = cloud.points;
    for (std::size_t id = cloud.indexed; id < points.size(); ++id) {
      // As nanoflann's L2_Simple_Adaptor computes it, so that ties tie here too.
      const double dx = q.x() - points[id].x();
      const double dy = q.y() - points[id].y();
      result.addPoint(dx * dx + dy * dy, static_cast<std::uint32_t>(id));
    }
    buffer_reads += 2 * (points.size() - cloud.indexed);
  }

  std::size_t max_points;
  PointCloud cloud;
  Index index;
  NearestWithin result;
  std::uint64_t build_reads = 0;   ///< of cloud.reads
  std::uint64_t buffer_reads = 0;  ///< coordinates read scanning the buffer
};

PointIndex::PointIndex(const std::vector<Eigen::Vector2d>& points, std::size_t max_points)
    : impl_(std::make_unique<Impl>(points, max_points)) {
  impl_->check_size();
  impl_->index_full_buffers();
}

PointIndex::~PointIndex() = default;

void PointIndex::add(int id) {
  if (id < 0 || static_cast<std::size_t>(id) + 1 != impl_->cloud.points.size()) {
    throw std::logic_error("PointIndex: point " + std::to_string(id) + " added, not the array's last, " +
                           std::to_string(impl_->cloud.points.size()) + " - 1");
  }
  impl_->check_size();
  impl_->index_full_buffers();
}

int PointIndex::nearest(const Eigen::Vector2d& q) {
  impl_->search(q, 1, std::numeric_limits<double>::infinity());
  return impl_->result.size() == 0 ? -1 : impl_->result.items().front().second;
}

void PointIndex::nearest_within(const Eigen::Vector2d& q, double radius_m, std::size_t k, std::vector<Neighbour>& out) {
  impl_->search(q, k, radius_m * radius_m);
  out.clear();
  for (const auto& [d2, id] : impl_->result.items()) out.push_back({id, std::sqrt(d2)});
  std::sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) { return a.id < b.id; });
}

std::uint64_t PointIndex::query_reads() const {
  return impl_->cloud.reads - impl_->build_reads + impl_->buffer_reads;
}

std::uint64_t PointIndex::build_reads() const { return impl_->build_reads; }

}  // namespace campo
