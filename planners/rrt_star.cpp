#include "planners/rrt_star.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

// nanoflann 1.4.3 copies a never-built tree's uninitialized bounding box when
// it sets up its sub-trees (harmless: a tree's box is computed when it is
// built, before any query reads it); GCC warns about that copy at -O2.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <nanoflann.hpp>
#pragma GCC diagnostic pop

#include "campo/random.hpp"

namespace campo {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("RRT*: " + message);
}

/// A tree node; its point is in a separate array (see NodeCloud).
struct Node {
  int parent = -1;
  double cost = 0.0;  ///< length of the tree path from the start
  std::vector<int> children;
  bool in_goal = false;  ///< within goal_radius_m of the goal
};

/// The cheapest node in the goal region (lowest id on ties), kept up to date
/// as nodes arrive and rewiring lowers costs, instead of a scan of every goal
/// node each iteration (which grows with the tree).
struct BestGoal {
  int id = -1;
  void consider(const std::vector<Node>& nodes, int k) {
    const double cost = nodes[static_cast<std::size_t>(k)].cost;
    if (id < 0) {
      id = k;
      return;
    }
    const double best = nodes[static_cast<std::size_t>(id)].cost;
    if (cost < best || (cost == best && k < id)) id = k;
  }
};

/// The nodes' points as nanoflann's dataset: a view of the array, no copy.
/// The points live apart from the rest of the nodes (16 bytes a node, not
/// 64) because nanoflann reads them in its leaf scans in an order unrelated
/// to the ids, where cache misses dominate the query time. Counts the coordinates nanoflann reads, which is its work:
/// two per distance it computes in a query, and the bounding boxes and splits
/// of the trees it rebuilds as nodes arrive.
struct NodeCloud {
  const std::vector<Eigen::Vector2d>& points;
  mutable std::uint64_t reads = 0;

  std::size_t kdtree_get_point_count() const { return points.size(); }
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
/// of the query, ties to the lower id, in a max-heap of (squared distance,
/// id) whose buffer is reused across queries. nanoflann's own KNNResultSet
/// keeps, among equal distances, the one found first, and once full it never
/// offers a point tied with the k-th (it offers only dist < worstDist()), so
/// which of two tied nodes is kept would depend on how the trees happen to be
/// built; RRT* breaks ties by the lower id, as its lattice and hand-written
/// k-d tree did.
class NearestWithin {
 public:
  using DistanceType = double;
  using IndexType = std::uint32_t;

  void reset(std::size_t k, double limit) {
    k_ = k;
    limit_ = limit;
    items_.clear();
    items_.reserve(k);
  }

  /// Called by nanoflann for a point nearer than worstDist().
  bool addPoint(double d2, IndexType id) {
    if (k_ == 0 || d2 > limit_) return true;
    const std::pair<double, int> item{d2, static_cast<int>(id)};
    if (items_.size() < k_) {
      items_.push_back(item);
      std::push_heap(items_.begin(), items_.end());
    } else if (item < items_.front()) {
      std::pop_heap(items_.begin(), items_.end());
      items_.back() = item;
      std::push_heap(items_.begin(), items_.end());
    }
    return true;  // search on
  }

  /// nanoflann offers a point only below this and searches a cell only when
  /// it may hold a point within it: a hair above the true bound (1e-9
  /// relative, at least one ulp), so that a point tied with the k-th still
  /// reaches addPoint, which decides by id, and that rounding in nanoflann's
  /// incremental cell distances cannot skip one. It costs a few more offers.
  double worstDist() const {
    if (k_ == 0) return -1.0;
    const double bound = items_.size() < k_ ? limit_ : std::min(limit_, items_.front().first);
    return bound * (1.0 + 1e-9) + std::numeric_limits<double>::denorm_min();
  }
  bool full() const { return items_.size() == k_; }
  std::size_t size() const { return items_.size(); }
  const std::vector<std::pair<double, int>>& items() const { return items_; }

