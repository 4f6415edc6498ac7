#pragma once
/// The planner workloads that `campo bench planners|guards` and the
/// micro-benchmarks (bench/depth_reactive_bench.cpp, bench/octomap_bench.cpp)
/// both measure, built in one place so that the guarded figures and the
/// micro-benchmarks' figures are of the same work.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "campo/range_scan.hpp"
#include "campo/scene.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/depth_reactive_steps.hpp"

namespace campo {

/// depth_reactive's first replanning of a scene: the scan of its first
/// vehicle's first sensor (at `resolution` x `resolution`) from the vehicle's
/// start, and the first mission waypoint it replans toward.
struct StartView {
  RangeSensorConfig sensor;
  DepthGrid grid;
  RangeScan scan;
  Eigen::Vector3d target_m = Eigen::Vector3d::Zero();  ///< world frame
};
StartView start_view(const Scene& scene, int resolution);

/// One replanning step as depth_reactive takes it at `view` with `config`'s
/// defaults for the search (`params`: dilation_params(config, view.grid);
/// `target_sensor`: view.target_m in the sensor frame): the depth map,
/// DilataMappa, ControllaVisibilita and TrovaWP.
WaypointSearch replan_step(const StartView& view, const DilationParams& params, const Eigen::Vector3d& target_sensor,
                           const DepthReactiveConfig& config);

/// One scan as dstar_lite_3d hands it to its map: the origin, every beam's
/// end (the hit, or the end of the beam without a return) and its return flag.
struct MappedScan {
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> ends_m;
  std::vector<std::uint8_t> returns;
};

/// The scanner of the mapping figures: 64 x 8 beams over 90 x 30 deg, 20 m.
RangeSensorConfig mapping_scanner_64x8();

/// A flight through scenes/bridge.json (`scene`) as the bridge route flies
/// it, looking north: a climb from 1 m to 14 m above the ground at x = 24 m
/// in 40 steps, then `north_scans` scans north under the deck, 0.1 m apart;
/// each scan cast by campo's Lidar with `sensor`.
std::vector<MappedScan> bridge_flight(const Scene& scene, const RangeSensorConfig& sensor, int north_scans);

}  // namespace campo
