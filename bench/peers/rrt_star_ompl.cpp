// campo's RRT* (planners/rrt_star) side by side with OMPL's ompl::geometric::RRTstar on the same
// 2-D occupancy-grid problems, in one process: for each map and budget, repetitions alternate
// campo, OMPL, campo, OMPL, ... (seed r for both in repetition r), and the table gives the median
// times, their ratio (OMPL / campo: above 1, campo is faster) and both planners' path costs
// (median and range), which must keep agreeing. docs/PERFORMANCE.md, "Peers".
//
// The OMPL problem is made as close to campo's as its API allows:
//  - the plane as RealVectorStateSpace(2) bounded by the grid, sampled uniformly like campo;
//  - a state is valid when its grid cell is free, a motion when OccupancyGrid::segment_free
//    holds: the very cell walk campo checks edges with, so both reject exactly the same edges;
//  - range (campo's step) 2 m, goal bias 0.05, goal region: within 1 m of the goal state
//    (ompl::base::GoalState, whose goal OMPL samples only until some node lies in the region;
//    campo samples it throughout, though once a node sits on the goal those samples add nothing);
//  - neighbours within a shrinking radius (setKNearest(false)), min(gamma (log n / n)^(1/2),
//    range), with OMPL's gamma = rewire factor x (3 A / pi)^(1/2) over the space's area A made
//    equal to campo's (6 A_free / pi)^(1/2) through the rewire factor (2 A_free / A)^(1/2);
//    campo also keeps at most k(n) = ceil(3 e ln n) of them, which seldom binds;
//  - a budget of iterations: ompl::base::IterationTerminationCondition, checked once an iteration.
// OMPL's time covers what campo's call does: creating the planner and the problem definition,
// setting up, solving and freeing the tree. Each OMPL run seeds ompl::RNG::setSeed before the
// planner and its sampler draw their seeds, so a run is reproducible.
//
//   build/campo_peer_rrt_star [--reps 9] [--budgets 500,2000,8000,32000] [--maps arena,box] [--planners campo,ompl]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/terminationconditions/IterationTerminationCondition.h>
#include <ompl/config.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "bench/peers/peer_record.hpp"
#include "grid/movingai.hpp"
#include "planners/rrt_star.hpp"
#include "scene/occupancy_grid.hpp"

namespace campo {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

using Clock = std::chrono::steady_clock;

/// A 2-D planning problem on 1 m cells.
struct GridProblem {
  std::string name;
  std::string description;
  OccupancyGrid grid;
  Eigen::Vector2d start_m;
  Eigen::Vector2d goal_m;
};

/// The rover benchmark's problem (bench/rover_global_bench.cpp): MovingAI arena.map, 49 x 49,
/// cell (1, 7) to cell (47, 46), A* optimum 62.15.
GridProblem arena_problem() {
  const grid::MovingAiMap map =
      grid::read_movingai_map(std::string(CAMPO_SOURCE_DIR) + "/tests/data/movingai/arena.map");
  return {"arena", "MovingAI arena.map, 49 m x 49 m", to_occupancy_grid(map), movingai_cell_centre(map, {1, 7, 0}),
          movingai_cell_centre(map, {47, 46, 0})};
}

/// The box map: 100 m x 100 m of 1 m cells with six axis-aligned boxes (no fixture of this size
/// exists, so it is defined here), from (5.5, 5.5) to (94.5, 94.5). The boxes block the diagonal
/// three times, so a path weaves between them.
GridProblem box_problem() {
  OccupancyGrid grid;
  grid.cols = grid.rows = 100;
  grid.resolution_m = 1.0;
  grid.occupied.assign(100 * 100, 0);
  // [x0, x1) x [y0, y1) in cells.
  struct Box {
    int x0, y0, x1, y1;
  };
  for (const Box& box : {Box{20, 10, 30, 60}, Box{45, 40, 55, 90}, Box{70, 10, 80, 60}, Box{10, 75, 35, 85},
                         Box{60, 70, 90, 78}, Box{85, 20, 95, 35}}) {
    for (int row = box.y0; row < box.y1; ++row) {
      for (int col = box.x0; col < box.x1; ++col) grid.occupied[static_cast<std::size_t>(row) * 100 + col] = 1;
    }
  }
  return {"box", "100 m x 100 m, six boxes", std::move(grid), {5.5, 5.5}, {94.5, 94.5}};
}

double free_area_m2(const OccupancyGrid& grid) {
  const auto free = std::count(grid.occupied.begin(), grid.occupied.end(), 0);
  return static_cast<double>(free) * grid.resolution_m * grid.resolution_m;
}

Eigen::Vector2d point_of(const ob::State* state) {
  const auto* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  return {values[0], values[1]};
}

/// A state is valid when its grid cell is free (outside the grid is not).
class GridStateValidityChecker : public ob::StateValidityChecker {
 public:
  GridStateValidityChecker(const ob::SpaceInformationPtr& si, const OccupancyGrid& grid)
      : ob::StateValidityChecker(si), grid_(grid) {}
  bool isValid(const ob::State* state) const override { return !grid_.is_occupied(point_of(state)); }