 private:
  std::size_t k_ = 0;
  double limit_ = 0.0;
  std::vector<std::pair<double, int>> items_;
};

/// The tree's points in nanoflann's dynamic k-d tree
/// (KDTreeSingleIndexDynamicAdaptor, libnanoflann-dev): the logarithmic
/// method of Bentley & Saxe, static balanced trees of 1, 2, 4, ... points
/// merged and rebuilt like the digits of a binary counter as points arrive,
/// so an insertion costs O(log^2 n) amortized and a nearest or k-nearest
/// query visits O(log n) trees of O(log n) depth, whatever the map's extent
/// or the step; memory O(n). (The old lattice of step-sized buckets cost
/// (extent / step)^2 memory and, for a sample far from the tree, a scan of
/// every bucket between them; issue 16.)
class PointIndex {
 public:
  /// Indexes the points already in `points`; `max_points` bounds their
  /// number (nanoflann keeps log2(max_points) + 1 sub-trees).
  PointIndex(const std::vector<Eigen::Vector2d>& points, std::size_t max_points)
      : cloud_{points},
        index_(2, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize), std::max<std::size_t>(max_points, 1)) {
    build_reads_ = cloud_.reads;
  }
  PointIndex(const PointIndex&) = delete;  // nanoflann keeps a reference to cloud_
  PointIndex& operator=(const PointIndex&) = delete;

  /// Adds points[id]; ids must arrive in order 1, 2, ... (nanoflann numbers
  /// its points by arrival).
  void add(int id) {
    const std::uint64_t before = cloud_.reads;
    index_.addPoints(static_cast<std::uint32_t>(id), static_cast<std::uint32_t>(id));
    build_reads_ += cloud_.reads - before;
  }

  /// Nearest point to q, lowest id on ties; -1 when empty.
  int nearest(const Eigen::Vector2d& q) {
    search(q, 1, std::numeric_limits<double>::infinity());
    return result_.size() == 0 ? -1 : result_.items().front().second;
  }

  /// The at most `k` nearest points within `radius` of q (by distance, then
  /// lower id), into `out` in increasing id order.
  void nearest_within(const Eigen::Vector2d& q, double radius, std::size_t k, std::vector<int>& out) {
    search(q, k, radius * radius);
    out.clear();
    for (const auto& item : result_.items()) out.push_back(item.second);
    std::sort(out.begin(), out.end());
  }

  /// Coordinates nanoflann read in queries (two per distance) and in building.
  std::uint64_t query_reads() const { return cloud_.reads - build_reads_; }
  std::uint64_t build_reads() const { return build_reads_; }

 private:
  using Index = nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, NodeCloud>, NodeCloud, 2>;
  /// nanoflann's default: leaves of up to 10 points are scanned, not split.
  static constexpr std::size_t kLeafSize = 10;

  void search(const Eigen::Vector2d& q, std::size_t k, double limit) {
    result_.reset(k, limit);
    index_.findNeighbors(result_, q.data(), nanoflann::SearchParams());
  }

  NodeCloud cloud_;
  Index index_;
  NearestWithin result_;
  std::uint64_t build_reads_ = 0;
};

/// Moves node `id` under `parent` at `cost`, shifting its subtree's costs alike.
void reparent(std::vector<Node>& nodes, int id, int parent, double cost, BestGoal& best_goal) {
  Node& node = nodes[static_cast<std::size_t>(id)];
  auto& siblings = nodes[static_cast<std::size_t>(node.parent)].children;
  siblings.erase(std::find(siblings.begin(), siblings.end(), id));
  node.parent = parent;
  nodes[static_cast<std::size_t>(parent)].children.push_back(id);
  const double delta = cost - node.cost;
  std::vector<int> stack{id};
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    nodes[static_cast<std::size_t>(k)].cost += delta;
    if (nodes[static_cast<std::size_t>(k)].in_goal) best_goal.consider(nodes, k);
    for (const int child : nodes[static_cast<std::size_t>(k)].children) stack.push_back(child);
  }
}

double free_area_m2(const OccupancyGrid& grid) {
  const auto free = std::count(grid.occupied.begin(), grid.occupied.end(), 0);
  return static_cast<double>(free) * grid.resolution_m * grid.resolution_m;
}

}  // namespace

