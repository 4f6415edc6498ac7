#pragma once
/// A colour camera's image (an "rgb_camera" sensor), as planners and the
/// Python module receive it.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace campo {

/// One image: 8-bit RGB, row-major from the top-left pixel, 3 bytes a pixel.
struct RgbImage {
  int rows = 0;
  int cols = 0;
  double time_s = 0.0;
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();  ///< world frame (x forward, y left, z up)
  std::vector<std::uint8_t> rgb;  ///< rows * cols * 3 bytes
};

}  // namespace campo
