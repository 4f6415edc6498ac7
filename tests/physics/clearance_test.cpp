// True clearance against analytic geometry: signed distances between the
// collision shapes themselves (GJK, EPA when they overlap), to within 1 mm.
#include "physics/clearance.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "physics/bullet_convert.hpp"
#include "campo/vehicle_factory.hpp"
#include "tests/physics/placed_vehicle.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;

btTransform at(double x, double y, double z, double yaw_deg = 0.0) {
  btQuaternion q(btVector3(0, 0, 1), yaw_deg * std::numbers::pi / 180.0);
  return btTransform(q, btVector3(x, y, z));
}

// Shapes without Bullet's collision margin: the exact solids.
btBoxShape exact_box(double hx, double hy, double hz) {
  btBoxShape box(btVector3(hx, hy, hz));
  box.setMargin(0.0);
  return box;
}

TEST(SignedDistance, BoxToBoxFaceEdgeAndCorner) {
  const btBoxShape a = exact_box(0.3, 0.3, 0.06);  // the quadrotor's collision box
  const btBoxShape b = exact_box(0.15, 2.5, 2.0);  // a barrier
  // Face to face: 2 - 0.3 - 0.15.
  EXPECT_NEAR(signed_distance(a, at(0, 0, 0), b, at(2, 0, 0)), 1.55, kMm);
  // Corner to corner: the drone's corner (0.3, 0.3) to the barrier's corner (1.85, 2.8) in the plane z = 0.
  EXPECT_NEAR(signed_distance(a, at(0, 0, 0), b, at(2, 3.3, 0)), std::hypot(1.55, 0.5), kMm);
  // Overlapping by 5 cm along x: the depth of the overlap, negative.
  EXPECT_NEAR(signed_distance(a, at(0, 0, 0), b, at(0.4, 0, 0)), -0.05, kMm);
}

TEST(SignedDistance, RotatedVehicleToAWall) {
  const btBoxShape drone = exact_box(0.3, 0.3, 0.06);
  const btBoxShape wall = exact_box(0.15, 5.0, 2.0);
  // Yawed 45 degrees, the drone reaches 0.3 sqrt(2) toward the wall, where a
  // bounding sphere would claim |(0.3, 0.3, 0.06)| = 0.429.
  const double reach = 0.3 * std::sqrt(2.0);
  EXPECT_NEAR(signed_distance(drone, at(0, 0, 0, 45), wall, at(1.0, 0, 0)), 1.0 - 0.15 - reach, kMm);
  EXPECT_NEAR(signed_distance(drone, at(0, 0, 0, 30), wall, at(1.0, 0, 0)),
              1.0 - 0.15 - 0.3 * (std::cos(std::numbers::pi / 6) + std::sin(std::numbers::pi / 6)), kMm);
}

TEST(SignedDistance, BoxToCylinderAndSphere) {
  const btBoxShape box = exact_box(0.5, 0.5, 0.5);
  btCylinderShapeZ trunk(btVector3(0.2, 0.2, 2.0));
  trunk.setMargin(0.0);
  // Side of the trunk to the box face: 3 - 0.2 - 0.5.
  EXPECT_NEAR(signed_distance(box, at(0, 0, 0), trunk, at(3, 0, 0)), 2.3, kMm);
  // Toward the box's vertical edge at (0.5, 0.5): the axis at (2, 2).
  EXPECT_NEAR(signed_distance(box, at(0, 0, 0), trunk, at(2, 2, 0)), std::hypot(1.5, 1.5) - 0.2, kMm);
  const btSphereShape ball(0.25);
  EXPECT_NEAR(signed_distance(box, at(0, 0, 0), ball, at(0, 0, 2)), 2 - 0.5 - 0.25, kMm);
}

TEST(Clearance, TouchingIsAContactOrAnOverlap) {
  Clearance c;
  EXPECT_FALSE(c.touching());  // nothing anywhere
  c.obstacle_m = 0.004;
  EXPECT_FALSE(c.touching());
  c.contact = true;  // pushed by a mover: in contact, a step's travel apart
  EXPECT_TRUE(c.touching());
  c = Clearance{};
  c.obstacle_m = -0.01;
  EXPECT_TRUE(c.touching());
  c = Clearance{};
  c.ground_m = 0.0;
  EXPECT_TRUE(c.touching());
}

Scene scene_from(const std::string& objects) {
  return parse_scene(nlohmann::json::parse(R"j({"objects": [)j" + objects + "]}"), "inline.json",
                     std::filesystem::temp_directory_path());
}

// The quadrotor of a scene, placed in its world (no step taken).
struct Placed : test::PlacedVehicle {
  explicit Placed(const std::string& objects) : PlacedVehicle(scene_from(objects)) {}
};

TEST(VehicleClearance, QuadrotorBoxToABarrierAndTheGround) {
  const Placed p(R"j({"alias": "ground", "type": "plane"},
    {"alias": "barrier", "type": "cuboid", "size_m": [0.3, 5, 4], "pose": {"position_m": [2, 0, 2]}},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5], "rpy_deg": [0, 0, 45]}})j");
  const Clearance c = p.world.vehicle_clearance();
  // Collision box (0.3, 0.3, 0.06) yawed 45 degrees: reach 0.3 sqrt(2) toward the barrier face at x = 1.85.
  EXPECT_NEAR(c.obstacle_m, 1.85 - 0.3 * std::sqrt(2.0), kMm);
  EXPECT_EQ(p.scene.shapes.at(static_cast<std::size_t>(c.obstacle)).alias, "barrier");
  EXPECT_NEAR(c.ground_m, 1.5 - 0.06, kMm);
  EXPECT_FALSE(c.touching());
  // A cutoff below the true distance reports "at least that far".
  EXPECT_TRUE(std::isinf(p.world.vehicle_clearance(0.5, 0.5).obstacle_m));
  EXPECT_NEAR(p.world.vehicle_clearance(2.0, 2.0).obstacle_m, c.obstacle_m, 1e-12);
}