std::size_t max_neighbours(std::size_t n) {
  return static_cast<std::size_t>(std::ceil(kNeighboursPerLogNode * std::log(static_cast<double>(std::max<std::size_t>(n, 2)))));
}

void validate(const RrtStarConfig& c) {
  require(c.step_m >= kMinStepM && c.step_m <= kMaxLengthM, "step must be in [0.001, 1000000] m");
  require(c.rewire_radius_m >= 0.0 && c.rewire_radius_m <= kMaxLengthM, "rewire_radius must be in [0, 1000000] m");
  require(c.rewire_gamma_m >= 0.0 && c.rewire_gamma_m <= kMaxLengthM, "rewire_gamma must be in [0, 1000000] m");
  require(std::isfinite(c.goal_radius_m) && c.goal_radius_m > 0.0, "goal_radius must be finite and > 0");
  require(c.goal_bias >= 0.0 && c.goal_bias <= 1.0, "goal_bias must be in [0, 1]");
  require(c.max_iterations >= 0 && c.max_iterations <= 10'000'000,
          "max_iterations must be in [0, 10000000], got " + std::to_string(c.max_iterations));
}

std::string_view to_string(RrtStarStatus status) {
  switch (status) {
    case RrtStarStatus::solved:
      return "solved";
    case RrtStarStatus::no_solution:
      return "no_solution";
    case RrtStarStatus::invalid_start:
      return "invalid_start";
    case RrtStarStatus::invalid_goal:
      return "invalid_goal";
  }
  return "unknown";
}

