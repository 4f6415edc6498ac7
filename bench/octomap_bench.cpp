// OctoMap mapping (dstar_lite_3d's "mapping": "octomap"): the cost of
// OctoMap3d::insert_scan per LIDAR scan over a flight through the bridge scene
// (scenes/bridge.json), with the scene's LIDAR (the Leddar fan of 8 x 8 beams
// over 48 x 48 deg, 100 m range, level) and with a 64 x 8 scanner of 20 m
// range (90 x 30 deg), on the planner's 0.75 m voxels and 100 x 100 x 9 grid.
// The scans are cast once by campo's Lidar before timing; one iteration maps a
// whole flight into a fresh map, so the octree grows as it does in a run; the
// _cold variants evict the caches between scans.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "campo/scene_loader.hpp"
#include "planners/octomap3d.hpp"
#include "tools/bench_workloads.hpp"

namespace campo {
namespace {

RangeSensorConfig leddar_8x8() {
  RangeSensorConfig c = *sensor_preset("leddar_vu8");
  c.fov_h_deg = 48.0;  // as scenes/bridge.json sets it
  c.fov_v_deg = 48.0;
  c.cols = 8;
  c.rows = 8;
  c.mount = Pose{};
  return c;
}

// The bridge route's flight (tools/bench_workloads.hpp): 41 scans up, 600 north (the run
// flies 581 scans in about 60 m).
std::vector<MappedScan> bridge_flight(const RangeSensorConfig& config) {
  return campo::bridge_flight(load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/bridge.json"), config, 600);
}

// The planner's grid over the bridge scene: 100 x 100 cells of 1.5 m, 9 levels 7 m apart.
GridMap3dConfig bridge_grid() {
  GridMap3dConfig g;
  g.ground_z_m = 0.3;
  return g;
}

// With `cold`, 64 MB are written between scans, untimed, so every scan finds
// the octree out of the caches, as in a run, where the physics, the sensors
// and the search run between two scans.
void BM_OctoMapInsertScan(benchmark::State& state, RangeSensorConfig (*sensor)(), bool cold) {
  const std::vector<MappedScan> flight = bridge_flight(sensor());
  std::vector<std::uint64_t> evict(cold ? (64u << 20) / sizeof(std::uint64_t) : 0);
  std::optional<OctoMap3d> map;
  std::int64_t scans = 0, changes = 0, occupied = 0;
  for (auto _ : state) {
    state.PauseTiming();
    map.reset();
    map.emplace(bridge_grid(), OctoMap3dConfig{});
    state.ResumeTiming();
    for (const MappedScan& s : flight) {
      if (cold) {
        state.PauseTiming();
        for (std::uint64_t& v : evict) v += 1;
        benchmark::ClobberMemory();
        state.ResumeTiming();
      }
      changes += static_cast<std::int64_t>(map->insert_scan(s.origin_m, s.ends_m, s.returns).size());
    }
    scans += static_cast<std::int64_t>(flight.size());
    occupied = map->occupied_leaf_count();
  }
  state.SetItemsProcessed(scans);
  state.counters["per_scan"] = benchmark::Counter(static_cast<double>(scans),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["scans"] = static_cast<double>(flight.size());
  state.counters["cell_changes_per_flight"] = static_cast<double>(changes) / static_cast<double>(state.iterations());
  state.counters["occupied_leaves"] = static_cast<double>(occupied);
}

BENCHMARK_CAPTURE(BM_OctoMapInsertScan, bridge_leddar_8x8_100m, &leddar_8x8, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OctoMapInsertScan, bridge_lidar_64x8_20m, &mapping_scanner_64x8, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OctoMapInsertScan, bridge_leddar_8x8_100m_cold, &leddar_8x8, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OctoMapInsertScan, bridge_lidar_64x8_20m_cold, &mapping_scanner_64x8, true)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace campo
