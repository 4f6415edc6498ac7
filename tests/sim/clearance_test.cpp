#include "sim/clearance.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace campo {
namespace {

Shape make(ShapeType type, const Eigen::Vector3d& at) {
  Shape s;
  s.type = type;
  s.pose.translation() = at;
  return s;
}

TEST(Clearance, CuboidDistances) {
  Shape box = make(ShapeType::cuboid, {0, 0, 0});
  box.size_m = {2, 4, 6};
  EXPECT_DOUBLE_EQ(distance_to_shape(box, {3, 0, 0}), 2.0);                  // face
  EXPECT_DOUBLE_EQ(distance_to_shape(box, {4, 5, 0}), std::hypot(3.0, 3.0));  // edge
  EXPECT_DOUBLE_EQ(distance_to_shape(box, {0.5, 0.5, 0.5}), 0.0);             // inside
  box.pose.linear() = rotation_from_rpy_deg({0, 0, 90});                      // now 4 wide in x
  EXPECT_NEAR(distance_to_shape(box, {3, 0, 0}), 1.0, 1e-12);
}

TEST(Clearance, RoundShapes) {
  Shape ball = make(ShapeType::sphere, {1, 1, 1});
  ball.radius_m = 0.5;
  EXPECT_DOUBLE_EQ(distance_to_shape(ball, {1, 1, 3}), 1.5);
  Shape can = make(ShapeType::cylinder, {0, 0, 0});
  can.radius_m = 1.0;
  can.height_m = 2.0;
  EXPECT_DOUBLE_EQ(distance_to_shape(can, {3, 0, 0.5}), 2.0);           // side
  EXPECT_DOUBLE_EQ(distance_to_shape(can, {0.5, 0, 4}), 3.0);           // top
  EXPECT_DOUBLE_EQ(distance_to_shape(can, {4, 0, 5}), 5.0);             // rim: (3, 4)
  Shape cone = make(ShapeType::cone, {0, 0, 0});
  cone.radius_m = 1.0;
  cone.height_m = 2.0;                                                  // apex (0, 0, 1)
  EXPECT_NEAR(distance_to_shape(cone, {0, 0, 3}), 2.0, 1e-12);          // above the apex
  EXPECT_NEAR(distance_to_shape(cone, {0, 0, -3}), 2.0, 1e-12);         // below the base
  // Side: the slant from (1, -1) to (0, 1) in (r, z); point (2, 0): distance 3 / sqrt(5).
  EXPECT_NEAR(distance_to_shape(cone, {2, 0, 0}), 3.0 / std::sqrt(5.0), 1e-12);
  EXPECT_TRUE(std::isinf(distance_to_shape(make(ShapeType::plane, {0, 0, 0}), {0, 0, 5})));
}

TEST(Clearance, FieldTakesTheNearestObstacleAndSkipsGround) {
  Scene scene;
  scene.shapes.push_back(make(ShapeType::plane, {0, 0, 0}));
  Shape near = make(ShapeType::sphere, {5, 0, 1});
  near.radius_m = 1.0;
  Shape far = make(ShapeType::sphere, {50, 0, 1});
  far.radius_m = 10.0;
  scene.shapes.push_back(near);
  scene.shapes.push_back(far);
  Mover walker;
  walker.shape = make(ShapeType::sphere, {0, 0, 1});
  walker.shape.radius_m = 0.5;
  walker.path_m = {{0, 10, 1}, {0, -10, 1}};
  walker.speed_mps = 1.0;
  scene.movers.push_back(walker);
  const ClearanceField field(scene);
  EXPECT_DOUBLE_EQ(field.distance({0, 0, 1}, 0.0), 4.0);   // walker 10 m away, sphere 4 m
  EXPECT_DOUBLE_EQ(field.distance({0, 0, 1}, 8.0), 1.5);   // walker at y = 2
}

}  // namespace
}  // namespace campo
