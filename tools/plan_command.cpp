#include <array>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "grid/astar.hpp"
#include "grid/dstar_lite.hpp"
#include "grid/lpa_star.hpp"
#include "grid/movingai.hpp"
#include "sim/json_reader.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

struct PlanOptions {
  std::string planner = "astar";
  std::string map;
  std::string start;
  std::string goal;
  std::string scen;
};

enum class GridPlanner { astar, dstar_lite, lpa_star };

struct GridPlannerName {
  GridPlanner planner;
  std::string_view name;
};
constexpr std::array<GridPlannerName, 3> kGridPlanners{{
    {GridPlanner::astar, "astar"},
    {GridPlanner::dstar_lite, "dstar_lite"},
    {GridPlanner::lpa_star, "lpa_star"},
}};

GridPlanner planner_from_name(std::string_view name) {
  for (const auto& entry : kGridPlanners) {
    if (entry.name == name) return entry.planner;
  }
  throw InputError("command line", "--planner", "no grid planner \"" + std::string(name) + "\"");
}

// One planner over one map, reusing its buffers from problem to problem.
class Solver {
 public:
  Solver(grid::GridGraph& graph, GridPlanner planner) : graph_(graph), planner_(planner), astar_(graph) {}

  grid::SearchResult solve(const grid::Cell& start, const grid::Cell& goal) {
    switch (planner_) {
      case GridPlanner::astar: return astar_.plan(start, goal);
      case GridPlanner::dstar_lite:
        if (!dstar_) dstar_.emplace(graph_, start, goal);
        dstar_->reset(start, goal);
        return dstar_->plan();
      case GridPlanner::lpa_star:
        if (!lpa_) lpa_.emplace(graph_, start, goal);
        lpa_->reset(start, goal);
        return lpa_->plan();
    }
    return {};
  }

 private:
  grid::GridGraph& graph_;
  GridPlanner planner_;
  grid::AStar astar_;
  std::optional<grid::DStarLite> dstar_;
  std::optional<grid::LpaStar> lpa_;
};

// "X,Y" as a passable cell of the map, or an InputError naming the option.
grid::Cell parse_cell(const std::string& text, const std::string& option, const grid::MovingAiMap& map) {
  const std::string expected = "X,Y with 0 <= X < " + std::to_string(map.width) + " and 0 <= Y < " +
                               std::to_string(map.height) + " (column, row)";
  const std::size_t comma = text.find(',');
  std::array<int, 2> xy{};
  const std::array<std::string_view, 2> parts{std::string_view(text).substr(0, comma),
                                              comma == std::string::npos ? std::string_view()
                                                                         : std::string_view(text).substr(comma + 1)};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto [ptr, ec] = std::from_chars(parts[i].data(), parts[i].data() + parts[i].size(), xy[i]);
    if (parts[i].empty() || ec != std::errc() || ptr != parts[i].data() + parts[i].size()) {
      throw InputError("command line", option, "expected " + expected + ", got \"" + text + "\"");
    }
  }
  if (xy[0] < 0 || xy[0] >= map.width || xy[1] < 0 || xy[1] >= map.height) {
    throw InputError("command line", option, "expected " + expected + ", got \"" + text + "\"");
  }
  if (!map.is_passable(xy[0], xy[1])) {
    throw InputError("command line", option, "expected a passable cell, got " + text + ", which the map blocks");
  }
  return {xy[0], xy[1], 0};
}

std::string format_cost(double cells) {
  if (cells < 0.0) return "-1";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.8f", cells);
  return buffer;
}

struct Timed {
  grid::SearchResult result;
  double time_ms = 0.0;
};

Timed timed_solve(Solver& solver, const grid::Cell& start, const grid::Cell& goal) {
  const auto t0 = std::chrono::steady_clock::now();
  Timed timed{solver.solve(start, goal)};
  timed.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return timed;
}

