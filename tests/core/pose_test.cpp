#include "campo/pose.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace campo {
namespace {

TEST(Pose, RollPitchYawAxes) {
  // Yaw turns x toward y; pitch turns x toward -z (nose down); roll turns y toward z.
  EXPECT_TRUE((rotation_from_rpy_deg({0, 0, 90}) * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((rotation_from_rpy_deg({0, 90, 0}) * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE((rotation_from_rpy_deg({90, 0, 0}) * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ()));
}

TEST(Pose, RpyRoundTrip) {
  for (double r : {-170.0, -30.0, 0.0, 45.0}) {
    for (double p : {-80.0, 0.0, 10.0, 60.0}) {
      for (double y : {-179.0, 0.0, 90.0, 135.0}) {
        const Eigen::Vector3d back = rpy_deg_from_rotation(rotation_from_rpy_deg({r, p, y}));
        EXPECT_NEAR(back.x(), r, 1e-9);
        EXPECT_NEAR(back.y(), p, 1e-9);
        EXPECT_NEAR(back.z(), y, 1e-9);
      }
    }
  }
}

TEST(Pose, IsometryAppliesRotationThenTranslation) {
  const Eigen::Isometry3d t = to_isometry({{1, 2, 3}, {0, 0, 90}});
  EXPECT_TRUE((t * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 3, 3)));
}

}  // namespace
}  // namespace campo
