// The rover's alternative planners (SPEC §7.3): RRT* on the MovingAI arena
// map (iterations to the first solution, cost after a fixed budget, averaged
// over seeds), the occupancy grid of the bundled vineyard (100 m x 100 m at
// 0.1 m, about a million cells), one VFH+ step between its rows, and the
// smoothing of an RRT* path into a drivable one.
#include <benchmark/benchmark.h>

#include <numbers>
#include <string>

#include "grid/movingai.hpp"
#include "planners/path_smoothing.hpp"
#include "planners/rrt_star.hpp"
#include "planners/vfh_plus.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/scene.hpp"
#include "sim/scene_loader.hpp"

namespace campo {
namespace {

const std::string kSourceDir = CAMPO_SOURCE_DIR;

/// The arena map and its longest scenario problem (octile optimum 62.15 cells).
struct ArenaProblem {
  OccupancyGrid grid;
  Eigen::Vector2d start;
  Eigen::Vector2d goal;
};

const ArenaProblem& arena() {
  static const ArenaProblem problem = [] {
    const grid::MovingAiMap map = grid::read_movingai_map(kSourceDir + "/tests/data/movingai/arena.map");
    return ArenaProblem{to_occupancy_grid(map), movingai_cell_centre(map, {1, 7, 0}),
                        movingai_cell_centre(map, {47, 46, 0})};
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
BENCHMARK(BM_OccupancyGridVineyard)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InflateVineyard)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VfhPlusStep)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SmoothRrtStarPath)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace campo
