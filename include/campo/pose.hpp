#pragma once
/// Poses as the scene files write them: position in metres, orientation as
/// roll/pitch/yaw in degrees (extrinsic x-y-z, i.e. R = Rz(yaw) Ry(pitch) Rx(roll)).
#include <Eigen/Geometry>

namespace campo {

/// A pose as written in a scene file, relative to its parent frame.
struct Pose {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< metres
  Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();      ///< roll, pitch, yaw in degrees
};

/// Rotation from roll/pitch/yaw in degrees: R = Rz(yaw) * Ry(pitch) * Rx(roll).
Eigen::Matrix3d rotation_from_rpy_deg(const Eigen::Vector3d& rpy_deg);

/// Rigid transform of a scene pose.
Eigen::Isometry3d to_isometry(const Pose& pose);

/// Roll/pitch/yaw in degrees of a rotation (inverse of rotation_from_rpy_deg;
/// pitch in [-90, 90]).
Eigen::Vector3d rpy_deg_from_rotation(const Eigen::Matrix3d& rotation);

}  // namespace campo
