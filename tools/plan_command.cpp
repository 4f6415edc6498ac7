#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <unistd.h>

#include "campo/json_reader.hpp"
#include "grid/astar.hpp"
#include "grid/dstar_lite.hpp"
#include "grid/lpa_star.hpp"
#include "grid/movingai.hpp"
#include "planners/dubins.hpp"
#include "planners/rrt_star.hpp"
#include "sweep/progress.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

struct PlanOptions {
  std::string planner = "astar";
  std::string map;
  std::string start;
  std::string goal;
  std::string scen;
  std::string from;
  std::string to;
  std::string radius;
  std::string seed;
  std::string iterations;
  std::string step;
  std::string time_limit;
  std::string progress_every;
  // Set by add_plan: which options the command line gave.
  std::vector<std::pair<std::string, const CLI::Option*>> given;

  bool has(std::string_view name) const {
    for (const auto& [option, cli] : given) {
      if (option == name) return cli->count() > 0;
    }
    return false;
  }
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
constexpr std::string_view kDubins = "dubins";
constexpr std::string_view kRrtStar = "rrt_star";

// RRT* on the command line: the defaults of --iterations and --step, the
// goal region (the goal cell's centre itself: the goal is sampled with
// probability goal_bias and steered onto exactly, and the node there is
// rewired like any other, so the cost is centre to centre like the octile
// optimum's) and the tolerance of `match` in scenario CSV.
constexpr int kRrtDefaultIterations = 20000;
constexpr double kRrtDefaultStep = 5.0;
constexpr double kRrtGoalRadius = 1e-6;
constexpr double kRrtMatchTolerance = 0.10;

GridPlanner planner_from_name(std::string_view name) {
  for (const auto& entry : kGridPlanners) {
    if (entry.name == name) return entry.planner;
  }
  throw InputError("command line", "--planner", "no grid planner \"" + std::string(name) + "\"");
}

// Options that the planner does not take are errors, not silently ignored.
void reject(const PlanOptions& o, std::initializer_list<std::string_view> options) {
  for (const std::string_view option : options) {
    if (o.has(option)) {
      throw InputError("command line", std::string(option),
                       "does not apply to --planner " + o.planner + " (see campo plan --help)");
    }
  }
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

std::string format_ms(double ms) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", ms);
  return buffer;
}

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// How far the planning has come, on stderr as a sweep shows it (sweep/progress.hpp): on a
// terminal one bar redrawn in place (from the first second on, at most 10 times a second),
// otherwise a plain line every --progress-every seconds (default 10), so quick plans print
// nothing. Also the --time-limit deadline: update() returns false once it has passed.
class PlanProgress {
 public:
  using Clock = std::chrono::steady_clock;

  PlanProgress(std::string what, double time_limit_s, double every_s)
      : what_(std::move(what)), time_limit_s_(time_limit_s), every_s_(every_s), tty_(::isatty(STDERR_FILENO) == 1) {}

  /// The work ahead: `items` (problems) of `per_item` units each (iterations; 1 for a grid search).
  void expect(std::size_t items, std::uint64_t per_item, std::string unit) {
    per_item_ = per_item;
    total_ = static_cast<std::uint64_t>(items) * per_item;
    unit_ = std::move(unit);
  }
  /// Item `index` (0-based) begins.
  void begin_item(std::size_t index) { base_ = static_cast<std::uint64_t>(index) * per_item_; }
  /// Item `index` has ended (a search that was not stopped ran every unit).
  void end_item(std::size_t index) {
    if (!timed_out_) done_ = static_cast<std::uint64_t>(index + 1) * per_item_;
  }
  /// `done` units of the current item are done; false when the time limit has passed.
  bool update(std::uint64_t done) {
    done_ = base_ + done;
    const Clock::time_point now = Clock::now();
    const double elapsed = seconds(now - start_);
    if (time_limit_s_ > 0.0 && elapsed >= time_limit_s_) {
      timed_out_ = true;
      return false;
    }
    if (tty_ ? elapsed >= 1.0 && seconds(now - last_) >= 0.1 : seconds(now - last_) >= every_s_) {
      last_ = now;
      show(elapsed);
    }
    return true;
  }
  /// A terminal's bar keeps its last state on a line of its own.
  void finish() {
    if (!drawn_) return;
    show(seconds(Clock::now() - start_));
    std::cerr << "\n";
  }
  bool timed_out() const { return timed_out_; }