 private:
  const OccupancyGrid& grid_;
};

/// A motion is valid when its segment crosses no occupied cell: campo's own edge check.
class GridMotionValidator : public ob::MotionValidator {
 public:
  GridMotionValidator(const ob::SpaceInformationPtr& si, const OccupancyGrid& grid)
      : ob::MotionValidator(si), grid_(grid) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool free = grid_.segment_free(point_of(s1), point_of(s2));
    ++(free ? valid_ : invalid_);
    return free;
  }

  /// RRTstar never asks for the last valid state; other planners do. Bisection on the fraction
  /// of the segment that is free, to 1e-6 of its length.
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override {
    if (checkMotion(s1, s2)) return true;
    const Eigen::Vector2d a = point_of(s1), b = point_of(s2);
    double free = 0.0, blocked = 1.0;
    while (blocked - free > 1e-6) {
      const double mid = 0.5 * (free + blocked);
      if (grid_.segment_free(a, a + mid * (b - a))) {
        free = mid;
      } else {
        blocked = mid;
      }
    }
    if (last_valid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, free, last_valid.first);
    last_valid.second = free;
    return false;
  }

 private:
  const OccupancyGrid& grid_;
};

/// OMPL's side of a problem: the space and its validity checks, built once per map.
struct OmplProblem {
  ob::StateSpacePtr space;
  ob::SpaceInformationPtr si;
  double rewire_factor = 1.0;  ///< makes OMPL's gamma campo's (see the file's comment)
};

OmplProblem make_ompl_problem(const GridProblem& problem) {
  const OccupancyGrid& grid = problem.grid;
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, grid.origin_m.x());
  bounds.setLow(1, grid.origin_m.y());
  bounds.setHigh(0, grid.origin_m.x() + grid.cols * grid.resolution_m);
  bounds.setHigh(1, grid.origin_m.y() + grid.rows * grid.resolution_m);
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<GridStateValidityChecker>(si, grid));
  si->setMotionValidator(std::make_shared<GridMotionValidator>(si, grid));
  si->setup();
  const double area_m2 = bounds.getVolume();
  return {space, si, std::sqrt(2.0 * free_area_m2(grid) / area_m2)};
}

/// One planner run: wall time, path cost (+inf unsolved), iterations run and
/// edges checked (OccupancyGrid::segment_free calls).
struct Run {
  double seconds = 0.0;
  double cost_m = std::numeric_limits<double>::infinity();
  unsigned iterations = 0;
  std::uint64_t edge_checks = 0;
};

constexpr double kStepM = 2.0;
constexpr double kGoalRadiusM = 1.0;
constexpr double kGoalBias = 0.05;

Run run_campo(const GridProblem& problem, int budget, std::uint64_t seed) {
  RrtStarConfig config;
  config.seed = seed;
  config.step_m = kStepM;
  config.goal_radius_m = kGoalRadiusM;
  config.goal_bias = kGoalBias;
  config.max_iterations = budget;
  const auto t0 = Clock::now();
  const RrtStarResult result = rrt_star(problem.grid, problem.start_m, problem.goal_m, config);
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return {seconds, result.cost_m, static_cast<unsigned>(result.iterations), result.work.segment_checks};
}

