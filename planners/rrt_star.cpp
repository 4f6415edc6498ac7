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

#include "campo/random.hpp"
#include "planners/point_index.hpp"

namespace campo {
namespace {

void rrt_star_requires(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("RRT*: " + message);
}

/// A tree node; its point is in a separate array (see PointIndex). Its
/// children form a list through first_child and next_sibling, so that a node
/// costs no allocation and 24 bytes: rewiring reads the costs of nodes all
/// over the array, and shifts whole subtrees.
struct Node {
  double cost = 0.0;  ///< length of the tree path from the start
  int parent = -1;
  int first_child = -1;
  int next_sibling = -1;  ///< the parent's next child
  bool in_goal = false;   ///< within goal_radius_m of the goal
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

/// The tree: nodes by id, the cheapest goal node, and a stack reused by reparent.
struct Tree {
  std::vector<Node> nodes;
  BestGoal best_goal;
  std::vector<int> stack;

  Node& operator[](int id) { return nodes[static_cast<std::size_t>(id)]; }

  /// Appends a node under `parent`; returns its id.
  int add(int parent, double cost, bool in_goal) {
    const int id = static_cast<int>(nodes.size());
    nodes.push_back({cost, parent, -1, -1, in_goal});
    if (parent >= 0) link(id, parent);
    if (in_goal) best_goal.consider(nodes, id);
    return id;
  }

  /// Moves node `id` under `parent` at `cost`, shifting its subtree's costs alike.
  void reparent(int id, int parent, double cost) {
    unlink(id);
    link(id, parent);
    const double delta = cost - (*this)[id].cost;
    stack.assign(1, id);
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      Node& node = (*this)[k];
      node.cost += delta;
      if (node.in_goal) best_goal.consider(nodes, k);
      for (int child = node.first_child; child >= 0; child = (*this)[child].next_sibling) stack.push_back(child);
    }
  }

 private:
  void link(int id, int parent) {
    (*this)[id].parent = parent;
    (*this)[id].next_sibling = (*this)[parent].first_child;
    (*this)[parent].first_child = id;
  }
  void unlink(int id) {
    int* slot = &(*this)[(*this)[id].parent].first_child;  // the link that leads to id
    while (*slot != id) slot = &(*this)[*slot].next_sibling;
    *slot = (*this)[id].next_sibling;
  }
};

double free_area_m2(const OccupancyGrid& grid) {
  const auto free = std::count(grid.occupied.begin(), grid.occupied.end(), 0);
  return static_cast<double>(free) * grid.resolution_m * grid.resolution_m;
}

}  // namespace

std::size_t max_neighbours(std::size_t n) {
  return static_cast<std::size_t>(std::ceil(kNeighboursPerLogNode * std::log(static_cast<double>(std::max<std::size_t>(n, 2)))));
}

void validate(const RrtStarConfig& c) {
  rrt_star_requires(c.step_m >= kMinStepM && c.step_m <= kMaxLengthM, "step must be in [0.001, 1000000] m");
  rrt_star_requires(c.rewire_radius_m >= 0.0 && c.rewire_radius_m <= kMaxLengthM, "rewire_radius must be in [0, 1000000] m");
  rrt_star_requires(c.rewire_gamma_m >= 0.0 && c.rewire_gamma_m <= kMaxLengthM, "rewire_gamma must be in [0, 1000000] m");
  rrt_star_requires(std::isfinite(c.goal_radius_m) && c.goal_radius_m > 0.0, "goal_radius must be finite and > 0");
  rrt_star_requires(c.goal_bias >= 0.0 && c.goal_bias <= 1.0, "goal_bias must be in [0, 1]");
  rrt_star_requires(c.max_iterations >= 0 && c.max_iterations <= 10'000'000,
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
                       const RrtStarConfig& config, const RrtStarProgress& progress) {
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
  Tree tree;
  tree.add(-1, 0.0, false);
  std::vector<Eigen::Vector2d> points{start_m};  ///< points[i] of tree[i]
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
  std::vector<PointIndex::Neighbour> near;  // reused: no allocation per iteration once grown
  Rng rng(config.seed);
  RrtStarWork& work = result.work;
  std::int64_t cells = 0;
  const auto segment_free = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    ++work.segment_checks;
    return grid.segment_free(a, b, &cells);
  };
  result.best_cost_by_iteration.reserve(static_cast<std::size_t>(config.max_iterations));

  int iterations = 0;
  for (int iteration = 1; iteration <= config.max_iterations; ++iteration) {
    if (progress && (iteration - 1) % kRrtStarProgressEvery == 0 && !progress(iteration - 1)) {
      result.stopped = true;
      break;
    }
    iterations = iteration;
    const std::int64_t cells_before = cells;
    Eigen::Vector2d sample = goal_m;
    if (!rng.bernoulli(config.goal_bias)) {
      // One draw per statement, y first: the order of a call's arguments is the compiler's (GCC,
      // which made the recorded results, evaluated them right to left; clang left to right).
      const double y = grid.origin_m.y() + extent.y() * rng.uniform01();
      const double x = grid.origin_m.x() + extent.x() * rng.uniform01();
      sample = Eigen::Vector2d(x, y);
    }
    const int nearest = index.nearest(sample);
    const Eigen::Vector2d from = points[static_cast<std::size_t>(nearest)];
    const double distance = (sample - from).norm();
    const Eigen::Vector2d point = distance > step_m ? Eigen::Vector2d(from + (sample - from) * (step_m / distance)) : sample;
    if (distance > 1e-12 && segment_free(from, point)) {
      // Connect through the cheapest free neighbour (the nearest node at worst):
      // the k(n) nearest within the rewiring radius.
      const std::size_t n = tree.nodes.size() + 1;
      index.nearest_within(point, rewire_radius(n), max_neighbours(n), near);
      work.max_neighbours = std::max(work.max_neighbours, near.size());
      int parent = nearest;
      double cost = tree[nearest].cost + (point - from).norm();
      for (const PointIndex::Neighbour& j : near) {
        const double via = tree[j.id].cost + j.distance_m;
        if (via < cost && segment_free(points[static_cast<std::size_t>(j.id)], point)) {
          parent = j.id;
          cost = via;
        }
      }
      const bool in_goal = (point - goal_m).norm() <= config.goal_radius_m;
      const int id = tree.add(parent, cost, in_goal);
      points.push_back(point);
      index.add(id);
      // Rewire: neighbours that are cheaper to reach through the new node.
      for (const PointIndex::Neighbour& j : near) {
        if (j.id == parent) continue;
        const double via = cost + j.distance_m;
        if (via < tree[j.id].cost && segment_free(point, points[static_cast<std::size_t>(j.id)])) {
          tree.reparent(j.id, id, via);
        }
      }
      if (in_goal && result.first_solution_iteration < 0) result.first_solution_iteration = iteration;
    }
    work.cells_checked += static_cast<std::uint64_t>(cells - cells_before);
    work.max_cells_per_iteration = std::max(work.max_cells_per_iteration, static_cast<std::uint64_t>(cells - cells_before));
    const int best = tree.best_goal.id;
    result.best_cost_by_iteration.push_back(best < 0 ? std::numeric_limits<double>::infinity() : tree[best].cost);
  }

  work.index_query_reads = index.query_reads();
  work.index_build_reads = index.build_reads();
  result.iterations = iterations;
  result.nodes = tree.nodes.size();
  if (tree.best_goal.id < 0) return result;
  result.status = RrtStarStatus::solved;
  result.cost_m = tree[tree.best_goal.id].cost;
  for (int k = tree.best_goal.id; k >= 0; k = tree[k].parent) {
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