 private:
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  // "[#####.........] rrt_star: 1234567/10000000 iterations | 81234 iterations/s | ETA 1m48s"
  void show(double elapsed_s) {
    const double fraction = total_ == 0 ? 0.0 : static_cast<double>(done_) / static_cast<double>(total_);
    std::string line = what_ + ": " + std::to_string(done_) + "/" + std::to_string(total_) + " " + unit_;
    if (done_ > 0 && elapsed_s > 0.0) {
      char pace[64];
      std::snprintf(pace, sizeof pace, " | %.0f %s/s", static_cast<double>(done_) / elapsed_s, unit_.c_str());
      line += pace;
      line += " | ETA " + format_duration(elapsed_s / fraction - elapsed_s);
    } else {
      line += " | ETA --";
    }
    if (!tty_) {
      std::cerr << "progress: " << line << "\n";
      return;
    }
    constexpr int kWidth = 30;
    const int filled = std::clamp(static_cast<int>(fraction * kWidth), 0, kWidth);
    std::cerr << "\r[" << std::string(static_cast<std::size_t>(filled), '#')
              << std::string(static_cast<std::size_t>(kWidth - filled), '.') << "] " << line << "\033[K" << std::flush;
    drawn_ = true;
  }

  std::string what_;
  double time_limit_s_;  // 0: none
  double every_s_;
  bool tty_;
  std::string unit_;
  std::uint64_t per_item_ = 1;
  std::uint64_t total_ = 0;
  std::uint64_t base_ = 0;
  std::uint64_t done_ = 0;
  bool drawn_ = false;
  bool timed_out_ = false;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_ = start_;
};

// One solved scenario problem: the cost in cells (-1 when unsolved) and the
// time spent planning.
struct Solved {
  double cost = -1.0;
  double time_ms = 0.0;
};

// Solves every problem of --scen and prints the CSV; `match` decides the last
// column, `what` names the criterion in the summary on stderr.
// `progress` counts `per_problem` units a problem and may stop before a problem at the time limit.
int run_scenario(const PlanOptions& o, const grid::MovingAiMap& map,
                 const std::function<Solved(const grid::Cell&, const grid::Cell&)>& solve,
                 const std::function<bool(double cost, double optimal)>& match, const std::string& what,
                 PlanProgress& progress, std::uint64_t per_problem, const std::string& unit) {
  const auto problems = grid::read_movingai_scenario(o.scen);
  grid::check_scenario(o.scen, problems, map);
  progress.expect(problems.size(), per_problem, unit);
  std::cout << "index,start_x,start_y,goal_x,goal_y,optimal,cost,match\n";
  std::size_t mismatches = 0;
  double total_ms = 0.0;
  std::size_t tried = 0;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    progress.begin_item(i);
    if (!progress.update(0)) break;
    ++tried;
    const grid::MovingAiProblem& p = problems[i];
    const Solved s = solve(p.start, p.goal);
    progress.end_item(i);
    const bool matched = match(s.cost, p.optimal_length);
    mismatches += matched ? 0 : 1;
    total_ms += s.time_ms;
    std::cout << i << ',' << p.start.x << ',' << p.start.y << ',' << p.goal.x << ',' << p.goal.y << ','
              << format_cost(p.optimal_length) << ',' << format_cost(s.cost) << ',' << (matched ? 1 : 0) << '\n';
  }
  progress.finish();
  char searching[64];
  std::snprintf(searching, sizeof searching, "%.1f ms searching", total_ms);
  std::cerr << tried - mismatches << " of " << problems.size() << " problems " << what << " (" << o.planner << ", "
            << searching << ")";
  if (progress.timed_out()) {
    std::cerr << "; stopped at --time-limit " << o.time_limit << " s with " << problems.size() - tried
              << " problems not tried";
  }
  std::cerr << "\n";
  // A wrong length is a bug; problems left untried at the user's time limit are not.
  if (mismatches > 0) return kInternalError;
  return tried == problems.size() ? kOk : kIncomplete;
}

