#include "planners/rrt_star.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
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
};

/// Nodes bucketed on a square lattice over the grid, for nearest and
/// radius queries without scanning the whole tree.
class NodeBuckets {
 public:
  NodeBuckets(const OccupancyGrid& grid, double bucket_m)
      : origin_(grid.origin_m),
        size_(bucket_m),
        cols_(std::max(1, static_cast<int>(std::ceil(grid.cols * grid.resolution_m / bucket_m)))),
        rows_(std::max(1, static_cast<int>(std::ceil(grid.rows * grid.resolution_m / bucket_m)))),
        buckets_(static_cast<std::size_t>(cols_) * rows_) {}

  void add(int id, const Eigen::Vector2d& p) {
    const Eigen::Vector2i b = bucket_of(p);
    buckets_[static_cast<std::size_t>(b.y()) * cols_ + b.x()].push_back(id);
  }

  /// Nearest node to q (lowest id on ties): rings of buckets outward until
  /// no unvisited bucket can hold anything nearer.
  int nearest(const Eigen::Vector2d& q, const std::vector<Node>& nodes) const {
    const Eigen::Vector2i c = bucket_of(q);
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    const int max_ring = std::max(cols_, rows_);
    for (int ring = 0; ring <= max_ring; ++ring) {
      for (int by = c.y() - ring; by <= c.y() + ring; ++by) {
        for (int bx = c.x() - ring; bx <= c.x() + ring; ++bx) {
          if (std::max(std::abs(bx - c.x()), std::abs(by - c.y())) != ring) continue;
          if (bx < 0 || by < 0 || bx >= cols_ || by >= rows_) continue;
          for (const int id : buckets_[static_cast<std::size_t>(by) * cols_ + bx]) {
            const double d2 = (nodes[static_cast<std::size_t>(id)].point - q).squaredNorm();
            if (d2 < best_d2 || (d2 == best_d2 && id < best)) {
              best_d2 = d2;
              best = id;
            }
          }
        }
      }
      // Buckets of the next ring are at least ring * size away.
      if (best >= 0 && std::sqrt(best_d2) <= ring * size_) break;
    }
    return best;
  }

  /// Nodes within radius of q, in increasing id order.
  std::vector<int> near(const Eigen::Vector2d& q, double radius, const std::vector<Node>& nodes) const {
    std::vector<int> out;
    const Eigen::Vector2i lo = bucket_of(q - Eigen::Vector2d::Constant(radius));
    const Eigen::Vector2i hi = bucket_of(q + Eigen::Vector2d::Constant(radius));
    for (int by = lo.y(); by <= hi.y(); ++by) {
      for (int bx = lo.x(); bx <= hi.x(); ++bx) {
        for (const int id : buckets_[static_cast<std::size_t>(by) * cols_ + bx]) {
          if ((nodes[static_cast<std::size_t>(id)].point - q).squaredNorm() <= radius * radius) out.push_back(id);
        }
      }
    }
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  Eigen::Vector2i bucket_of(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d u = (p - origin_) / size_;
    return {std::clamp(static_cast<int>(std::floor(std::clamp(u.x(), -1.0, 1e9))), 0, cols_ - 1),
            std::clamp(static_cast<int>(std::floor(std::clamp(u.y(), -1.0, 1e9))), 0, rows_ - 1)};
  }

  Eigen::Vector2d origin_;
  double size_;
  int cols_;
  int rows_;
  std::vector<std::vector<int>> buckets_;
};

/// Moves node `id` under `parent` at `cost`, shifting its subtree's costs alike.
void reparent(std::vector<Node>& nodes, int id, int parent, double cost) {
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
    for (const int child : nodes[static_cast<std::size_t>(k)].children) stack.push_back(child);
  }
}

double free_area_m2(const OccupancyGrid& grid) {
  const auto free = std::count(grid.occupied.begin(), grid.occupied.end(), 0);
  return static_cast<double>(free) * grid.resolution_m * grid.resolution_m;
}

}  // namespace