TEST(VehicleClearance, GroundOfAHeightfieldAndMovingBodies) {
  const Placed p(R"j({"alias": "hill", "type": "heightfield", "size_m": [20, 20], "spacing_m": 0.5,
      "expression": "0.1 * x"},
    {"alias": "box", "type": "cuboid", "size_m": [1, 1, 1], "static": false, "mass_kg": 2,
     "pose": {"position_m": [-3, 0, 2]}},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 2]}})j");
  const Clearance c = p.world.vehicle_clearance();
  // The plane z = 0.1 x under the box's lowest edge: the distance from the
  // box (z = 2 - 0.06, x = -0.3 .. 0.3) to the slope, at the corner x = 0.3:
  // (1.94 - 0.03) cos(atan 0.1).
  EXPECT_NEAR(c.ground_m, (1.94 - 0.03) / std::sqrt(1.01), kMm);
  // The dynamic box (not yet stepped), face to face: 3 - 0.5 - 0.3.
  EXPECT_NEAR(c.obstacle_m, 2.2, kMm);
  EXPECT_EQ(p.scene.shapes.at(static_cast<std::size_t>(c.obstacle)).alias, "box");
}

// Bullet's narrow phase counts a contact within 1 mm as touching while the
// clearance is still positive (the case the closed loop once called "the
// ground" whatever it was): what is touched comes from the contact itself, a
// child of a compound of static obstacles named by its own index.
TEST(VehicleTouch, ABulletContactNamesTheChildOfACompoundTouched) {
  // Trunk, crown and rock share one compound (same friction, same 8 m cell),
  // the crown its third child. The crown (radius 1) is 0.5 mm from the
  // drone's box's top edge (x = 0.3, z = 2.06) along the diagonal, so that
  // their bounding boxes overlap and Bullet's narrow phase measures the pair.
  const double gap = 0.5 * kMm;
  const double a = (1.0 + gap) / std::sqrt(2.0);
  const Eigen::Vector3d centre(0.3 + a, 0, 2.06 + a);
  const std::string crown_at = "[" + std::to_string(centre.x()) + ", 0, " + std::to_string(centre.z()) + "]";
  const Placed p(R"j({"alias": "rock", "type": "cuboid", "size_m": [1, 1, 1], "pose": {"position_m": [4, 3, 0.5]}},
    {"alias": "trunk", "type": "cylinder", "radius_m": 0.2, "height_m": 1.8, "pose": {"position_m": [1.0075, 0, 0.9]}},
    {"alias": "crown", "type": "sphere", "radius_m": 1, "pose": {"position_m": )j" + crown_at + R"j(}},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 2]}})j");
  ASSERT_NEAR(p.world.vehicle_clearance().obstacle_m, gap, 1e-5);
  World& world = const_cast<World&>(p.world);
  world.step();  // Bullet's narrow phase runs within a step
  const Clearance c = world.vehicle_clearance();
  ASSERT_TRUE(c.contact);
  EXPECT_GT(c.obstacle_m, 0.0);  // not overlapping: the contact says what is touched
  ASSERT_TRUE(c.touch.has_value());
  EXPECT_FALSE(c.touch->ground);
  EXPECT_EQ(p.scene.shapes.at(static_cast<std::size_t>(c.touch->body)).alias, "crown");
  // On the crown's sphere, at the edge it nearly touches: within the gap
  // plus the drone's fall in one step (g dt^2 / 2, 0.09 mm at 240 Hz).
  EXPECT_NEAR((c.touch->point_m - centre).norm(), 1.0, 1e-6);
  EXPECT_LE((c.touch->point_m - Eigen::Vector3d(0.3, 0, 2.06)).norm(), 2 * gap);
}

TEST(VehicleTouch, ABulletContactWithTheGroundNamesIt) {
  // The box's bottom face 0.5 mm above the plane z = 0.
  const Placed p(R"j({"alias": "field", "type": "plane"},
    {"alias": "post", "type": "cylinder", "radius_m": 0.1, "height_m": 1, "pose": {"position_m": [0.5, 0, 0.5]}},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 0.0605]}})j");
  World& world = const_cast<World&>(p.world);
  world.step();
  const Clearance c = world.vehicle_clearance();
  ASSERT_TRUE(c.contact);
  EXPECT_GT(c.ground_m, 0.0);
  ASSERT_TRUE(c.touch.has_value());
  EXPECT_TRUE(c.touch->ground);
  EXPECT_EQ(p.scene.shapes.at(static_cast<std::size_t>(c.touch->body)).alias, "field");
  EXPECT_NEAR(c.touch->point_m.z(), 0.0, 1e-9);  // straight below the box's lowest point, on the plane
  EXPECT_LE(c.touch->point_m.head<2>().cwiseAbs().maxCoeff(), 0.3 + 1e-6);  // under the box
}

TEST(VehicleTouch, NothingWhenNothingTouches) {
  const Placed p(R"j({"alias": "field", "type": "plane"},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]}})j");
  World& world = const_cast<World&>(p.world);
  world.step();
  EXPECT_FALSE(world.vehicle_clearance().touch.has_value());
}

}  // namespace
}  // namespace campo
