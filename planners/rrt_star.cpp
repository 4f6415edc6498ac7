#include "planners/rrt_star.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <stdexcept>
#include <string>

#include "sim/random.hpp"

namespace campo {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("RRT*: " + message);
}

struct Node {
  Eigen::Vector2d point;
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

/// The tree's points in a k-d tree kept by the logarithmic method (Bentley &
/// Saxe): static balanced trees of 1, 2, 4, ... points, merged and rebuilt
/// like the digits of a binary counter as points arrive. Nearest and
/// k-nearest queries cost O(log^2 n) node visits whatever the map's extent
/// or the step, and the memory is O(n): the old lattice of step-sized
/// buckets cost (extent / step)^2 memory and, for a sample far from the
/// tree, a scan of every bucket between them (issue 16). Ties are broken by
/// the lower id, so the answers do not depend on how the trees are built.
class PointIndex {
 public:
  explicit PointIndex(const std::vector<Node>& nodes) : nodes_(nodes) {}

  void add(int id) {
    std::vector<int> carry{id};
    for (std::size_t k = 0;; ++k) {
      if (k == trees_.size()) trees_.emplace_back();
      if (trees_[k].ids.empty()) {
        build(trees_[k], std::move(carry));
        return;
      }
      carry.insert(carry.end(), trees_[k].ids.begin(), trees_[k].ids.end());
      trees_[k] = {};
    }
  }

  /// Nearest point to q, lowest id on ties; -1 when empty.
  int nearest(const Eigen::Vector2d& q) {
    Best best(1);
    for (const Tree& tree : trees_) search(tree, 0, tree.ids.size(), q, kInf, best);
    return best.items.empty() ? -1 : best.items.front().second;
  }

  /// The at most `k` nearest points within `radius` of q (by distance, then
  /// lower id), in increasing id order.
  std::vector<int> nearest_within(const Eigen::Vector2d& q, double radius, std::size_t k) {
    Best best(k);
    for (const Tree& tree : trees_) search(tree, 0, tree.ids.size(), q, radius * radius, best);
    std::vector<int> out;
    out.reserve(best.items.size());
    for (const auto& item : best.items) out.push_back(item.second);
    std::sort(out.begin(), out.end());
    return out;
  }

  /// k-d tree nodes visited by the queries so far.
  std::uint64_t visits() const { return visits_; }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  /// A balanced k-d tree stored implicitly: the median of ids[lo, hi) sits
  /// at (lo + hi) / 2 and splits along axis[(lo + hi) / 2].
  struct Tree {
    std::vector<int> ids;
    std::vector<Eigen::Vector2d> points;  ///< points[i] of ids[i], copied for locality
    std::vector<std::uint8_t> axis;
  };
  /// Ranges this small are scanned, not split.
  static constexpr std::size_t kLeafSize = 8;

  /// The k best (squared distance, id) pairs so far, a max-heap.
  struct Best {
    explicit Best(std::size_t k) : k(k) {}
    std::size_t k;
    std::vector<std::pair<double, int>> items;
    /// Squared distance beyond which nothing can enter.
    double bound(double limit) const { return items.size() < k ? limit : std::min(limit, items.front().first); }
    void offer(double d2, int id) {
      if (k == 0) return;
      const std::pair<double, int> item{d2, id};
      if (items.size() < k) {
        items.push_back(item);
        std::push_heap(items.begin(), items.end());
      } else if (item < items.front()) {
        std::pop_heap(items.begin(), items.end());
        items.back() = item;
        std::push_heap(items.begin(), items.end());
      }
    }
  };

  const Eigen::Vector2d& point(int id) const { return nodes_[static_cast<std::size_t>(id)].point; }

  void build(Tree& tree, std::vector<int> ids) {
    tree.ids = std::move(ids);
    tree.axis.assign(tree.ids.size(), 0);
    build(tree, 0, tree.ids.size());
    tree.points.clear();
    tree.points.reserve(tree.ids.size());
    for (const int id : tree.ids) tree.points.push_back(point(id));
  }

