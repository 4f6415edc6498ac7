#pragma once
/// Ray-cast LIDAR (SPEC §6): beams from a RangeSensorConfig cast in one batch, with
/// seeded noise, dropout and quantization; range image, point cloud, and the
/// normalized depth map that the depth-map planners read.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/range_sensor_config.hpp"
#include "campo/range_scan.hpp"
#include "campo/random.hpp"
#include "sensors/ray_fan.hpp"
#include "sensors/raycaster.hpp"

namespace campo {

class Lidar {
 public:
  /// `world_seed` is combined with config.seed for the noise stream.
  Lidar(const RangeSensorConfig& config, std::uint64_t world_seed);

  const RangeSensorConfig& config() const { return config_; }
  /// Unit beam directions in the sensor frame, beam order.
  const std::vector<Eigen::Vector3f>& directions() const { return directions_sensor_; }

  /// Scans from `sensor_pose` (world frame); reuses `out`'s buffers.
  void scan(const RayCaster& caster, const Eigen::Isometry3d& sensor_pose, double time_s,
            RangeScan& out);

 private:
  RangeSensorConfig config_;
  Rng rng_;
  std::vector<Eigen::Vector3f> directions_sensor_;
  RayFan fan_;                // the beams binned once, cast from each scan's pose
  std::vector<RayHit> hits_;  // scratch, reused
};

/// Sets a scan's header, its layout from `config` (scan_rows() x
/// scan_cols()), and sizes its buffers for `config.beam_count()` beams
/// (points emptied, capacity kept); shared by every RangeSensor.
void begin_scan(RangeScan& out, const RangeSensorConfig& config, double time_s, const Eigen::Isometry3d& sensor_pose);
/// A measured range as reported: rounded to the config's quantization step
/// (if any) and clamped to [0, max_range_m], as a real sensor reports neither
/// negative ranges nor ranges beyond its maximum.
float reported_range(double range_m, const RangeSensorConfig& config);

/// Unit direction of a beam in the sensor frame (x forward, y left, z up).
Eigen::Vector3f beam_direction(const Beam& beam);
/// The beams of a config in beam order (explicit list, or the grid row-major).
std::vector<Beam> lidar_beams(const RangeSensorConfig& config);

/// Depth map of SPEC §6 as CV_32F rows x cols: value = range / max_range_m in
/// [0, 1], 0 where the range is below min_range_m, 1 where nothing was hit.
cv::Mat depth_map(const RangeScan& scan, const RangeSensorConfig& config);

}  // namespace campo
