// The rover's alternative planners (SPEC §7.3): RRT* on the MovingAI arena
// map (iterations to the first solution, cost after a fixed budget, averaged
// over seeds; time to the first solution and cost after 1 s of wall time),
// the occupancy grid of the bundled vineyard (100 m x 100 m at
// 0.1 m, about a million cells), one VFH+ step between its rows, and the
// smoothing of an RRT* path into a drivable one.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <numbers>
#include <string>
#include <vector>

#include "campo/scene.hpp"
#include "campo/scene_loader.hpp"
#include "grid/astar.hpp"
#include "grid/movingai.hpp"
#include "planners/path_smoothing.hpp"
#include "planners/rrt_star.hpp"
#include "planners/vfh_plus.hpp"
#include "scene/occupancy_grid.hpp"

namespace campo {
namespace {

const std::string kSourceDir = CAMPO_SOURCE_DIR;

/// The arena map and its longest scenario problem (octile optimum 62.15 cells).
struct ArenaProblem {
  OccupancyGrid grid;
  Eigen::Vector2d start;
  Eigen::Vector2d goal;
  double astar_optimum = 0.0;  ///< octile cost in cells (= metres) of the same problem
};

const ArenaProblem& arena() {
  static const ArenaProblem problem = [] {
    const grid::MovingAiMap map = grid::read_movingai_map(kSourceDir + "/tests/data/movingai/arena.map");
    const grid::Cell start{1, 7, 0}, goal{47, 46, 0};
    grid::GridGraph graph = grid::to_grid_graph(map);
    const double optimum = grid::to_cells(grid::AStar(graph).plan(start, goal).cost);
    return ArenaProblem{to_occupancy_grid(map), movingai_cell_centre(map, start), movingai_cell_centre(map, goal),
                        optimum};
  }();
  return problem;
}

const Scene& vineyard() {
  static const Scene scene = load_scene(kSourceDir + "/scenes/vineyard.json");
  return scene;
}

/// range(0) iterations per run; the seed changes every run, and the counters
/// average over runs.
void BM_RrtStarArena(benchmark::State& state) {
  const ArenaProblem& problem = arena();
  RrtStarConfig config;
  config.max_iterations = static_cast<int>(state.range(0));
  double first_solution = 0.0, first_cost = 0.0, final_cost = 0.0, solved = 0.0, runs = 0.0;
  for (auto _ : state) {
    config.seed = static_cast<std::uint64_t>(runs);
    const RrtStarResult result = rrt_star(problem.grid, problem.start, problem.goal, config);
    benchmark::DoNotOptimize(result.cost_m);
    runs += 1.0;
    if (result.status != RrtStarStatus::solved) continue;
    solved += 1.0;
    first_solution += result.first_solution_iteration;
    first_cost += result.best_cost_by_iteration[static_cast<std::size_t>(result.first_solution_iteration - 1)];
    final_cost += result.cost_m;
  }
  state.counters["solved_fraction"] = solved / runs;
  if (solved > 0.0) {
    state.counters["first_solution_iteration"] = first_solution / solved;
    state.counters["first_cost_m"] = first_cost / solved;
    state.counters["final_cost_m"] = final_cost / solved;
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

/// Time to the first solution and cost after 1 s of wall time, seed 0,
/// default config. rrt_star's budget is iterations, and the first k
/// iterations of a run are the same for any budget >= k, so: runs of doubling
/// budgets (1000, 2000, ...) until one takes >= 1 s; the iteration count
/// reached at 1 s is interpolated linearly in time between the last two runs,
/// and the cost there is read from the last run's best_cost_by_iteration.
/// The first solution's time is that of one run stopped at its iteration.
/// Costs end within goal_radius_m (1 m) of the goal's centre, as in
/// BM_RrtStarArena; astar_optimum is the octile optimum, centre to centre.
void BM_RrtStarCostAfterOneSecond(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const ArenaProblem& problem = arena();
  const auto timed = [&](int iterations, RrtStarResult& result) {
    RrtStarConfig config;
    config.max_iterations = iterations;
    const auto t0 = Clock::now();
    result = rrt_star(problem.grid, problem.start, problem.goal, config);
    benchmark::DoNotOptimize(result.cost_m);
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  constexpr int kMaxIterations = 10'000'000;  // rrt_star's limit
  double iterations_in_1s = 0.0, cost_after_1s = 0.0, first_solution_ms = 0.0, first_solution = -1.0, last_s = 0.0;
  for (auto _ : state) {
    RrtStarResult result;
    int previous = 0, budget = 1000;
    double previous_s = 0.0, seconds = 0.0;
    for (;;) {
      seconds = timed(budget, result);
      if (seconds >= 1.0 || budget >= kMaxIterations) break;
      previous = budget;
      previous_s = seconds;
      budget = std::min(2 * budget, kMaxIterations);
    }
    last_s = seconds;
    const double fraction = seconds >= 1.0 ? (1.0 - previous_s) / (seconds - previous_s) : 1.0;
    const int reached = std::clamp(static_cast<int>(previous + fraction * (budget - previous)), 1, budget);
    iterations_in_1s = reached;
    cost_after_1s = result.best_cost_by_iteration[static_cast<std::size_t>(reached - 1)];
    first_solution = result.first_solution_iteration;
    if (result.first_solution_iteration > 0) {
      RrtStarResult first;
      first_solution_ms = 1e3 * timed(result.first_solution_iteration, first);
    }
  }
  state.counters["iterations_in_1s"] = iterations_in_1s;
  state.counters["cost_after_1s_m"] = cost_after_1s;
  state.counters["first_solution_iteration"] = first_solution;
  state.counters["first_solution_ms"] = first_solution_ms;
  state.counters["astar_optimum_m"] = problem.astar_optimum;
  state.counters["last_run_s"] = last_s;
}

void BM_OccupancyGridVineyard(benchmark::State& state) {
  const Scene& scene = vineyard();
  std::size_t cells = 0;
  for (auto _ : state) {
    const OccupancyGrid grid = build_occupancy_grid(scene);
    cells = grid.occupied.size();
    benchmark::DoNotOptimize(grid.occupied.data());
  }
  state.counters["cells"] = static_cast<double>(cells);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cells));
}

void BM_InflateVineyard(benchmark::State& state) {
  const OccupancyGrid grid = build_occupancy_grid(vineyard());
  for (auto _ : state) {
    const OccupancyGrid inflated = inflate(grid, 0.5);
    benchmark::DoNotOptimize(inflated.occupied.data());
  }
  state.counters["cells"] = static_cast<double>(grid.occupied.size());
}

/// Between the two middle rows of the vineyard, heading north up the inter-row.
void BM_VfhPlusStep(benchmark::State& state) {
  const OccupancyGrid grid = build_occupancy_grid(vineyard());
  const VfhPlusConfig config;
  VfhPlusState vfh;
  for (auto _ : state) {
    const VfhPlusResult result = vfh_plus_step(grid, {0.0, 0.0}, std::numbers::pi / 2, {0.0, 43.0}, config, vfh);
    benchmark::DoNotOptimize(result.direction_rad);
  }
}

void BM_SmoothRrtStarPath(benchmark::State& state) {
  const ArenaProblem& problem = arena();
  RrtStarConfig rrt;
  rrt.max_iterations = 2000;
  const RrtStarResult tree = rrt_star(problem.grid, problem.start, problem.goal, rrt);
  PathSmoothingConfig config;
  config.step_m = 0.1;
  SmoothedPath smoothed;
  for (auto _ : state) {
    smoothed = smooth_path(problem.grid, tree.path_m, config);
    benchmark::DoNotOptimize(smoothed.points_m.data());
  }
  state.counters["input_points"] = static_cast<double>(tree.path_m.size());
  state.counters["waypoints"] = static_cast<double>(smoothed.waypoints_m.size());
  state.counters["fillets"] = static_cast<double>(smoothed.fillets.size());
}

BENCHMARK(BM_RrtStarArena)->Arg(500)->Arg(2000)->Arg(8000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RrtStarCostAfterOneSecond)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OccupancyGridVineyard)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InflateVineyard)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VfhPlusStep)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SmoothRrtStarPath)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace campo