// Either --start and --goal (true) or --scen (false), never both or neither.
bool single_problem(const PlanOptions& o) {
  if (!o.has("--map")) {
    throw InputError("command line", "--map", "expected --map FILE.map with --planner " + o.planner);
  }
  const bool single = o.has("--start") || o.has("--goal");
  if (single == o.has("--scen")) {
    throw InputError("command line", "--scen", "expected either --start X,Y and --goal X,Y, or --scen FILE.scen");
  }
  if (single && !(o.has("--start") && o.has("--goal"))) {
    throw InputError("command line", o.has("--start") ? "--goal" : "--start",
                     "expected both --start X,Y and --goal X,Y");
  }
  return single;
}

// Map and scenario format errors as InputErrors naming the file and line.
template <class F>
int with_format_errors(F&& run) {
  try {
    return run();
  } catch (const grid::FormatError& e) {
    throw InputError(e.file(), e.line() > 0 ? "line " + std::to_string(e.line()) : "", e.message());
  }
}

// --time-limit and --progress-every (seconds), read before any work; 0: no time limit.
struct ProgressOptions {
  double time_limit_s = 0.0;
  double every_s = 10.0;
};
constexpr double kMinSeconds = 1e-3;
constexpr double kMaxSeconds = 1e6;
ProgressOptions parse_progress_options(const PlanOptions& o);

int run_grid(const PlanOptions& o) {
  const GridPlanner planner = planner_from_name(o.planner);
  reject(o, {"--from", "--to", "--radius", "--seed", "--iterations", "--step"});
  const bool single = single_problem(o);
  const ProgressOptions progress_options = parse_progress_options(o);
  return with_format_errors([&] {
    const grid::MovingAiMap map = grid::read_movingai_map(o.map);
    grid::GridGraph graph = grid::to_grid_graph(map);
    Solver solver(graph, planner);
    if (!single) {
      // One search is bounded by the map (at most 4096 x 4096 cells); the problems are counted.
      PlanProgress progress(o.planner, progress_options.time_limit_s, progress_options.every_s);
      return run_scenario(
          o, map,
          [&](const grid::Cell& start, const grid::Cell& goal) {
            const auto t0 = std::chrono::steady_clock::now();
            const grid::SearchResult result = solver.solve(start, goal);
            return Solved{grid::to_cells(result.cost), elapsed_ms(t0)};
          },
          [](double cost, double optimal) { return grid::matches_optimal(cost, optimal); }, "at the optimal length",
          progress, 1, "problems");
    }
    const grid::Cell start = parse_cell(o.start, "--start", map), goal = parse_cell(o.goal, "--goal", map);
    const auto t0 = std::chrono::steady_clock::now();
    const grid::SearchResult result = solver.solve(start, goal);
    const double time_ms = elapsed_ms(t0);
    std::cout << "cost=" << format_cost(grid::to_cells(result.cost)) << " steps=" << result.steps()
              << " expansions=" << result.expansions << " time_ms=" << format_ms(time_ms) << "\n";
    return static_cast<int>(kOk);
  });
}

// ---- numbers on the command line ----

// Accepted ranges. Dubins: coordinates within 10,000 km, headings within a
// million degrees and radii from a micrometre to 10,000 km keep every
// intermediate (distances over the radius, angles) finite and exact enough.
// RRT*: the step's limits are RrtStarConfig's (cells are metres here).
constexpr double kMaxCoordinateM = 1e7;
constexpr double kMaxHeadingDeg = 1e6;
constexpr double kMinRadiusM = 1e-6;
constexpr double kMaxRadiusM = 1e7;