RrtStarResult rrt_star(const OccupancyGrid& grid, const Eigen::Vector2d& start_m, const Eigen::Vector2d& goal_m,
                       const RrtStarConfig& config) {
  validate(config);
  RrtStarResult result;
  if (!start_m.allFinite() || grid.is_occupied(start_m)) {
    result.status = RrtStarStatus::invalid_start;
    return result;
  }
  if (!goal_m.allFinite() || grid.is_occupied(goal_m)) {
    result.status = RrtStarStatus::invalid_goal;
    return result;
  }
  std::vector<Node> nodes{{-1, 0.0, {}, false}};
  std::vector<Eigen::Vector2d> points{start_m};  ///< points[i] of nodes[i]
  if ((start_m - goal_m).norm() <= config.goal_radius_m) {
    result.status = RrtStarStatus::solved;
    result.path_m = {start_m};
    result.cost_m = 0.0;
    result.first_solution_iteration = 0;
    result.nodes = 1;
    return result;
  }

  const double gamma =
      config.rewire_gamma_m > 0.0 ? config.rewire_gamma_m : 2.0 * std::sqrt(1.5 * free_area_m2(grid) / std::numbers::pi);
  const auto rewire_radius = [&](std::size_t n) {
    if (config.rewire_radius_m > 0.0) return config.rewire_radius_m;
    const double count = static_cast<double>(n);
    return std::min(gamma * std::sqrt(std::log(count) / count), config.step_m);
  };
  // Samples lie in the grid, so no edge is longer than its diagonal: a step
  // beyond it changes nothing.
  const Eigen::Vector2d extent = grid.resolution_m * Eigen::Vector2d(grid.cols, grid.rows);
  const double step_m = std::min(config.step_m, extent.norm());
  PointIndex index(points, static_cast<std::size_t>(config.max_iterations) + 1);
  std::vector<int> near;  // reused: no allocation per iteration once grown
  Rng rng(config.seed);
  BestGoal best_goal;
  RrtStarWork& work = result.work;
  std::int64_t cells = 0;
  const auto segment_free = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    ++work.segment_checks;
    return grid.segment_free(a, b, &cells);
  };
  result.best_cost_by_iteration.reserve(static_cast<std::size_t>(config.max_iterations));

  for (int iteration = 1; iteration <= config.max_iterations; ++iteration) {
    const std::int64_t cells_before = cells;
    const Eigen::Vector2d sample = rng.bernoulli(config.goal_bias)
                                       ? goal_m
                                       : Eigen::Vector2d(grid.origin_m.x() + extent.x() * rng.uniform01(),
                                                         grid.origin_m.y() + extent.y() * rng.uniform01());
    const int nearest = index.nearest(sample);
    const Eigen::Vector2d from = points[static_cast<std::size_t>(nearest)];
    const double distance = (sample - from).norm();
    const Eigen::Vector2d point = distance > step_m ? Eigen::Vector2d(from + (sample - from) * (step_m / distance)) : sample;
    if (distance > 1e-12 && segment_free(from, point)) {
      // Connect through the cheapest free neighbour (the nearest node at worst):
      // the k(n) nearest within the rewiring radius.
      index.nearest_within(point, rewire_radius(nodes.size() + 1), max_neighbours(nodes.size() + 1), near);
      work.max_neighbours = std::max(work.max_neighbours, near.size());
      int parent = nearest;
      double cost = nodes[static_cast<std::size_t>(nearest)].cost + (point - from).norm();
      for (const int j : near) {
        const Eigen::Vector2d& at = points[static_cast<std::size_t>(j)];
        const double via = nodes[static_cast<std::size_t>(j)].cost + (point - at).norm();
        if (via < cost && segment_free(at, point)) {
          parent = j;
          cost = via;
        }
      }
      const int id = static_cast<int>(nodes.size());
      const bool in_goal = (point - goal_m).norm() <= config.goal_radius_m;
      nodes.push_back({parent, cost, {}, in_goal});
      points.push_back(point);
      nodes[static_cast<std::size_t>(parent)].children.push_back(id);
      index.add(id);
      // Rewire: neighbours that are cheaper to reach through the new node.
      for (const int j : near) {
        if (j == parent) continue;
        const Eigen::Vector2d& at = points[static_cast<std::size_t>(j)];
        const double via = cost + (at - point).norm();
        if (via < nodes[static_cast<std::size_t>(j)].cost && segment_free(point, at)) reparent(nodes, j, id, via, best_goal);
      }
      if (in_goal) {
        best_goal.consider(nodes, id);
        if (result.first_solution_iteration < 0) result.first_solution_iteration = iteration;
      }
    }
    work.cells_checked += static_cast<std::uint64_t>(cells - cells_before);
    work.max_cells_per_iteration = std::max(work.max_cells_per_iteration, static_cast<std::uint64_t>(cells - cells_before));
    result.best_cost_by_iteration.push_back(best_goal.id < 0 ? std::numeric_limits<double>::infinity()
                                                             : nodes[static_cast<std::size_t>(best_goal.id)].cost);
  }

  work.index_query_reads = index.query_reads();
  work.index_build_reads = index.build_reads();
  result.iterations = config.max_iterations;
  result.nodes = nodes.size();
  if (best_goal.id < 0) return result;
  result.status = RrtStarStatus::solved;
  result.cost_m = nodes[static_cast<std::size_t>(best_goal.id)].cost;
  for (int k = best_goal.id; k >= 0; k = nodes[static_cast<std::size_t>(k)].parent) {
    result.path_m.push_back(points[static_cast<std::size_t>(k)]);
  }
  std::reverse(result.path_m.begin(), result.path_m.end());
  return result;
}

OccupancyGrid to_occupancy_grid(const grid::MovingAiMap& map) {
  OccupancyGrid grid;
  grid.cols = map.width;
  grid.rows = map.height;
  grid.resolution_m = 1.0;
  grid.origin_m = Eigen::Vector2d::Zero();
  grid.occupied.resize(static_cast<std::size_t>(map.width) * map.height);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      grid.occupied[static_cast<std::size_t>(map.height - 1 - y) * map.width + x] = map.is_passable(x, y) ? 0 : 1;
    }
  }
  return grid;
}

Eigen::Vector2d movingai_cell_centre(const grid::MovingAiMap& map, const grid::Cell& cell) {
  return {cell.x + 0.5, map.height - 1 - cell.y + 0.5};
}

}  // namespace campo
