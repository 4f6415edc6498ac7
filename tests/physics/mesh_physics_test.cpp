// Mesh obstacles in the physics: a box and a cylinder given as mesh files
// give the same clearance, contacts, resting heights and ray hits as the same
// primitives (to within 1 mm), a dynamic mesh collides as its convex hull,
// and inside a closed mesh the clearance is negative.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"
#include "tests/physics/placed_vehicle.hpp"
#include "campo/world.hpp"
#include "tests/mesh_file_writers.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using namespace campo::test_units;

// The mesh files every test here reads: a unit box and a closed cylinder
// (radius 0.5, height 1, 256 segments: the inscribed polygon is within 0.04 mm of the circle).
const fs::path& mesh_dir() {
  static const fs::path dir = [] {
    const fs::path d = test_support::process_temp_dir("campo_mesh_physics");
    test_support::write_file(d / "box.stl", test_support::stl_binary_bytes(test_support::box_mesh()));
    test_support::write_file(d / "cylinder.obj", test_support::obj_text(test_support::cylinder_mesh(0.5, 1.0, 256)));
    test_support::SimpleMesh open = test_support::box_mesh();
    open.triangles.resize(10);  // no +x face
    test_support::write_file(d / "open_box.ply", test_support::ply_ascii_text(open));
    return d;
  }();
  return dir;
}

Scene mesh_scene_from(const std::string& objects) {
  return parse_scene(nlohmann::json::parse(R"j({"objects": [)j" + objects + "]}"), "inline.json", mesh_dir());
}

struct PlacedOnMeshes : test::PlacedVehicle {
  explicit PlacedOnMeshes(const std::string& objects) : PlacedVehicle(mesh_scene_from(objects)) {}
};

std::string vec(const Eigen::Vector3d& v) {
  return "[" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) + "]";
}

std::string drone_at(const Eigen::Vector3d& p, double yaw_deg) {
  return R"({"alias": "drone", "type": "quadrotor", "pose": {"position_m": )" + vec(p) +
         R"(, "rpy_deg": [0, 0, )" + std::to_string(yaw_deg) + "]}}";
}

// A barrier (0.3 x 5 x 4 at x = 2) as a primitive and as the unit box mesh scaled.
const std::string kBoxPrimitive =
    R"({"alias": "barrier", "type": "cuboid", "size_m": [0.3, 5, 4], "pose": {"position_m": [2, 0, 2], "rpy_deg": [0, 0, 20]}})";
const std::string kBoxMesh =
    R"({"alias": "barrier", "type": "mesh", "file": "box.stl", "scale": [0.3, 5, 4], "pose": {"position_m": [2, 0, 2], "rpy_deg": [0, 0, 20]}})";
const std::string kCylinderPrimitive =
    R"({"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 3, "pose": {"position_m": [0, 2, 1.5]}})";
const std::string kCylinderMesh =
    R"({"alias": "post", "type": "mesh", "file": "cylinder.obj", "scale": [1, 1, 3], "pose": {"position_m": [0, 2, 1.5]}})";

TEST(MeshClearance, BoxMeshMeasuresAsTheCuboid) {
  // Positions and yaws about the barrier: face on, at its edge, above it, beside its end.
  const std::vector<std::pair<Eigen::Vector3d, double>> poses = {
      {{0, 0, 1.5}, 0}, {{0.5, 0.3, 1.0}, 45}, {{1.2, 2.8, 3.0}, 10}, {{2.3, 0, 4.6}, 0}, {{3.0, -3.5, 2.0}, 70}};
  for (const auto& [position, yaw] : poses) {
    SCOPED_TRACE(position.transpose());
    const PlacedOnMeshes primitive(kBoxPrimitive + "," + drone_at(position, yaw));
    const PlacedOnMeshes mesh(kBoxMesh + "," + drone_at(position, yaw));
    const Clearance a = primitive.world.vehicle_clearance();
    const Clearance b = mesh.world.vehicle_clearance();
    ASSERT_TRUE(std::isfinite(a.obstacle_m));
    EXPECT_NEAR(b.obstacle_m, a.obstacle_m, kMm);
    EXPECT_EQ(mesh.scene.shapes.at(static_cast<std::size_t>(b.obstacle)).alias, "barrier");
    // A cutoff below the distance: nothing within it, as for the primitive.
    EXPECT_TRUE(std::isinf(mesh.world.vehicle_clearance(a.obstacle_m - 0.01, 1.0).obstacle_m));
  }
  // One analytic value: face on, unrotated barrier face at x = 1.85, the drone's box reaching 0.3.
  const PlacedOnMeshes straight(R"({"alias": "barrier", "type": "mesh", "file": "box.stl", "scale": [0.3, 5, 4],
      "pose": {"position_m": [2, 0, 2]}},)" + drone_at({0, 0, 1.5}, 0));
  EXPECT_NEAR(straight.world.vehicle_clearance().obstacle_m, 1.85 - 0.3, kMm);
}