// 1e-06 -> "1e-06", 1000000 -> "1000000".
std::string format_limit(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

std::optional<double> to_number(std::string_view text) {
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// A number in [min, max]: bounds keep the work of every planner bounded and
// its arithmetic finite (see docs/planners.md, "Limits of campo plan").
double parse_in_range(const std::string& text, const std::string& option, const std::string& what, double min,
                      double max) {
  const auto value = to_number(text);
  if (!value || !(*value >= min && *value <= max)) {
    throw InputError("command line", option,
                     "expected " + what + ", a number in [" + format_limit(min) + ", " + format_limit(max) +
                         "], got \"" + text + "\"");
  }
  return *value;
}

ProgressOptions parse_progress_options(const PlanOptions& o) {
  ProgressOptions p;
  if (o.has("--time-limit")) {
    p.time_limit_s = parse_in_range(o.time_limit, "--time-limit", "seconds of wall time", kMinSeconds, kMaxSeconds);
  }
  if (o.has("--progress-every")) {
    p.every_s = parse_in_range(o.progress_every, "--progress-every", "seconds between progress lines", kMinSeconds,
                               kMaxSeconds);
  }
  return p;
}

template <class Int>
Int parse_integer(const std::string& text, const std::string& option, Int min, Int max) {
  Int value{};
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || value < min || value > max) {
    throw InputError("command line", option,
                     "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got \"" +
                         text + "\"");
  }
  return value;
}

// "X,Y,HEADING" (metres, metres, degrees counter-clockwise from +x).
dubins::Pose2 parse_pose(const std::string& text, const std::string& option) {
  std::array<double, 3> v{};
  std::size_t begin = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t comma = i < 2 ? text.find(',', begin) : text.size();
    const auto value = comma == std::string::npos ? std::nullopt
                                                  : to_number(std::string_view(text).substr(begin, comma - begin));
    const double limit = i < 2 ? kMaxCoordinateM : kMaxHeadingDeg;
    if (!value || std::abs(*value) > limit || (i == 2 && text.find(',', begin) != std::string::npos)) {
      throw InputError("command line", option,
                       "expected X,Y,HEADING (metres, metres, degrees counter-clockwise from +x; |X|, |Y| <= " +
                           format_limit(kMaxCoordinateM) + ", |HEADING| <= " + format_limit(kMaxHeadingDeg) +
                           "), got \"" + text + "\"");
    }
    v[i] = *value;
    begin = comma + 1;
  }
  return {v[0], v[1], v[2] * std::numbers::pi / 180.0};
}

std::string fixed6(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  return buffer;
}

int run_dubins(const PlanOptions& o) {
  reject(o, {"--map", "--start", "--goal", "--scen", "--seed", "--iterations", "--step", "--time-limit",
             "--progress-every"});
  for (const char* option : {"--from", "--to", "--radius"}) {
    if (!o.has(option)) {
      throw InputError("command line", option,
                       "expected --from X,Y,HEADING --to X,Y,HEADING --radius R with --planner dubins");
    }
  }
  const dubins::Pose2 from = parse_pose(o.from, "--from"), to = parse_pose(o.to, "--to");
  const double radius =
      parse_in_range(o.radius, "--radius", "the turning radius in metres", kMinRadiusM, kMaxRadiusM);
  const dubins::Path path = dubins::shortest_path(from, to, radius);
  std::cout << "word=" << dubins::to_string(path.word) << " length=" << fixed6(path.length_m()) << " segments="
            << fixed6(path.segment_lengths_m[0]) << ',' << fixed6(path.segment_lengths_m[1]) << ','
            << fixed6(path.segment_lengths_m[2]) << "\n";
  return kOk;
}

// One RRT* problem on the map's 1 m grid. The tree's path ends within
// kRrtGoalRadius of the goal cell's centre; a last straight to the centre
// (when not already there) completes it.
struct RrtRun {
  RrtStarResult result;
  double time_ms = 0.0;
  double cost = -1.0;  ///< cells (= metres), -1 when unsolved
};

RrtRun solve_rrt(const OccupancyGrid& occupancy, const grid::MovingAiMap& map, const grid::Cell& start,
                 const grid::Cell& goal, const RrtStarConfig& config, PlanProgress& progress) {
  const Eigen::Vector2d goal_m = movingai_cell_centre(map, goal);
  const auto t0 = std::chrono::steady_clock::now();
  RrtRun run{rrt_star(occupancy, movingai_cell_centre(map, start), goal_m, config,
                      [&](int done) { return progress.update(static_cast<std::uint64_t>(done)); })};
  run.time_ms = elapsed_ms(t0);
  if (run.result.status == RrtStarStatus::solved) {
    run.cost = run.result.cost_m;
    const double last = (goal_m - run.result.path_m.back()).norm();
    if (last > 0.0) {
      run.result.path_m.push_back(goal_m);
      run.cost += last;
    }
  }
  return run;
}