int run_scenario(const PlanOptions& o, const grid::MovingAiMap& map, Solver& solver) {
  const auto problems = grid::read_movingai_scenario(o.scen);
  grid::check_scenario(o.scen, problems, map);
  std::cout << "index,start_x,start_y,goal_x,goal_y,optimal,cost,match\n";
  std::size_t mismatches = 0;
  double total_ms = 0.0;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const grid::MovingAiProblem& p = problems[i];
    const Timed t = timed_solve(solver, p.start, p.goal);
    const double cost = grid::to_cells(t.result.cost);
    const bool match = grid::matches_optimal(cost, p.optimal_length);
    mismatches += match ? 0 : 1;
    total_ms += t.time_ms;
    std::cout << i << ',' << p.start.x << ',' << p.start.y << ',' << p.goal.x << ',' << p.goal.y << ','
              << format_cost(p.optimal_length) << ',' << format_cost(cost) << ',' << (match ? 1 : 0) << '\n';
  }
  char searching[64];
  std::snprintf(searching, sizeof searching, "%.1f ms searching", total_ms);
  std::cerr << problems.size() - mismatches << " of " << problems.size() << " problems at the optimal length ("
            << o.planner << ", " << searching << ")\n";
  return mismatches == 0 ? kOk : kInternalError;
}

int run_plan(const PlanOptions& o) {
  const GridPlanner planner = planner_from_name(o.planner);
  const bool single = !o.start.empty() || !o.goal.empty();
  if (single == !o.scen.empty()) {
    throw InputError("command line", "--scen", "expected either --start X,Y and --goal X,Y, or --scen FILE.scen");
  }
  if (single && (o.start.empty() || o.goal.empty())) {
    throw InputError("command line", o.start.empty() ? "--start" : "--goal", "expected both --start X,Y and --goal X,Y");
  }
  try {
    const grid::MovingAiMap map = grid::read_movingai_map(o.map);
    grid::GridGraph graph = grid::to_grid_graph(map);
    Solver solver(graph, planner);
    if (!single) return run_scenario(o, map, solver);

    const grid::Cell start = parse_cell(o.start, "--start", map), goal = parse_cell(o.goal, "--goal", map);
    const Timed t = timed_solve(solver, start, goal);
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", t.time_ms);
    std::cout << "cost=" << format_cost(grid::to_cells(t.result.cost)) << " steps=" << t.result.steps()
              << " expansions=" << t.result.expansions << " time_ms=" << time << "\n";
    return kOk;
  } catch (const grid::FormatError& e) {
    throw InputError(e.file(), e.line() > 0 ? "line " + std::to_string(e.line()) : "", e.message());
  }
}

}  // namespace

Command add_plan(CLI::App& app) {
  auto o = std::make_shared<PlanOptions>();
  std::vector<std::string> names;
  for (const auto& entry : kGridPlanners) names.emplace_back(entry.name);
  app.add_option("--planner", o->planner, "Planner (D* Lite and LPA*: their first plan)")
      ->capture_default_str()
      ->check(CLI::IsMember(names));
  app.add_option("--map", o->map, "Grid map in the MovingAI .map format")->required();
  app.add_option("--start", o->start, "Start cell X,Y (column, row; 0,0 is the top-left cell)");
  app.add_option("--goal", o->goal, "Goal cell X,Y");
  app.add_option("--scen", o->scen, "MovingAI scenario file: solve every problem in it, print CSV");
  app.footer(
      "Plans on a 2D grid map, 8-connected: straight moves cost 1, diagonal moves sqrt(2), and a\n"
      "diagonal needs both orthogonal neighbours free (no corner cutting), as the MovingAI\n"
      "benchmark defines.\n"
      "FILE.map: 'type octile', 'height H', 'width W', 'map', then H rows of W cells: '.' 'G' 'S'\n"
      "passable, '@' 'O' 'T' 'W' blocked; x is the column, y the row, (0,0) the top-left cell.\n"
      "With --start X,Y --goal X,Y prints one line:\n"
      "  cost=C steps=S expansions=E time_ms=T\n"
      "with C the path cost in cells (-1 when no path exists), S the moves, E the nodes expanded\n"
      "and T the search time in milliseconds.\n"
      "With --scen FILE.scen ('version 1', then one problem per line: bucket, map, width, height,\n"
      "start x, start y, goal x, goal y, optimal length) solves every problem and prints CSV:\n"
      "  index,start_x,start_y,goal_x,goal_y,optimal,cost,match\n"
      "with match 1 when the cost equals the file's optimal length (within 1e-3, or 1e-4 relative),\n"
      "and a summary on stderr.\n"
      "Exit 0 when done (with --scen: every cost matched), 1 when a cost did not match or on an\n"
      "internal failure, 2 on bad input (the error names the file, the line and what was expected).");
  return [o] { return run_plan(*o); };
}

}  // namespace campo::cli