  // Splits along the axis of the larger spread, so a long narrow map does not
  // waste the levels that split its short side.
  void build(Tree& tree, std::size_t lo, std::size_t hi) {
    if (hi - lo <= kLeafSize) return;
    Eigen::Vector2d min = point(tree.ids[lo]), max = min;
    for (std::size_t i = lo + 1; i < hi; ++i) {
      min = min.cwiseMin(point(tree.ids[i]));
      max = max.cwiseMax(point(tree.ids[i]));
    }
    const int axis = (max.x() - min.x()) >= (max.y() - min.y()) ? 0 : 1;
    const std::size_t mid = (lo + hi) / 2;
    std::nth_element(tree.ids.begin() + static_cast<std::ptrdiff_t>(lo), tree.ids.begin() + static_cast<std::ptrdiff_t>(mid),
                     tree.ids.begin() + static_cast<std::ptrdiff_t>(hi), [&](int a, int b) {
                       return std::pair(point(a)[axis], a) < std::pair(point(b)[axis], b);
                     });
    tree.axis[mid] = static_cast<std::uint8_t>(axis);
    build(tree, lo, mid);
    build(tree, mid + 1, hi);
  }

  // Offers the points of ids[lo, hi) within sqrt(limit) of q to `best`,
  // skipping halves that lie farther than the current bound.
  void search(const Tree& tree, std::size_t lo, std::size_t hi, const Eigen::Vector2d& q, double limit, Best& best) {
    if (hi - lo <= kLeafSize) {
      for (std::size_t i = lo; i < hi; ++i) {
        ++visits_;
        const double d2 = (tree.points[i] - q).squaredNorm();
        if (d2 <= limit) best.offer(d2, tree.ids[i]);
      }
      return;
    }
    ++visits_;
    const std::size_t mid = (lo + hi) / 2;
    const Eigen::Vector2d& p = tree.points[mid];
    const double d2 = (p - q).squaredNorm();
    if (d2 <= limit) best.offer(d2, tree.ids[mid]);
    const int axis = tree.axis[mid];
    const double offset = q[axis] - p[axis];
    // The near side first; the far side only when its slab can hold a point within the bound.
    const bool left_first = offset < 0.0;
    search(tree, left_first ? lo : mid + 1, left_first ? mid : hi, q, limit, best);
    if (offset * offset <= best.bound(limit)) search(tree, left_first ? mid + 1 : lo, left_first ? hi : mid, q, limit, best);
  }

  const std::vector<Node>& nodes_;
  std::vector<Tree> trees_;
  std::uint64_t visits_ = 0;
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
  std::vector<Node> nodes{{start_m, -1, 0.0, {}, false}};
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
  PointIndex index(nodes);
  index.add(0);
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
    const Eigen::Vector2d from = nodes[static_cast<std::size_t>(nearest)].point;
    const double distance = (sample - from).norm();
    const Eigen::Vector2d point = distance > step_m ? Eigen::Vector2d(from + (sample - from) * (step_m / distance)) : sample;
    if (distance > 1e-12 && segment_free(from, point)) {
      // Connect through the cheapest free neighbour (the nearest node at worst):
      // the k(n) nearest within the rewiring radius.
      const std::vector<int> near =
          index.nearest_within(point, rewire_radius(nodes.size() + 1), max_neighbours(nodes.size() + 1));
      work.max_neighbours = std::max(work.max_neighbours, near.size());
      int parent = nearest;
      double cost = nodes[static_cast<std::size_t>(nearest)].cost + (point - from).norm();
      for (const int j : near) {
        const Node& candidate = nodes[static_cast<std::size_t>(j)];
        const double via = candidate.cost + (point - candidate.point).norm();
        if (via < cost && segment_free(candidate.point, point)) {
          parent = j;
          cost = via;
        }
      }
      const int id = static_cast<int>(nodes.size());
      const bool in_goal = (point - goal_m).norm() <= config.goal_radius_m;
      nodes.push_back({point, parent, cost, {}, in_goal});
      nodes[static_cast<std::size_t>(parent)].children.push_back(id);
      index.add(id);
      // Rewire: neighbours that are cheaper to reach through the new node.
      for (const int j : near) {
        if (j == parent) continue;
        const Node& neighbour = nodes[static_cast<std::size_t>(j)];
        const double via = cost + (neighbour.point - point).norm();
        if (via < neighbour.cost && segment_free(point, neighbour.point)) reparent(nodes, j, id, via, best_goal);
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

  work.index_visits = index.visits();
  result.iterations = config.max_iterations;
  result.nodes = nodes.size();
  if (best_goal.id < 0) return result;
  result.status = RrtStarStatus::solved;
  result.cost_m = nodes[static_cast<std::size_t>(best_goal.id)].cost;
  for (int k = best_goal.id; k >= 0; k = nodes[static_cast<std::size_t>(k)].parent) {
    result.path_m.push_back(nodes[static_cast<std::size_t>(k)].point);
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
