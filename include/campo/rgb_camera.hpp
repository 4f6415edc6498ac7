#pragma once
/// A colour camera ("rgb_camera" sensor) as the closed loop sees it: an image
/// of the scene rendered off-screen from a pose. Implemented in sensors/
/// (OSMesa, like the depth camera); campo/sensor_factory.hpp builds it.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include <Eigen/Geometry>

#include "campo/rgb_image.hpp"
#include "campo/scene.hpp"

namespace campo {

class RgbCamera {
 public:
  virtual ~RgbCamera() = default;
  virtual const RgbCameraDef& def() const = 0;
  /// Renders `out` (buffer reused) as seen from `camera_pose` (world frame,
  /// x forward, y left, z up) at time_s, with the scene's moving bodies at
  /// `body_poses` (one per moving_bodies(scene) entry, in that order).
  virtual void render(const Eigen::Isometry3d& camera_pose, double time_s,
                      std::span<const Eigen::Isometry3d> body_poses, RgbImage& out) = 0;
};

/// Builds the colour camera of a definition for a scene (which must outlive it).
using RgbCameraFactory =
    std::function<std::unique_ptr<RgbCamera>(const Scene& scene, const RgbCameraDef& def, std::uint64_t world_seed)>;

}  // namespace campo
