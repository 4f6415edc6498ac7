#include "tools/bench_workloads.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "campo/pose.hpp"
#include "sensors/lidar.hpp"
#include "sensors/raycaster.hpp"

namespace campo {

StartView start_view(const Scene& scene, int resolution) {
  const VehicleDef& drone = scene.vehicles.front();
  StartView v;
  v.sensor = drone.sensors.front().range;
  v.sensor.cols = v.sensor.rows = resolution;
  v.target_m = drone.mission.front().position_m;
  const RayCaster caster(scene);
  Lidar lidar(v.sensor, scene.world.seed);
  lidar.scan(caster, drone.pose * to_isometry(v.sensor.mount), 0.0, v.scan);
  v.grid = DepthGrid::of(v.scan, v.sensor);
  return v;
}

WaypointSearch replan_step(const StartView& view, const DilationParams& params, const Eigen::Vector3d& target_sensor,
                           const DepthReactiveConfig& config) {
  const cv::Mat dilated = dilate_depth_map(depth_map(view.scan, view.sensor), params);
  const VisibilityCheck check = check_visibility(dilated, view.grid, target_sensor, config.safety_radius_m);
  return find_waypoint(dilated, view.grid, check.pixel, check.waypoint_range_m / view.grid.max_range_m,
                       check.obstacle_range_m / view.grid.max_range_m, find_waypoint_params(config));
}

RangeSensorConfig mapping_scanner_64x8() {
  RangeSensorConfig c;
  c.fov_h_deg = 90.0;
  c.fov_v_deg = 30.0;
  c.cols = 64;
  c.rows = 8;
  c.max_range_m = 20.0;
  return c;
}

std::vector<MappedScan> bridge_flight(const Scene& scene, const RangeSensorConfig& sensor, int north_scans) {
  const RayCaster caster(scene);
  Lidar lidar(sensor, scene.world.seed);
  // The bridge route's cruise height over the rolling ground at x = 24 m.
  const double x = 24.0, cruise_z = 14.0 + std::sin(x / 5.0);
  constexpr int kClimbSteps = 40;
  std::vector<MappedScan> flight;
  RangeScan scan;
  for (int i = 0; i <= kClimbSteps + north_scans; ++i) {
    const Eigen::Vector3d p = i <= kClimbSteps
                                  ? Eigen::Vector3d(x, 0.75, 1.0 + (cruise_z - 1.0) * i / kClimbSteps)
                                  : Eigen::Vector3d(x, 0.75 + 0.1 * (i - kClimbSteps), cruise_z);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = p;
    pose.linear() = Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    lidar.scan(caster, pose, 0.0, scan);
    // As dstar_lite_3d's insert_rays: a beam without a return ends at its range.
    MappedScan m{p, {}, scan.hits};
    m.ends_m.reserve(scan.ranges_m.size());
    for (std::size_t r = 0; r < scan.ranges_m.size(); ++r) {
      m.ends_m.push_back(p + pose.linear() * lidar.directions()[r].cast<double>() * static_cast<double>(scan.ranges_m[r]));
    }
    flight.push_back(std::move(m));
  }
  return flight;
}

}  // namespace campo