/// `k_nearest`: OMPL's default neighbourhood, the k(n) = 1.1 2^3 e (1 + 1/2) ln(n + 1) nearest
/// (no radius; rewire factor 1.1), instead of the shrinking radius matched to campo's.
Run run_ompl(const GridProblem& problem, const OmplProblem& ompl_problem, int budget, std::uint64_t seed,
             bool k_nearest) {
  Run run;
  ompl_problem.si->getMotionValidator()->resetMotionCounter();
  const auto t0 = Clock::now();
  {
    // Before anything draws a seed from OMPL's seed generator: the planner's and the sampler's.
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed));
    auto pdef = std::make_shared<ob::ProblemDefinition>(ompl_problem.si);
    ob::ScopedState<ob::RealVectorStateSpace> start(ompl_problem.space), goal(ompl_problem.space);
    start[0] = problem.start_m.x();
    start[1] = problem.start_m.y();
    goal[0] = problem.goal_m.x();
    goal[1] = problem.goal_m.y();
    pdef->addStartState(start);
    auto goal_region = std::make_shared<ob::GoalState>(ompl_problem.si);
    goal_region->setState(goal);
    goal_region->setThreshold(kGoalRadiusM);
    pdef->setGoal(goal_region);
    pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(ompl_problem.si));
    og::RRTstar planner(ompl_problem.si);
    planner.setRange(kStepM);
    planner.setGoalBias(kGoalBias);
    if (!k_nearest) {
      planner.setKNearest(false);
      planner.setRewireFactor(ompl_problem.rewire_factor);
    }
    planner.setProblemDefinition(pdef);
    planner.setup();
    ob::IterationTerminationCondition iterations(static_cast<unsigned>(budget));
    planner.solve(iterations);
    if (pdef->hasExactSolution()) run.cost_m = planner.bestCost().value();
    run.iterations = planner.numIterations();
  }
  run.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  run.edge_checks = ompl_problem.si->getMotionValidator()->getCheckedMotionCount();
  return run;
}

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

/// "median [min, max]" of the solved runs' costs, with the count solved when not all were.
std::string cost_summary(const std::vector<Run>& runs) {
  std::vector<double> costs;
  for (const Run& run : runs) {
    if (std::isfinite(run.cost_m)) costs.push_back(run.cost_m);
  }
  if (costs.empty()) return "unsolved";
  const auto [lo, hi] = std::minmax_element(costs.begin(), costs.end());
  char text[96];
  std::snprintf(text, sizeof text, "%.1f [%.1f, %.1f]", median(costs), *lo, *hi);
  std::string summary = text;
  if (costs.size() < runs.size()) {
    summary += " (" + std::to_string(costs.size()) + "/" + std::to_string(runs.size()) + " solved)";
  }
  return summary;
}

/// Median wall time in ms, "-" without runs.
std::string median_ms(const std::vector<Run>& runs) {
  if (runs.empty()) return "-";
  std::vector<double> seconds;
  for (const Run& run : runs) seconds.push_back(run.seconds);
  char text[32];
  std::snprintf(text, sizeof text, "%.3g ms", 1e3 * median(seconds));
  return text;
}