void validate(const RrtStarConfig& c) {
  require(std::isfinite(c.step_m) && c.step_m > 0.0, "step must be finite and > 0");
  require(std::isfinite(c.rewire_radius_m) && c.rewire_radius_m >= 0.0, "rewire_radius must be finite and >= 0");
  require(std::isfinite(c.rewire_gamma_m) && c.rewire_gamma_m >= 0.0, "rewire_gamma must be finite and >= 0");
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
  std::vector<Node> nodes{{start_m, -1, 0.0, {}}};
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
  NodeBuckets buckets(grid, config.step_m);
  buckets.add(0, start_m);
  Rng rng(config.seed);
  const Eigen::Vector2d extent = grid.resolution_m * Eigen::Vector2d(grid.cols, grid.rows);
  std::vector<int> goal_nodes;
  int best_goal = -1;
  result.best_cost_by_iteration.reserve(static_cast<std::size_t>(config.max_iterations));

  for (int iteration = 1; iteration <= config.max_iterations; ++iteration) {
    const Eigen::Vector2d sample = rng.bernoulli(config.goal_bias)
                                       ? goal_m
                                       : Eigen::Vector2d(grid.origin_m.x() + extent.x() * rng.uniform01(),
                                                         grid.origin_m.y() + extent.y() * rng.uniform01());
    const int nearest = buckets.nearest(sample, nodes);
    const Eigen::Vector2d from = nodes[static_cast<std::size_t>(nearest)].point;
    const double distance = (sample - from).norm();
    const Eigen::Vector2d point = distance > config.step_m ? Eigen::Vector2d(from + (sample - from) * (config.step_m / distance)) : sample;
    if (distance > 1e-12 && grid.segment_free(from, point)) {
      // Connect through the cheapest free neighbour (the nearest node at worst).
      const std::vector<int> near = buckets.near(point, rewire_radius(nodes.size() + 1), nodes);
      int parent = nearest;
      double cost = nodes[static_cast<std::size_t>(nearest)].cost + (point - from).norm();
      for (const int j : near) {
        const Node& candidate = nodes[static_cast<std::size_t>(j)];
        const double via = candidate.cost + (point - candidate.point).norm();
        if (via < cost && grid.segment_free(candidate.point, point)) {
          parent = j;
          cost = via;
        }
      }
      const int id = static_cast<int>(nodes.size());
      nodes.push_back({point, parent, cost, {}});
      nodes[static_cast<std::size_t>(parent)].children.push_back(id);
      buckets.add(id, point);
      // Rewire: neighbours that are cheaper to reach through the new node.
      for (const int j : near) {
        if (j == parent) continue;
        const Node& neighbour = nodes[static_cast<std::size_t>(j)];
        const double via = cost + (neighbour.point - point).norm();
        if (via < neighbour.cost && grid.segment_free(point, neighbour.point)) reparent(nodes, j, id, via);
      }
      if ((point - goal_m).norm() <= config.goal_radius_m) {
        goal_nodes.push_back(id);
        if (result.first_solution_iteration < 0) result.first_solution_iteration = iteration;
      }
    }
    for (const int g : goal_nodes) {
      if (best_goal < 0 || nodes[static_cast<std::size_t>(g)].cost < nodes[static_cast<std::size_t>(best_goal)].cost) {
        best_goal = g;
      }
    }
    result.best_cost_by_iteration.push_back(best_goal < 0 ? std::numeric_limits<double>::infinity()
                                                          : nodes[static_cast<std::size_t>(best_goal)].cost);
  }

  result.iterations = config.max_iterations;
  result.nodes = nodes.size();
  if (best_goal < 0) return result;
  result.status = RrtStarStatus::solved;
  result.cost_m = nodes[static_cast<std::size_t>(best_goal)].cost;
  for (int k = best_goal; k >= 0; k = nodes[static_cast<std::size_t>(k)].parent) {
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
