#pragma once
/// Eigen <-> Bullet conversions, for the code that talks to Bullet (physics/world,
/// vehicles/). Nothing else includes Bullet.
#include <Eigen/Geometry>
#include <LinearMath/btTransform.h>

namespace campo {

inline btVector3 to_bt(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d from_bt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

inline btTransform to_bt(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d& r = t.linear();
  const btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2));
  return btTransform(basis, to_bt(t.translation()));
}

}  // namespace campo
