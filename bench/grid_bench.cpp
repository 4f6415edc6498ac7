// Grid search: A* node expansions per second, and D* Lite first plan and
// incremental replanning against A* from scratch at the same moments, on the
// SPEC §7.2 grid (100 x 100 cells of 1.5 m, 9 levels 7 m apart, 26-connected)
// over a cluttered city, while the vehicle flies along its path and a sweep
// keeps finding obstacles just ahead of it. The recorded obstacle_field
// mission is replayed in dstar_mission_bench.cpp.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "campo/random.hpp"
#include "grid/astar.hpp"
#include "grid/dstar_lite.hpp"
#include "grid/movingai.hpp"

namespace campo::grid {
namespace {

constexpr GridSize kSize{100, 100, 9};
constexpr int kGroundLevel = 2;     ///< 0 and 1 are below ground
constexpr double kLevelStep = 7.0 / 1.5;  ///< levels 7 m apart over 1.5 m cells

// A map to fly over and the leg flown.
struct Flight {
  GridGraph (*build)();
  Cell start;
  Cell goal;
};

GridGraph ground() {
  GridGraph graph(kSize, Connectivity::twenty_six, kLevelStep);
  for (int y = 0; y < kSize.height; ++y)
    for (int x = 0; x < kSize.width; ++x)
      for (int z = 0; z < kGroundLevel; ++z) graph.set_state({x, y, z}, CellState::blocked);
  return graph;
}

// A cluttered map: buildings of 7-42 m on 20 % of the ground cells (seeded).
GridGraph city() {
  GridGraph graph = ground();
  Rng rng(5);
  for (int y = 0; y < kSize.height; ++y)
    for (int x = 0; x < kSize.width; ++x) {
      if (!rng.bernoulli(0.2)) continue;
      const auto top = static_cast<int>(rng.uniform_int(kGroundLevel + 1, kSize.depth - 1));
      for (int z = kGroundLevel; z <= top; ++z) graph.set_state({x, y, z}, CellState::blocked);
    }
  graph.set_state({5, 5, 4}, CellState::free);
  graph.set_state({95, 90, 4}, CellState::free);
  return graph;
}

// The city crossed diagonally at 14 m (level 4).
const Flight kCityFlight{city, {5, 5, 4}, {95, 90, 4}};

// One replanning moment: where the vehicle is and what the sweep found.
struct Moment {
  Cell start;
  std::vector<CellChange> changes;
};

// The flight: 3 cells along the current path, then 8 cells found blocked
// around the path cell 4 ahead (the cell and 7 of its neighbours); until the
// goal is 8 cells away. Built once with D* Lite, checked against A* at every moment.
std::vector<Moment> fly(const Flight& flight) {
  GridGraph graph = flight.build();
  DStarLite dstar(graph, flight.start, flight.goal);
  AStar astar(graph);
  Rng rng(2026);
  std::vector<Moment> moments;
  SearchResult path = dstar.plan();
  while (path.status == SearchStatus::found && path.steps() > 8) {
    Moment m{path.path[3], {}};
    const Cell ahead = path.path[7];
    m.changes.push_back({ahead, CellState::blocked});
    while (m.changes.size() < 8) {
      const Cell c{ahead.x + static_cast<int>(rng.uniform_int(-1, 1)), ahead.y + static_cast<int>(rng.uniform_int(-1, 1)),
                   ahead.z + static_cast<int>(rng.uniform_int(-1, 1))};
      if (graph.contains(c) && c != m.start && c != flight.goal) m.changes.push_back({c, CellState::blocked});
    }
    dstar.move_start(m.start);
    dstar.set_cells(m.changes);
    path = dstar.plan();
    if (path.cost != astar.plan(m.start, flight.goal).cost) throw std::logic_error("D* Lite and A* disagree");
    moments.push_back(std::move(m));
  }
  return moments;
}

const std::vector<Moment>& moments(const Flight& flight) {
  static const std::vector<Moment> town = fly(flight);  // the only flight
  return town;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

using Clock = std::chrono::steady_clock;
double since_us(Clock::time_point t0) { return std::chrono::duration<double, std::micro>(Clock::now() - t0).count(); }

// A* from scratch on a 512 x 512 maze (every 40th problem of the scenario).
void BM_AStarExpansionsMaze512(benchmark::State& state) {
  const std::string dir = std::string(CAMPO_SOURCE_DIR) + "/tests/data/movingai/";
  const GridGraph graph = to_grid_graph(read_movingai_map(dir + "maze512-32-9.map"));
  const auto problems = read_movingai_scenario(dir + "maze512-32-9.map.scen");
  AStar astar(graph);
  std::int64_t expansions = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const MovingAiProblem& p = problems[i];
    i = (i + 40) % problems.size();
    expansions += astar.plan(p.start, p.goal).expansions;
  }
  state.counters["expansions_per_s"] = benchmark::Counter(static_cast<double>(expansions), benchmark::Counter::kIsRate);
}

// First plan of the leg on the 100 x 100 x 9 grid.
void BM_AStarFirstPlan3D(benchmark::State& state, const Flight* flight) {
  const GridGraph graph = flight->build();
  AStar astar(graph);
  std::int64_t expansions = 0;
  for (auto _ : state) expansions = astar.plan(flight->start, flight->goal).expansions;
  state.counters["expansions"] = static_cast<double>(expansions);
  state.counters["expansions_per_s"] = benchmark::Counter(
      static_cast<double>(expansions) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_DStarLiteFirstPlan3D(benchmark::State& state, const Flight* flight) {
  GridGraph graph = flight->build();
  DStarLite dstar(graph, flight->start, flight->goal);
  std::int64_t expansions = 0;
  for (auto _ : state) {
    dstar.reset(flight->start, flight->goal);  // O(cells): part of a first plan
    expansions = dstar.plan().expansions;
  }
  state.counters["expansions"] = static_cast<double>(expansions);
}

// Replanning times of one flight, with a median over every replan of every iteration.
struct ReplanStats {
  std::vector<double> times_us;
  std::int64_t expansions = 0;

  void report(benchmark::State& state, std::size_t replans) const {
    state.counters["replans"] = static_cast<double>(replans);
    state.counters["median_us"] = median(times_us);
    state.counters["expansions"] = static_cast<double>(expansions) / static_cast<double>(times_us.size());
  }
};

// One iteration flies the whole leg; only the replans are timed (move, map
// update and search, including the path).
void BM_DStarLiteReplan3D(benchmark::State& state, const Flight* flight) {
  ReplanStats stats;
  for (auto _ : state) {
    GridGraph graph = flight->build();
    DStarLite dstar(graph, flight->start, flight->goal);
    dstar.plan();
    double total_us = 0.0;
    for (const Moment& m : moments(*flight)) {
      const auto t0 = Clock::now();
      dstar.move_start(m.start);
      dstar.set_cells(m.changes);
      const SearchResult r = dstar.plan();
      const double us = since_us(t0);
      stats.times_us.push_back(us);
      stats.expansions += r.expansions;
      total_us += us;
    }
    state.SetIterationTime(total_us * 1e-6);
  }
  stats.report(state, moments(*flight).size());
}

// A* from scratch at the same moments, on the same map.
void BM_AStarReplan3D(benchmark::State& state, const Flight* flight) {
  ReplanStats stats;
  for (auto _ : state) {
    GridGraph graph = flight->build();
    AStar astar(graph);
    double total_us = 0.0;
    for (const Moment& m : moments(*flight)) {
      for (const CellChange& c : m.changes) graph.set_state(c.cell, c.state);
      const auto t0 = Clock::now();
      const SearchResult r = astar.plan(m.start, flight->goal);
      const double us = since_us(t0);
      stats.times_us.push_back(us);
      stats.expansions += r.expansions;
      total_us += us;
    }
    state.SetIterationTime(total_us * 1e-6);
  }
  stats.report(state, moments(*flight).size());
}

BENCHMARK(BM_AStarExpansionsMaze512)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AStarFirstPlan3D, city, &kCityFlight)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DStarLiteFirstPlan3D, city, &kCityFlight)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DStarLiteReplan3D, city, &kCityFlight)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AStarReplan3D, city, &kCityFlight)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace campo::grid
