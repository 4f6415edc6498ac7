// D* Lite against A* from scratch during the recorded obstacle_field mission
// (SPEC §7.2, issue target: incremental replanning >= 10x faster, median; first
// plan < 10 ms). The mission is flown once in closed loop with dstar_lite_3d;
// its recorded LIDAR hits, start cells and goals are then replayed into the
// same 100 x 100 x 9 map, so both searches see exactly the map and the start
// the planner had at each of its replanning moments.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"
#include "grid/astar.hpp"
#include "grid/dstar_lite.hpp"
#include "planners/dstar_lite_3d.hpp"

namespace campo {
namespace {

using Clock = std::chrono::steady_clock;

// One replanning moment of the mission: what the scan changed, where the
// vehicle was and where it was going; the first moment of a leg starts a new search.
struct Moment {
  grid::Cell start;
  grid::Cell goal;
  std::vector<grid::CellChange> changes;
  bool new_leg = false;
};

struct RecordedMission {
  GridMap3dConfig map;
  double level_step_cells = 1.0;
  grid::Connectivity connectivity = grid::Connectivity::twenty_six;
  std::vector<Moment> moments;
};

grid::Cell cell(const nlohmann::json& j) { return {j.at(0).get<int>(), j.at(1).get<int>(), j.at(2).get<int>()}; }

RecordedMission record(const std::string& scene_name) {
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + scene_name + ".json");
  // Every hit of every scan, as the planner got them (the run's record keeps a bounded sample, run/event_log.hpp).
  std::vector<PlannerEvent> events;
  EpisodeOptions options;
  options.on_plan = [&events](std::size_t, const Observation& o, const PlanResult& plan) {
    if (!plan.decisions.empty()) events.push_back({o.time_s, plan.decisions});
  };
  const EpisodeResult flown = run_episode(scene, &make_vehicle, &create_planner, options);
  const DStarLite3dConfig config = parse_dstar_lite_3d_config(scene.vehicles.front().planner.params);
  RecordedMission mission;
  mission.map = grid_map_config(config, flown.only().trajectory.front().state.position_m.z());
  mission.level_step_cells = climb_cost_cells(config);  // as the planner searches
  mission.connectivity = config.connectivity;
  GridMap3d map(mission.map);
  std::vector<grid::CellChange> pending;
  std::optional<grid::Cell> goal;
  for (const PlannerEvent& e : events) {
    for (const Eigen::Vector3d& p : e.decisions.lidar_hits) {
      const auto changed = map.mark_hit(p);
      pending.insert(pending.end(), changed.begin(), changed.end());
    }
    if (!e.decisions.replan) continue;
    const nlohmann::json& r = e.decisions.replan->details;
    const DStarLite3dRecord& declared = dstar_lite_3d_record();
    Moment m{cell(declared.start_cell.get(r).value()), cell(declared.goal_cell.get(r).value()), std::move(pending),
             false};
    pending.clear();
    m.new_leg = !goal || !(*goal == m.goal);
    goal = m.goal;
    mission.moments.push_back(std::move(m));
  }
  return mission;
}

const RecordedMission& obstacle_field() {
  static const RecordedMission mission = record("obstacle_field");
  return mission;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Times {
  std::vector<double> first_us;   // first plan of each leg
  std::vector<double> replan_us;  // every other replanning moment
  std::int64_t replan_expansions = 0;

  // One planning moment's time (µs) and work; returns the time.
  double add(const Moment& m, double us, const grid::SearchResult& r) {
    (m.new_leg ? first_us : replan_us).push_back(us);
    if (!m.new_leg) replan_expansions += r.expansions;
    return us;
  }

  void report(benchmark::State& state) const {
    state.counters["legs"] = static_cast<double>(first_us.size() / state.iterations());
    state.counters["replans"] = static_cast<double>(replan_us.size() / state.iterations());
    state.counters["first_plan_median_us"] = median(first_us);
    state.counters["first_plan_max_us"] = first_us.empty() ? 0.0 : *std::max_element(first_us.begin(), first_us.end());
    state.counters["replan_median_us"] = median(replan_us);
    state.counters["replan_expansions"] =
        static_cast<double>(replan_expansions) / std::max<double>(1.0, static_cast<double>(replan_us.size()));
  }
};

// D* Lite as the planner runs it: a new leg resets the search on the map
// known so far; within a leg, move the start, pass the changed cells, repair.
void BM_DStarLiteMission(benchmark::State& state) {
  const RecordedMission& mission = obstacle_field();
  Times times;
  for (auto _ : state) {
    grid::GridGraph graph(GridMap3d(mission.map).size(), mission.connectivity, mission.level_step_cells);
    grid::DStarLite dstar(graph, mission.moments.front().start, mission.moments.front().goal);
    double total_us = 0.0;
    for (const Moment& m : mission.moments) {
      const auto t0 = Clock::now();
      if (m.new_leg) {
        for (const grid::CellChange& c : m.changes) graph.set_state(c.cell, c.state);
        dstar.reset(m.start, m.goal);
      } else {
        dstar.move_start(m.start);
        dstar.set_cells(m.changes);
      }
      const grid::SearchResult r = dstar.plan();
      total_us += times.add(m, std::chrono::duration<double, std::micro>(Clock::now() - t0).count(), r);
    }
    state.SetIterationTime(total_us * 1e-6);
  }
  times.report(state);
}

// A* from scratch at the same moments, on the same map.
void BM_AStarMission(benchmark::State& state) {
  const RecordedMission& mission = obstacle_field();
  Times times;
  for (auto _ : state) {
    grid::GridGraph graph(GridMap3d(mission.map).size(), mission.connectivity, mission.level_step_cells);
    grid::AStar astar(graph);
    double total_us = 0.0;
    for (const Moment& m : mission.moments) {
      for (const grid::CellChange& c : m.changes) graph.set_state(c.cell, c.state);
      const auto t0 = Clock::now();
      const grid::SearchResult r = astar.plan(m.start, m.goal);
      total_us += times.add(m, std::chrono::duration<double, std::micro>(Clock::now() - t0).count(), r);
    }
    state.SetIterationTime(total_us * 1e-6);
  }
  times.report(state);
}

BENCHMARK(BM_DStarLiteMission)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AStarMission)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace campo
