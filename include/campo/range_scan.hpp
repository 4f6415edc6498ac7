#pragma once
/// A sensor's reading: the ranges, returns and hit points of one scan of a
/// LIDAR or depth camera, as planners receive it (campo/planner.hpp).
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace campo {

/// One scan. Beam i of a grid sensor is pixel (i % cols, i / cols).
struct RangeScan {
  int rows = 0;
  int cols = 0;
  double time_s = 0.0;
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();  ///< world frame
  std::vector<float> ranges_m;           ///< per beam; max_range_m where no hit
  std::vector<std::uint8_t> hits;        ///< per beam: 1 hit, 0 no return
  std::vector<Eigen::Vector3f> points;   ///< world-frame hit points (hits only, beam order)
};

}  // namespace campo