int run_rrt_star(const PlanOptions& o) {
  reject(o, {"--from", "--to", "--radius"});
  const bool single = single_problem(o);
  RrtStarConfig config;
  config.seed = o.has("--seed") ? parse_seed(o.seed, "command line", "--seed") : 0;
  config.max_iterations =
      o.has("--iterations") ? parse_integer<int>(o.iterations, "--iterations", 1, 10'000'000) : kRrtDefaultIterations;
  config.step_m =
      o.has("--step") ? parse_in_range(o.step, "--step", "the step in cells", kMinStepM, kMaxLengthM) : kRrtDefaultStep;
  config.goal_radius_m = kRrtGoalRadius;
  const ProgressOptions progress_options = parse_progress_options(o);
  return with_format_errors([&] {
    const grid::MovingAiMap map = grid::read_movingai_map(o.map);
    const OccupancyGrid occupancy = to_occupancy_grid(map);
    const auto iterations = static_cast<std::uint64_t>(config.max_iterations);
    if (!single) {
      PlanProgress progress(o.planner, progress_options.time_limit_s, progress_options.every_s);
      return run_scenario(
          o, map,
          [&](const grid::Cell& start, const grid::Cell& goal) {
            const RrtRun run = solve_rrt(occupancy, map, start, goal, config, progress);
            return Solved{run.cost, run.time_ms};
          },
          [](double cost, double optimal) {
            return cost >= 0.0 && cost <= (1.0 + kRrtMatchTolerance) * optimal + 1e-3;
          },
          "at most 10 % longer than the optimal length", progress, iterations, "iterations");
    }
    const grid::Cell start = parse_cell(o.start, "--start", map), goal = parse_cell(o.goal, "--goal", map);
    PlanProgress progress(o.planner, progress_options.time_limit_s, progress_options.every_s);
    progress.expect(1, iterations, "iterations");
    const RrtRun run = solve_rrt(occupancy, map, start, goal, config, progress);
    progress.end_item(0);
    progress.finish();
    const std::size_t steps = run.result.path_m.empty() ? 0 : run.result.path_m.size() - 1;
    std::cout << "cost=" << format_cost(run.cost) << " steps=" << steps << " iterations=" << run.result.iterations
              << " first_solution=" << run.result.first_solution_iteration << " time_ms=" << format_ms(run.time_ms)
              << "\n";
    if (run.result.stopped) {
      std::cerr << "rrt_star: stopped at --time-limit " << o.time_limit << " s after " << run.result.iterations
                << " of " << config.max_iterations << " iterations; the path is the best found by then\n";
    }
    return static_cast<int>(kOk);
  });
}

int run_plan(const PlanOptions& o) {
  if (o.planner == kDubins) return run_dubins(o);
  if (o.planner == kRrtStar) return run_rrt_star(o);
  return run_grid(o);
}

}  // namespace

