#pragma once
/// RRT* (Karaman & Frazzoli 2011; seed 003 §2.2.3, SPEC §7.3) on an
/// OccupancyGrid: the rover's sampling-based alternative global planner.
/// Deterministic: the samples come from a seeded generator and the budget is
/// an iteration count, never the wall clock, so the same inputs give the
/// same tree and path.
#include <cstdint>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "grid/movingai.hpp"
#include "scene/occupancy_grid.hpp"

namespace campo {

/// Bounds of the lengths in RrtStarConfig: a step below kMinStepM would add
/// nodes that barely move; lengths above kMaxLengthM have no use on any grid.
inline constexpr double kMinStepM = 1e-3;
inline constexpr double kMaxLengthM = 1e6;
/// A new node considers at most k(n) = ceil(kNeighboursPerLogNode ln n) of
/// its nearest nodes within the rewiring radius (n the number of nodes), so
/// an iteration's work stays O(log n) segment checks even with a fixed
/// radius or nodes crowded together. k-nearest RRT* is asymptotically
/// optimal for a factor above e (1 + 1/d) = 1.5 e in the plane (Karaman &
/// Frazzoli 2011, Thm. 38); twice that leaves the shrinking radius (about
/// 6 ln n nodes expected in it) almost always the binding limit.
inline constexpr double kNeighboursPerLogNode = 3.0 * std::numbers::e;
/// k(n) above.
std::size_t max_neighbours(std::size_t n);

struct RrtStarConfig {
  std::uint64_t seed = 0;        ///< of the sampler (campo::Rng, mt19937_64)
  /// lambda: the farthest a new node lies from its nearest node, [kMinStepM,
  /// kMaxLengthM]; a step beyond the grid's diagonal acts as the diagonal.
  double step_m = 2.0;
  /// > 0: fixed rewiring radius. 0: shrinking radius
  /// min(gamma (log n / n)^(1/2), lambda), n the number of nodes. <= kMaxLengthM.
  double rewire_radius_m = 0.0;
  /// gamma of the shrinking radius; 0: Karaman & Frazzoli's bound for the
  /// plane, 2 (1.5 A_free / pi)^(1/2), A_free the grid's free area. [0, kMaxLengthM].
  double rewire_gamma_m = 0.0;
  double goal_radius_m = 1.0;    ///< a node this near the goal solves the problem, > 0
  double goal_bias = 0.05;       ///< probability of sampling the goal itself, [0, 1]
  int max_iterations = 5000;     ///< the budget, [0, 10'000'000]
};

/// Throws std::invalid_argument naming the first field out of range.
void validate(const RrtStarConfig& config);

enum class RrtStarStatus {
  solved,         ///< a path reaches the goal region
  no_solution,    ///< none within the iteration budget
  invalid_start,  ///< the start's cell is occupied (or outside the grid)
  invalid_goal,   ///< the goal's cell is occupied (or outside the grid)
};
std::string_view to_string(RrtStarStatus status);

/// Work done, for bounds tests: none of it grows with the grid's extent.
struct RrtStarWork {
  /// Node coordinates read in the nearest / near queries (PointIndex:
  /// nanoflann's k-d trees and the buffer of the newest nodes): two per
  /// distance computed (tree cells nanoflann steps through read none, but
  /// each leads to a leaf of at most 16 points whose distances count).
  std::uint64_t index_query_reads = 0;
  /// Node coordinates nanoflann read building its trees (bounding boxes,
  /// splits) as nodes arrived: O(log^2 n) amortized per node.
  std::uint64_t index_build_reads = 0;
  std::size_t max_neighbours = 0;             ///< most rewiring candidates of one iteration (<= k(n))
  std::uint64_t segment_checks = 0;           ///< OccupancyGrid::segment_free calls
  std::uint64_t cells_checked = 0;            ///< grid cells those calls looked up
  std::uint64_t max_cells_per_iteration = 0;  ///< most cells looked up in one iteration
};

struct RrtStarResult {
  RrtStarStatus status = RrtStarStatus::no_solution;
  std::vector<Eigen::Vector2d> path_m;  ///< start .. a node inside the goal region; empty unless solved
  double cost_m = std::numeric_limits<double>::infinity();  ///< length of path_m
  int first_solution_iteration = -1;  ///< 1-based iteration that first reached the goal region; 0: start inside it
  int iterations = 0;                 ///< iterations run (fewer than max_iterations when stopped)
  bool stopped = false;               ///< the progress callback stopped the search before its budget
  std::size_t nodes = 0;              ///< tree size at the end
  /// Best cost after each iteration (index i: after iteration i + 1); +inf
  /// before the first solution. Never increases: rewiring only lowers costs.
  std::vector<double> best_cost_by_iteration;
  RrtStarWork work;
};

/// Iterations between two calls of an RrtStarProgress.
inline constexpr int kRrtStarProgressEvery = 1024;
/// Told the iterations done before iterations 1, 1 + kRrtStarProgressEvery,
/// 1 + 2 kRrtStarProgressEvery, ... (a progress display, a wall-clock
/// deadline); returning false stops the search there, with the tree so far.
using RrtStarProgress = std::function<bool(int iterations_done)>;

/// Grows the tree from `start_m` for config.max_iterations iterations:
/// sample (the goal with probability goal_bias, else uniform over the grid),
/// steer from the nearest node by at most lambda, keep the new node when the
/// segment is free (OccupancyGrid::segment_free), connect it through the
/// cheapest free neighbour among the k(n) nearest within the rewiring radius,
/// then rewire those neighbours through it when that is cheaper. Nearest
/// nodes come from a PointIndex (planners/point_index.hpp: nanoflann's
/// dynamic k-d tree and a buffer of the newest nodes), so an iteration costs
/// O(log^2 n) index work (amortized) plus at most 2 k(n) + 1 segment checks of about 3 lambda / resolution
/// cells each, independent of the grid's extent. The path is the cheapest
/// tree path to a node inside the goal region. `progress`, if given, may stop
/// the search early (result.stopped); without it the result depends only on
/// the inputs. Throws std::invalid_argument for a bad config.
RrtStarResult rrt_star(const OccupancyGrid& grid, const Eigen::Vector2d& start_m, const Eigen::Vector2d& goal_m,
                       const RrtStarConfig& config = {}, const RrtStarProgress& progress = {});

/// A MovingAI map as an occupancy grid of 1 m cells, origin (0, 0): map
/// cell (x, y), y counted from the top row, becomes grid cell
/// (x, height - 1 - y); impassable cells are occupied.
OccupancyGrid to_occupancy_grid(const grid::MovingAiMap& map);
/// Centre of a MovingAI map cell in that grid's world coordinates.
Eigen::Vector2d movingai_cell_centre(const grid::MovingAiMap& map, const grid::Cell& cell);

}  // namespace campo
