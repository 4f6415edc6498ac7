#pragma once
/// A sensor that produces a range image over an angular grid: the ray-cast
/// LIDAR and the OSMesa depth camera (sensors/). The closed loop and
/// `campo scan` take either through this interface.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include <Eigen/Geometry>

#include "campo/range_scan.hpp"
#include "campo/scene.hpp"

namespace campo {

class RangeSensor {
 public:
  virtual ~RangeSensor() = default;
  virtual const SensorDef& def() const = 0;
  /// Fills `out` (ranges, hits, points; buffers reused) as seen from
  /// `sensor_pose` (world frame) at time_s, with the scene's moving bodies
  /// at `body_poses` (one per moving_bodies(scene) entry, in that order:
  /// World::moving_body_poses in the closed loop).
  virtual void scan(const Eigen::Isometry3d& sensor_pose, double time_s,
                    std::span<const Eigen::Isometry3d> body_poses, RangeScan& out) = 0;
};

/// Builds the sensor of a definition for a scene (which must outlive it).
using SensorFactory =
    std::function<std::unique_ptr<RangeSensor>(const Scene& scene, const SensorDef& def, std::uint64_t world_seed)>;

/// The ray-cast LIDAR as a RangeSensor; throws std::invalid_argument for
/// other sensor types (make_range_sensor in sensor_factory.hpp builds those).
std::unique_ptr<RangeSensor> make_lidar_sensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed);

}  // namespace campo