Command add_plan(CLI::App& app) {
  auto o = std::make_shared<PlanOptions>();
  std::vector<std::string> names;
  for (const auto& entry : kGridPlanners) names.emplace_back(entry.name);
  names.emplace_back(kRrtStar);
  names.emplace_back(kDubins);
  const auto add = [&](const char* name, std::string& value, const char* description) {
    o->given.emplace_back(name, app.add_option(name, value, description));
  };
  app.add_option("--planner", o->planner,
                 "Planner: astar, dstar_lite, lpa_star (grid searches; D* Lite and LPA*: their first plan), "
                 "rrt_star (sampling, on the map's 1 m cells), dubins (no map)")
      ->capture_default_str()
      ->check(CLI::IsMember(names));
  add("--map", o->map, "Grid map in the MovingAI .map format (grid planners and rrt_star)");
  add("--start", o->start, "Start cell X,Y (column, row; 0,0 is the top-left cell)");
  add("--goal", o->goal, "Goal cell X,Y");
  add("--scen", o->scen, "MovingAI scenario file: solve every problem in it, print CSV");
  for (const char* file : {"--map", "--scen"}) app.get_option(file)->check(input_path());
  add("--seed", o->seed, "rrt_star: seed of the sampler (default 0)");
  add("--iterations", o->iterations, "rrt_star: iterations, 1 to 10000000 (default 20000)");
  add("--step", o->step, "rrt_star: farthest a new node lies from the tree, cells, 0.001 to 1000000 (default 5)");
  add("--time-limit", o->time_limit,
      "Seconds of wall time the planning may take, 0.001 to 1000000 (default: none): rrt_star stops its search "
      "there with the best path so far; with --scen, the problems not yet tried are not (exit 1)");
  add("--progress-every", o->progress_every,
      "Seconds between progress lines when stderr is not a terminal, 0.001 to 1000000 (default 10; on a "
      "terminal, a progress bar with ETA from the first second on)");
  add("--from", o->from,
      "dubins: start pose X,Y,HEADING (metres, metres, degrees CCW from +x; |X|, |Y| <= 1e7, |HEADING| <= 1e6)");
  add("--to", o->to, "dubins: goal pose X,Y,HEADING");
  add("--radius", o->radius, "dubins: minimum turning radius in metres, 1e-06 to 1e+07");
  app.footer(
      "  campo plan [--planner astar|dstar_lite|lpa_star] --map FILE.map (--start X,Y --goal X,Y | --scen FILE.scen)\n"
      "  campo plan --planner rrt_star --map FILE.map (--start X,Y --goal X,Y | --scen FILE.scen)\n"
      "             [--seed N] [--iterations N] [--step CELLS]\n"
      "  (map planners also take [--time-limit S] [--progress-every S])\n"
      "  campo plan --planner dubins --from X,Y,HEADING --to X,Y,HEADING --radius R\n"
      "\n"
      "Grid planners plan on a 2D grid map, 8-connected: straight moves cost 1, diagonal moves\n"
      "sqrt(2), and a diagonal needs both orthogonal neighbours free (no corner cutting), as the\n"
      "MovingAI benchmark defines.\n"
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
      "\n"
      "rrt_star: RRT* in the plane of the map's cells taken as 1 m squares, from the centre of the\n"
      "start cell to the centre of the goal cell, straight segments through free cells only. Its\n"
      "paths are any-angle and may pass a blocked cell at its corner, so they can be shorter than\n"
      "the 8-connected optimum. Deterministic: the same seed gives the same path (the budget is\n"
      "iterations, not time). With --start and --goal prints one line:\n"
      "  cost=C steps=S iterations=I first_solution=K time_ms=T\n"
      "with C the path length in cells (= metres; -1 when no path was found within the iterations),\n"
      "S the segments, I the iterations run and K the iteration that first reached the goal (-1:\n"
      "never). With --scen prints the same CSV, with match 1 when a path was found and its cost is\n"
      "at most 10 % longer than the file's optimal length (RRT* is asymptotically optimal, not\n"
      "exact), and a summary on stderr. --step is 0.001 to 1000000 cells; each iteration checks at\n"
      "most k(n) = ceil(3e ln n) neighbours of a new node, n the tree's size, whatever the map's size.\n"
      "\n"
      "dubins: the shortest path forward-only with a minimum turning radius between two poses (no\n"
      "map, no obstacles); HEADING in degrees, counter-clockwise from +x. Prints one line:\n"
      "  word=LSL length=L segments=A,B,C\n"
      "with the word (L left arc, R right arc, S straight), the length and the three segment\n"
      "lengths in metres, 6 decimals; a segment that is not needed has length 0. Accepted: |X|, |Y|\n"
      "up to 1e7 m, |HEADING| up to 1e6 degrees, R from 1e-6 to 1e7 m.\n"
      "\n"
      "Planning that lasts shows how far it has come on stderr: on a terminal a bar with ETA (from the\n"
      "first second on), otherwise a line every 10 s (--progress-every). It ends in bounded time: one\n"
      "grid search visits each of the map's at most 4096 x 4096 cells a bounded number of times, and\n"
      "rrt_star runs at most 10000000 iterations (several minutes). --time-limit S stops rrt_star's\n"
      "search after S seconds of wall time with the best path so far (iterations= tells how many ran,\n"
      "and a line on stderr says so) and, with --scen, tries no further problem (exit 1). Without it,\n"
      "the results depend on the inputs only.\n"
      "\n"
      "Options that do not apply to the planner are errors.\n"
      "Exit 0 when done (with --scen: every cost matched), 1 when a cost did not match or on an\n"
      "internal failure, 2 on bad input (the error names the option or the file, the line and\n"
      "what was expected).");
  return [o] { return run_plan(*o); };
}

}  // namespace campo::cli
