#include "campo/pose.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace campo {

namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;
}

Eigen::Matrix3d rotation_from_rpy_deg(const Eigen::Vector3d& rpy_deg) {
  const Eigen::Vector3d rpy = rpy_deg * kDegToRad;
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Isometry3d to_isometry(const Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation_from_rpy_deg(pose.rpy_deg);
  t.translation() = pose.position_m;
  return t;
}

Eigen::Vector3d rpy_deg_from_rotation(const Eigen::Matrix3d& r) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  return Eigen::Vector3d(roll, pitch, yaw) / kDegToRad;
}

}  // namespace campo