TEST(MeshClearance, CylinderMeshMeasuresAsTheCylinder) {
  for (const double angle_deg : {0.0, 17.0, 45.0, 90.0, 133.0, 200.0, 271.0}) {
    for (const double range : {0.8, 0.95, 1.6, 3.0}) {
      const double a = angle_deg * std::numbers::pi / 180.0;
      const Eigen::Vector3d p(range * std::cos(a), 2.0 + range * std::sin(a), 1.2);
      SCOPED_TRACE(p.transpose());
      const PlacedOnMeshes primitive(kCylinderPrimitive + "," + drone_at(p, angle_deg / 3));
      const PlacedOnMeshes mesh(kCylinderMesh + "," + drone_at(p, angle_deg / 3));
      const double expected = primitive.world.vehicle_clearance().obstacle_m;
      const double measured = mesh.world.vehicle_clearance().obstacle_m;
      if (expected > 0.0) {
        EXPECT_NEAR(measured, expected, kMm);
      } else {
        // Overlapping: the depth is the overlap with the nearest face's triangle, not
        // the solid's (docs/scene-format.md); both say the drone is in the post.
        EXPECT_LT(measured, 0.0);
      }
    }
  }
  // Above the top cap: 3 m tall, the drone's box 0.06 below its centre at z = 3.5.
  const PlacedOnMeshes above(kCylinderMesh + "," + drone_at({0.1, 2.0, 3.5}, 0));
  EXPECT_NEAR(above.world.vehicle_clearance().obstacle_m, 0.5 - 0.06, kMm);
}

TEST(MeshClearance, InsideAClosedMeshIsNegativeAndAnOpenMeshHasNoInside) {
  // A 6 m cube around the drone: 3 - 0.3 to the nearest (side) face.
  const PlacedOnMeshes closed(R"({"alias": "hall", "type": "mesh", "file": "box.stl", "scale": 6, "pose": {"position_m": [0, 0, 1]}},)" +
                      drone_at({0, 0, 1}, 0));
  const Clearance c = closed.world.vehicle_clearance();
  EXPECT_NEAR(c.obstacle_m, -(3.0 - 0.3), kMm);
  EXPECT_TRUE(c.touching());
  // A cutoff does not hide it.
  EXPECT_LT(closed.world.vehicle_clearance(0.5, 0.5).obstacle_m, 0.0);
  // Without its +x face the box has no inside: the distance to the nearest face, positive.
  const PlacedOnMeshes open(R"({"alias": "hall", "type": "mesh", "file": "open_box.ply", "scale": 6, "pose": {"position_m": [0, 0, 1]}},)" +
                    drone_at({0, 0, 1}, 0));
  EXPECT_NEAR(open.world.vehicle_clearance().obstacle_m, 3.0 - 0.3, kMm);
  // Just outside the closed one: positive again.
  const PlacedOnMeshes outside(R"({"alias": "hall", "type": "mesh", "file": "box.stl", "scale": 6, "pose": {"position_m": [0, 0, 1]}},)" +
                       drone_at({4, 0, 1}, 0));
  EXPECT_NEAR(outside.world.vehicle_clearance().obstacle_m, 1.0 - 0.3, kMm);
}

