// Replanning cost of depth_reactive (seed 000) on one core, step by step, on
// the depth map its scanner sees at the start of each seed 000 scene (the
// first replanning of an episode): DilataMappa, TrovaWP's threshold and
// distance transform, the candidate search, and the whole replanning step.
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <string>

#include "campo/scene_loader.hpp"
#include "planners/depth_reactive.hpp"
#include "sensors/lidar.hpp"
#include "tools/bench_workloads.hpp"

namespace campo {
namespace {

StartView start_view(const std::string& name, int resolution) {
  return campo::start_view(load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json"), resolution);
}

DepthReactiveConfig planner_config(StructuringShape shape) {
  DepthReactiveConfig c;
  c.structuring_element = shape;
  return c;
}

void BM_DilataMappa(benchmark::State& state, const std::string& name, StructuringShape shape) {
  const StartView v = start_view(name, static_cast<int>(state.range(0)));
  const cv::Mat depth = depth_map(v.scan, v.sensor);
  const DilationParams params = dilation_params(planner_config(shape), v.grid);
  for (auto _ : state) benchmark::DoNotOptimize(dilate_depth_map(depth, params));
}

void BM_ThresholdAndDistanceTransform(benchmark::State& state, const std::string& name) {
  const StartView v = start_view(name, static_cast<int>(state.range(0)));
  const cv::Mat dilated = dilate_depth_map(depth_map(v.scan, v.sensor), dilation_params(DepthReactiveConfig{}, v.grid));
  cv::Mat distance;
  for (auto _ : state) {
    cv::distanceTransform(threshold_free(dilated, 0.6), distance, cv::DIST_L1, 3, CV_8U);
    benchmark::DoNotOptimize(distance.data);
  }
}

// TrovaWP whole (threshold, distance transform, candidate search and reachability).
void BM_TrovaWP(benchmark::State& state, const std::string& name) {
  const StartView v = start_view(name, static_cast<int>(state.range(0)));
  const DepthReactiveConfig config;
  const cv::Mat dilated = dilate_depth_map(depth_map(v.scan, v.sensor), dilation_params(config, v.grid));
  const Eigen::Vector3d target = v.scan.sensor_pose.inverse() * v.target_m;
  const VisibilityCheck check = check_visibility(dilated, v.grid, target, config.safety_radius_m);
  for (auto _ : state) {
    benchmark::DoNotOptimize(find_waypoint(dilated, v.grid, check.pixel, check.waypoint_range_m / v.grid.max_range_m,
                                           check.obstacle_range_m / v.grid.max_range_m, find_waypoint_params(config)));
  }
}

// One replanning step as the planner runs it: depth map, DilataMappa, ControllaVisibilita, TrovaWP.
void BM_Replan(benchmark::State& state, const std::string& name) {
  const StartView v = start_view(name, static_cast<int>(state.range(0)));
  const DepthReactiveConfig config;
  const DilationParams params = dilation_params(config, v.grid);
  const Eigen::Vector3d target = v.scan.sensor_pose.inverse() * v.target_m;
  for (auto _ : state) benchmark::DoNotOptimize(replan_step(v, params, target, config));
}

// The replanning step as DepthReactive::evaluate runs it at the start of an
// episode: the depth margin in ControllaVisibilita with the map before
// dilation, and TrovaWP with the blind start of the next leg, the vehicle's
// centre (the sensor pose's, close enough for cost) and the map before
// dilation (no discarded waypoints yet). BM_Replan above leaves these out.
void BM_ReplanAsPlanner(benchmark::State& state, const std::string& name) {
  const StartView v = start_view(name, static_cast<int>(state.range(0)));
  const DepthReactiveConfig config;
  const DilationParams params = dilation_params(config, v.grid);
  const Eigen::Isometry3d to_sensor = v.scan.sensor_pose.inverse();
  const Eigen::Vector3d target = to_sensor * v.target_m;
  const double margin = config.margin_in_depth ? config.dilation_margin_m : 0.0;
  FindWaypointParams search = find_waypoint_params(config);
  if (config.margin_in_depth) {
    search.next_leg_check_m = blind_leg_m(config.dilation_margin_m, 0.5 * std::min(v.sensor.fov_h_deg, v.sensor.fov_v_deg),
                                          v.sensor.mount.position_m.x());
  }
  const Eigen::Vector3d origin = to_sensor * v.scan.sensor_pose.translation();
  const Eigen::Vector3d up = to_sensor.linear() * Eigen::Vector3d::UnitZ();
  for (auto _ : state) {
    const cv::Mat depth = depth_map(v.scan, v.sensor);
    const cv::Mat dilated = dilate_depth_map(depth, params);
    const VisibilityCheck check = check_visibility(dilated, v.grid, target, config.safety_radius_m, 0.0, margin, &depth);
    benchmark::DoNotOptimize(find_waypoint(dilated, v.grid, check.pixel, check.waypoint_range_m / v.grid.max_range_m,
                                           check.obstacle_range_m / v.grid.max_range_m, search, {}, origin, up, &depth));
  }
}

void resolutions(benchmark::internal::Benchmark* b) {
  for (const int r : {16, 32, 64, 128, 256}) b->Arg(r);
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(BM_DilataMappa, trees_square, "trees_rolling_terrain", StructuringShape::square)->Apply(resolutions);
BENCHMARK_CAPTURE(BM_DilataMappa, trees_disc, "trees_rolling_terrain", StructuringShape::disc)->Apply(resolutions);
BENCHMARK_CAPTURE(BM_DilataMappa, two_barriers_square, "two_barriers", StructuringShape::square)->Apply(resolutions);
BENCHMARK_CAPTURE(BM_ThresholdAndDistanceTransform, trees, "trees_rolling_terrain")->Apply(resolutions);
BENCHMARK_CAPTURE(BM_TrovaWP, trees, "trees_rolling_terrain")->Apply(resolutions);
BENCHMARK_CAPTURE(BM_TrovaWP, two_barriers, "two_barriers")->Apply(resolutions);
BENCHMARK_CAPTURE(BM_Replan, trees, "trees_rolling_terrain")->Apply(resolutions);
BENCHMARK_CAPTURE(BM_Replan, two_barriers, "two_barriers")->Apply(resolutions);
BENCHMARK_CAPTURE(BM_ReplanAsPlanner, trees, "trees_rolling_terrain")->Apply(resolutions);
BENCHMARK_CAPTURE(BM_ReplanAsPlanner, two_barriers, "two_barriers")->Apply(resolutions);

}  // namespace
}  // namespace campo
