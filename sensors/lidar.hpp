#pragma once
/// Ray-cast LIDAR (SPEC §6): beams from a LidarConfig cast in one batch, with
/// seeded noise, dropout and quantization; range image, point cloud, and the
/// normalized depth map that the depth-map planners read.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/lidar_config.hpp"
#include "campo/lidar_scan.hpp"
#include "campo/random.hpp"
#include "sensors/ray_fan.hpp"
#include "sensors/raycaster.hpp"

namespace campo {

class Lidar {
 public:
  /// `world_seed` is combined with config.seed for the noise stream.
  Lidar(const LidarConfig& config, std::uint64_t world_seed);

  const LidarConfig& config() const { return config_; }
  /// Unit beam directions in the sensor frame, beam order.
  const std::vector<Eigen::Vector3f>& directions() const { return directions_sensor_; }

  /// Scans from `sensor_pose` (world frame); reuses `out`'s buffers.
  void scan(const RayCaster& caster, const Eigen::Isometry3d& sensor_pose, double time_s,
            LidarScan& out);

 private:
  LidarConfig config_;
  Rng rng_;
  std::vector<Eigen::Vector3f> directions_sensor_;
  RayFan fan_;                // the beams binned once, cast from each scan's pose
  std::vector<RayHit> hits_;  // scratch, reused
};

/// Sets a scan's header and sizes its buffers for `beams` beams (points
/// emptied, capacity kept); shared by every RangeSensor.
void begin_scan(LidarScan& out, int rows, int cols, std::size_t beams, double time_s,
                const Eigen::Isometry3d& sensor_pose);
/// A measured range as reported: rounded to the config's quantization step
/// (if any) and clamped to [0, max_range_m], as a real sensor reports neither
/// negative ranges nor ranges beyond its maximum.
float reported_range(double range_m, const LidarConfig& config);

/// Unit direction of a beam in the sensor frame (x forward, y left, z up).
Eigen::Vector3f beam_direction(const Beam& beam);
/// The beams of a config in beam order (explicit list, or the grid row-major).
std::vector<Beam> lidar_beams(const LidarConfig& config);

/// Depth map of SPEC §6 as CV_32F rows x cols: value = range / max_range_m in
/// [0, 1], 0 where the range is below min_range_m, 1 where nothing was hit.
cv::Mat depth_map(const LidarScan& scan, const LidarConfig& config);

}  // namespace campo