TEST(MeshContacts, ABulletContactNamesTheMesh) {
  // The unpowered drone's box bottom 2 mm above the top of a mesh block (top at z = 1): it falls onto it.
  const PlacedOnMeshes p(R"({"alias": "block", "type": "mesh", "file": "box.stl", "scale": [2, 2, 1], "pose": {"position_m": [0, 0, 0.5]}},)" +
                 drone_at({0, 0, 1.062}, 0));
  World& world = const_cast<World&>(p.world);
  Clearance c;
  for (int i = 0; i < 30 && !c.contact; ++i) {
    world.step();
    c = world.vehicle_clearance();
  }
  ASSERT_TRUE(c.contact);
  EXPECT_TRUE(c.touching());
  ASSERT_TRUE(c.touch.has_value());
  EXPECT_FALSE(c.touch->ground);
  EXPECT_EQ(p.scene.shapes.at(static_cast<std::size_t>(c.touch->body)).alias, "block");
  EXPECT_NEAR(c.touch->point_m.z(), 1.0, 1e-4);
}

// Where a dynamic 0.5 m box dropped onto a static block comes to rest.
double resting_height(const std::string& block, const std::string& falling) {
  const Scene scene = mesh_scene_from(block + "," + falling);
  World world(scene);
  for (int i = 0; i < 3 * 240; ++i) world.step();
  const BodyState s = world.shape_state(1);
  EXPECT_LT(s.linear_velocity_mps.norm(), 1e-3);
  return s.position_m.z();
}

TEST(MeshContacts, ABoxRestsOnAMeshBlockAsOnACuboid) {
  const std::string falling_box =
      R"({"alias": "crate", "type": "cuboid", "size_m": [0.5, 0.5, 0.5], "static": false, "mass_kg": 3, "pose": {"position_m": [0.2, 0.1, 2]}})";
  const double on_cuboid = resting_height(
      R"({"alias": "block", "type": "cuboid", "size_m": [3, 3, 1], "pose": {"position_m": [0, 0, 0.5]}})", falling_box);
  const double on_mesh = resting_height(
      R"({"alias": "block", "type": "mesh", "file": "box.stl", "scale": [3, 3, 1], "pose": {"position_m": [0, 0, 0.5]}})",
      falling_box);
  EXPECT_NEAR(on_cuboid, 1.25, 5 * kMm);  // the block's top plus half the crate
  EXPECT_NEAR(on_mesh, on_cuboid, kMm);
  // A dynamic mesh collides as its convex hull, with a box's extents: it rests where the cuboid does.
  const double mesh_on_mesh = resting_height(
      R"({"alias": "block", "type": "mesh", "file": "box.stl", "scale": [3, 3, 1], "pose": {"position_m": [0, 0, 0.5]}})",
      R"({"alias": "crate", "type": "mesh", "file": "box.stl", "scale": 0.5, "static": false, "mass_kg": 3, "pose": {"position_m": [0.2, 0.1, 2]}})");
  EXPECT_NEAR(mesh_on_mesh, on_cuboid, kMm);
  // A dynamic cylinder mesh standing on its end.
  const double post = resting_height(
      R"({"alias": "block", "type": "cuboid", "size_m": [3, 3, 1], "pose": {"position_m": [0, 0, 0.5]}})",
      R"({"alias": "post", "type": "mesh", "file": "cylinder.obj", "scale": [0.4, 0.4, 0.6], "static": false, "mass_kg": 1, "pose": {"position_m": [0, 0, 2]}})");
  EXPECT_NEAR(post, 1.0 + 0.3, 5 * kMm);
}

TEST(MeshWorld, RaysHitTheMeshAndStepsAreDeterministic) {
  const Scene scene = mesh_scene_from(kCylinderMesh + "," + kBoxMesh +
                                 R"(, {"alias": "crate", "type": "mesh", "file": "box.stl", "scale": 0.5, "static": false, "mass_kg": 3, "pose": {"position_m": [0, 2, 5]}})");
  World a(scene), b(scene);
  const auto hit = a.ray_test({0, -2, 1}, {0, 6, 1});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(scene.shapes.at(static_cast<std::size_t>(hit->shape)).alias, "post");
  EXPECT_NEAR(hit->distance_m, 3.5, kMm);
  // The static mesh stays where the scene put it.
  const BodyState post = a.shape_state(0);
  EXPECT_TRUE(post.position_m.isApprox(Eigen::Vector3d(0, 2, 1.5)));
  for (int i = 0; i < 480; ++i) {
    a.step();
    b.step();
  }
  EXPECT_EQ(a.state_hash(), b.state_hash());
  // The crate fell onto the post's top (z = 3) and rests there.
  EXPECT_NEAR(a.shape_state(2).position_m.z(), 3.25, 5 * kMm);
}

}  // namespace
}  // namespace campo