/// Median edge checks an iteration, "-" without runs.
std::string median_checks(const std::vector<Run>& runs) {
  if (runs.empty()) return "-";
  std::vector<double> per_iteration;
  for (const Run& run : runs) {
    per_iteration.push_back(static_cast<double>(run.edge_checks) / std::max(run.iterations, 1u));
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", median(per_iteration));
  return text;
}

int run_main(int argc, char** argv) {
  CLI::App app{"campo's RRT* side by side with OMPL's RRTstar on the same grid problems (Markdown table)"};
  int reps = 9;
  std::vector<int> budgets{500, 2000, 8000, 32000};
  std::vector<std::string> maps{"arena", "box"};
  std::vector<std::string> planners{"campo", "ompl"};
  bool k_nearest = false;
  bool json = false;
  app.add_flag("--json", json, "one line of JSON per map and budget (campo bench peers reads them), not the table");
  app.add_option("--reps", reps, "interleaved repetitions per map and budget (medians of these)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--budgets", budgets, "iteration budgets")->delimiter(',')->check(CLI::Range(1, 10'000'000));
  app.add_option("--maps", maps, "maps: arena, box")->delimiter(',')->check(CLI::IsMember({"arena", "box"}));
  app.add_option("--planners", planners, "planners to run (one alone: for profiling)")
      ->delimiter(',')
      ->check(CLI::IsMember({"campo", "ompl"}));
  app.add_flag("--ompl-k-nearest", k_nearest,
               "OMPL with its default neighbourhood, the 1.1 2^3 e 1.5 ln(n + 1) nearest (not campo's radius)");
  CLI11_PARSE(app, argc, argv);
  const bool with_campo = std::find(planners.begin(), planners.end(), "campo") != planners.end();
  const bool with_ompl = std::find(planners.begin(), planners.end(), "ompl") != planners.end();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);  // setSeed's "generation already started" on every run
  if (json && !(with_campo && with_ompl)) throw CLI::ValidationError("--json", "compares both planners");
  // Human output goes to stderr when JSON lines are asked for.
  FILE* const text_out = json ? stderr : stdout;

  std::fprintf(text_out, "campo RRT* vs OMPL %d.%d.%d RRTstar: step 2 m, goal region 1 m, goal bias 0.05, %s;\n",
              OMPL_MAJOR_VERSION, OMPL_MINOR_VERSION, OMPL_PATCH_VERSION,
              k_nearest ? "OMPL with its default k-nearest neighbours" : "neighbours within the same shrinking radius");
  std::fprintf(text_out, "median of %d interleaved repetitions (seeds 1..%d); costs: median [min, max] in m;\n", reps, reps);
  std::fprintf(text_out, "checks: edges checked an iteration (OccupancyGrid::segment_free), median.\n");
  for (const std::string& name : maps) {
    const GridProblem problem = name == "arena" ? arena_problem() : box_problem();
    std::fprintf(text_out, "%s: %s, (%.1f, %.1f) -> (%.1f, %.1f)\n", problem.name.c_str(), problem.description.c_str(),
                problem.start_m.x(), problem.start_m.y(), problem.goal_m.x(), problem.goal_m.y());
  }
  std::fprintf(text_out, "\n| map | budget | campo | OMPL | OMPL / campo | campo cost | OMPL cost | campo checks | OMPL checks |"
              "\n");
  std::fprintf(text_out, "| --- | ---: | ---: | ---: | ---: | --- | --- | ---: | ---: |\n");
  for (const std::string& name : maps) {
    const GridProblem problem = name == "arena" ? arena_problem() : box_problem();
    const OmplProblem ompl_problem = make_ompl_problem(problem);
    // Untimed warm-up: first-touch page faults and lazy symbol binding.
    if (with_campo) run_campo(problem, budgets.front(), 1);
    if (with_ompl) run_ompl(problem, ompl_problem, budgets.front(), 1, k_nearest);
    for (const int budget : budgets) {
      std::vector<Run> campo_runs, ompl_runs;
      for (int rep = 1; rep <= reps; ++rep) {
        const auto seed = static_cast<std::uint64_t>(rep);
        if (with_campo) campo_runs.push_back(run_campo(problem, budget, seed));
        if (with_ompl) ompl_runs.push_back(run_ompl(problem, ompl_problem, budget, seed, k_nearest));
      }
      for (const Run& run : ompl_runs) {
        if (run.iterations != static_cast<unsigned>(budget)) {
          throw std::runtime_error("OMPL ran " + std::to_string(run.iterations) + " iterations, not " +
                                   std::to_string(budget));
        }
      }
      std::string ratio = "-";
      if (with_campo && with_ompl) {
        std::vector<double> campo_s, ompl_s;
        for (const Run& run : campo_runs) campo_s.push_back(run.seconds);
        for (const Run& run : ompl_runs) ompl_s.push_back(run.seconds);
        char text[32];
        std::snprintf(text, sizeof text, "%.2fx", median(ompl_s) / median(campo_s));
        ratio = text;
      }
      if (json) {
        std::vector<double> campo_s, ompl_s;
        for (const Run& run : campo_runs) campo_s.push_back(run.seconds);
        for (const Run& run : ompl_runs) ompl_s.push_back(run.seconds);
        peers::print_json({"rrt_star/" + problem.name + "/" + std::to_string(budget),
                           "RRT* on " + problem.name + ", " + std::to_string(budget) + " iterations", 1.0 / median(campo_s),
                           1.0 / median(ompl_s), "plans/s",
                           "OMPL " + std::to_string(OMPL_MAJOR_VERSION) + "." + std::to_string(OMPL_MINOR_VERSION) + "." +
                               std::to_string(OMPL_PATCH_VERSION) + " RRTstar",
                           "path costs (m) campo " + cost_summary(campo_runs) + ", OMPL " + cost_summary(ompl_runs)});
      }
      std::fprintf(text_out, "| %s | %d | %s | %s | %s | %s | %s | %s | %s |\n", problem.name.c_str(), budget,
                  median_ms(campo_runs).c_str(), median_ms(ompl_runs).c_str(), ratio.c_str(),
                  with_campo ? cost_summary(campo_runs).c_str() : "-",
                  with_ompl ? cost_summary(ompl_runs).c_str() : "-",
                  median_checks(campo_runs).c_str(), median_checks(ompl_runs).c_str());
      std::fflush(text_out);
    }
  }
  return 0;
}

}  // namespace
}  // namespace campo

int main(int argc, char** argv) { return campo::run_main(argc, argv); }
