#pragma once
/// Nearest and near queries over a growing array of 2-D points, for RRT*'s
/// tree (planners/rrt_star.cpp): exact, ties to the lower id, and work
/// bounded by the number of points, never by the map's extent or the step.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace campo {

/// The newest points (fewer than kBufferSize) wait in a buffer that queries
/// scan point by point; every kBufferSize of them go together into
/// nanoflann's dynamic k-d tree (KDTreeSingleIndexDynamicAdaptor,
/// libnanoflann-dev): the logarithmic method of Bentley & Saxe, static
/// balanced trees of kBufferSize, 2 kBufferSize, 4 kBufferSize, ... points
/// merged and rebuilt like the digits of a binary counter, so an insertion
/// costs O(log^2 n) amortized and a query visits O(log n) trees of O(log n)
/// depth plus the buffer; memory O(n). The index views the caller's array,
/// which must outlive it and may only grow at its end.
class PointIndex {
 public:
  /// Points queries scan one by one before they go to nanoflann together:
  /// no tree smaller than this is ever built (one point at a time, every
  /// other insertion rebuilt a one-point tree, with its own allocations),
  /// and a query visits log2(kBufferSize) fewer trees.
  static constexpr std::size_t kBufferSize = 64;

  /// A point near a query point: its id (index in the array) and distance.
  struct Neighbour {
    int id = -1;
    double distance_m = 0.0;
  };

  /// Indexes the points already in `points`. At most `max_points` points in
  /// all (nanoflann keeps log2(max_points) + 1 trees; 0 counts as 1): more
  /// throw std::logic_error, here or in add.
  PointIndex(const std::vector<Eigen::Vector2d>& points, std::size_t max_points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;  // nanoflann keeps references into it
  PointIndex& operator=(const PointIndex&) = delete;

  /// Indexes points[id], the point just appended to the array (ids arrive in
  /// order: nanoflann numbers its points by arrival). Throws
  /// std::logic_error for any other id or past max_points.
  void add(int id);

  /// Nearest point to q, the lowest id among equally near ones; -1 when empty.
  int nearest(const Eigen::Vector2d& q);

  /// The at most `k` nearest points within `radius_m` of q (distance <=
  /// radius_m; nearer first, then the lower id), into `out` in increasing id
  /// order. `out` is reused: no allocation once it has grown.
  void nearest_within(const Eigen::Vector2d& q, double radius_m, std::size_t k, std::vector<Neighbour>& out);

  /// Work done, for bounds tests: point coordinates read in queries (two per
  /// distance computed, by nanoflann or in the buffer; the tree cells it
  /// steps through read none, but each leads to a leaf of at most 16 points
  /// whose distances count) ...
  std::uint64_t query_reads() const;
  /// ... and by nanoflann building its trees (bounding boxes, splits).
  std::uint64_t build_reads() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace campo
