#include "scene/scene_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "campo/pose.hpp"

namespace campo {
namespace {

constexpr double kUm = 1e-6;

Shape shape_of(ShapeType type, const Eigen::Vector3d& position,
                 const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
  Shape s;
  s.type = type;
  s.pose = to_isometry(Pose{position, rpy_deg});
  s.size_m = Eigen::Vector3d(1.0, 2.0, 3.0);
  s.radius_m = 0.7;
  s.height_m = 2.5;
  return s;
}

Shape heightfield(const Eigen::Vector3d& position, double yaw_deg) {
  auto grid = std::make_shared<HeightGrid>();
  grid->cols = 13;
  grid->rows = 9;
  grid->spacing_x_m = 0.5;
  grid->spacing_y_m = 0.75;
  for (int r = 0; r < grid->rows; ++r) {
    for (int c = 0; c < grid->cols; ++c) grid->heights_m.push_back(std::sin(0.7 * c) * std::cos(1.3 * r));
  }
  Shape s = shape_of(ShapeType::heightfield, position, {0.0, 0.0, yaw_deg});
  s.terrain = grid;
  return s;
}

// Bounding box of the vertices a part's triangles use.
Eigen::AlignedBox3d part_box(const SceneMesh& mesh, const MeshPart& part) {
  Eigen::AlignedBox3d box;
  for (std::uint32_t i = part.first_index; i < part.first_index + part.index_count; ++i) {
    box.extend(mesh.positions[mesh.indices[i]].cast<double>());
  }
  return box;
}

Eigen::Vector3d face_normal(const SceneMesh& mesh, std::size_t triangle) {
  const Eigen::Vector3d a = mesh.positions[mesh.indices[3 * triangle]].cast<double>();
  const Eigen::Vector3d b = mesh.positions[mesh.indices[3 * triangle + 1]].cast<double>();
  const Eigen::Vector3d c = mesh.positions[mesh.indices[3 * triangle + 2]].cast<double>();
  return (b - a).cross(c - a);
}

TEST(SceneMesh, TriangleCountsPerShape) {
  Scene scene;
  scene.shapes.push_back(shape_of(ShapeType::cuboid, {0, 0, 0}));
  scene.shapes.push_back(shape_of(ShapeType::cylinder, {3, 0, 0}));
  scene.shapes.push_back(shape_of(ShapeType::cone, {6, 0, 0}));
  scene.shapes.push_back(shape_of(ShapeType::sphere, {9, 0, 0}));
  scene.shapes.push_back(shape_of(ShapeType::plane, {0, 0, -2}));
  scene.shapes.push_back(heightfield({0, 0, -1}, 0.0));
  MeshOptions options;
  options.round_segments = 16;
  const SceneMesh mesh = build_scene_mesh(scene, options);
  ASSERT_EQ(mesh.parts.size(), 6u);
  const std::uint32_t expected[] = {
      12,                 // cuboid
      4 * 16,             // cylinder: side quads and two caps
      2 * 16,             // cone: side and base
      2 * 16 * (8 - 1),   // sphere: 8 latitude bands, the polar ones single triangles
      2,                  // plane
      2 * 12 * 8,         // heightfield: two per cell
  };
  std::uint32_t total = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(mesh.parts[i].index_count, 3 * expected[i]) << i;
    EXPECT_EQ(mesh.parts[i].first_index, 3 * total) << i;
    EXPECT_EQ(mesh.parts[i].shape, static_cast<int>(i));
    total += expected[i];
  }
  EXPECT_EQ(mesh.triangle_count(), total);
  EXPECT_EQ(mesh.positions.size(), mesh.normals.size());
  for (const std::uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions.size());
}

TEST(SceneMesh, HeightfieldHasBulletsTrianglesInTheWorldFrame) {
  Scene scene;
  scene.shapes.push_back(heightfield({2.0, -1.0, 0.5}, 30.0));
  const Shape& shape = scene.shapes[0];
  const HeightGrid& g = *shape.terrain;
  const SceneMesh mesh = build_scene_mesh(scene);
  ASSERT_EQ(mesh.positions.size(), static_cast<std::size_t>(g.cols * g.rows));
  // Every vertex of the grid is a mesh vertex at its height.
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const Eigen::Vector3d local((c - 0.5 * (g.cols - 1)) * g.spacing_x_m, (r - 0.5 * (g.rows - 1)) * g.spacing_y_m,
                                  g.at(c, r));
      const Eigen::Vector3d expected = shape.pose * local;
      bool found = false;
      for (const Eigen::Vector3f& p : mesh.positions) found = found || (p.cast<double>() - expected).norm() < kUm;
      EXPECT_TRUE(found) << c << " " << r;
    }
  }
  // Every triangle lies on the surface height_at describes (the same split):
  // its centroid and points next to its edge midpoints are on it.
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    Eigen::Vector3d v[3];
    for (int k = 0; k < 3; ++k) v[k] = mesh.positions[mesh.indices[3 * t + k]].cast<double>();
    const Eigen::Vector3d centroid = (v[0] + v[1] + v[2]) / 3.0;
    const auto near_midpoint = [&](int a, int b) { return centroid + 0.95 * (0.5 * (v[a] + v[b]) - centroid); };
    const Eigen::Vector3d samples[] = {centroid, near_midpoint(0, 1), near_midpoint(1, 2), near_midpoint(2, 0)};
    for (const Eigen::Vector3d& p : samples) {
      const Eigen::Vector3d local = shape.pose.inverse() * p;
      const auto h = g.height_at(local.x(), local.y());
      ASSERT_TRUE(h.has_value());
      EXPECT_NEAR(local.z(), *h, 1e-5) << "triangle " << t;
    }
    EXPECT_GT(face_normal(mesh, t).z(), 0.0) << "triangle " << t << " faces down";
  }
}

TEST(SceneMesh, NormalsAreUnitAndPointOutward) {
  Scene scene;
  const Eigen::Vector3d tilt(20.0, -35.0, 50.0);
  scene.shapes.push_back(shape_of(ShapeType::cuboid, {1, 2, 3}, tilt));
  scene.shapes.push_back(shape_of(ShapeType::cylinder, {-4, 0, 1}, tilt));
  scene.shapes.push_back(shape_of(ShapeType::cone, {0, 5, 0}, tilt));
  scene.shapes.push_back(shape_of(ShapeType::sphere, {3, -3, 2}, tilt));
  const SceneMesh mesh = build_scene_mesh(scene);
  for (const MeshPart& part : mesh.parts) {
    const Eigen::Vector3d centre = scene.shapes[static_cast<std::size_t>(part.shape)].pose.translation();
    for (std::uint32_t i = part.first_index; i < part.first_index + part.index_count; i += 3) {
      const Eigen::Vector3d n = face_normal(mesh, i / 3);
      const Eigen::Vector3d a = mesh.positions[mesh.indices[i]].cast<double>();
      // Convex shapes: every face looks away from the centre.
      EXPECT_GT(n.dot(a - centre), 0.0) << "part " << part.shape << " triangle " << i / 3;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3f& vn = mesh.normals[mesh.indices[i + k]];
        EXPECT_NEAR(vn.norm(), 1.0f, 1e-5f);
        EXPECT_GT(vn.cast<double>().dot(n), 0.0) << "part " << part.shape << " triangle " << i / 3;
      }
    }
  }
}

TEST(SceneMesh, BoundsMatchTheShapesAndRoundVerticesLieOnTheSurface) {
  Scene scene;
  scene.shapes.push_back(shape_of(ShapeType::cuboid, {1, 2, 3}));
  scene.shapes.push_back(shape_of(ShapeType::cylinder, {-4, 0, 1}));
  scene.shapes.push_back(shape_of(ShapeType::cone, {0, 5, 0}));
  scene.shapes.push_back(shape_of(ShapeType::sphere, {3, -3, 2}));
  scene.shapes.push_back(shape_of(ShapeType::plane, {0, 0, -1}));
  MeshOptions options;
  options.plane_half_extent_m = 50.0;
  const SceneMesh mesh = build_scene_mesh(scene, options);
  const double r = 0.7, hz = 1.25;
  const Eigen::Vector3d half_extents[] = {{0.5, 1.0, 1.5}, {r, r, hz}, {r, r, hz}, {r, r, r}, {50.0, 50.0, 0.0}};
  for (std::size_t i = 0; i < 5; ++i) {
    const Eigen::Vector3d centre = scene.shapes[i].pose.translation();
    const Eigen::AlignedBox3d box = part_box(mesh, mesh.parts[i]);
    EXPECT_TRUE(box.min().isApprox(centre - half_extents[i], 1e-6)) << i << ": " << box.min().transpose();
    EXPECT_TRUE(box.max().isApprox(centre + half_extents[i], 1e-6)) << i << ": " << box.max().transpose();
  }
  // Round shapes are inscribed: vertices on the true surface, so only chords differ.
  const MeshPart& sphere = mesh.parts[3];
  for (std::uint32_t i = sphere.first_index; i < sphere.first_index + sphere.index_count; ++i) {
    EXPECT_NEAR((mesh.positions[mesh.indices[i]].cast<double>() - Eigen::Vector3d(3, -3, 2)).norm(), r, kUm);
  }
  const MeshPart& cylinder = mesh.parts[1];
  for (std::uint32_t i = cylinder.first_index; i < cylinder.first_index + cylinder.index_count; ++i) {
    const Eigen::Vector3d p = mesh.positions[mesh.indices[i]].cast<double>() - Eigen::Vector3d(-4, 0, 1);
    const bool on_side = std::abs(p.head<2>().norm() - r) < kUm;
    const bool on_cap = std::abs(std::abs(p.z()) - hz) < kUm && p.head<2>().norm() <= r + kUm;
    EXPECT_TRUE(on_side || on_cap) << p.transpose();
  }
}

TEST(SceneMesh, MoversAreInTheirShapeFrameOnePartEach) {
  Scene scene;
  scene.shapes.push_back(shape_of(ShapeType::cuboid, {0, 0, 0}));
  Mover walker;
  walker.shape = shape_of(ShapeType::cylinder, {10, 0, 1}, {0, 0, 45});
  walker.path_m = {{10, 0, 1}, {10, 10, 1}};
  scene.movers.push_back(walker);
  Mover ball;
  ball.shape = shape_of(ShapeType::sphere, {-5, 0, 1});
  ball.path_m = {{-5, 0, 1}, {-5, 5, 1}};
  scene.movers.push_back(ball);
  const SceneMesh mesh = build_scene_mesh(scene);
  ASSERT_EQ(mesh.parts.size(), 1u);
  ASSERT_EQ(mesh.moving_parts.size(), 2u);
  EXPECT_EQ(mesh.moving_parts[0].shape, -1);
  EXPECT_EQ(mesh.moving_parts[1].shape, -2);
  const Eigen::AlignedBox3d walker_box = part_box(mesh, mesh.moving_parts[0]);
  EXPECT_TRUE(walker_box.min().isApprox(Eigen::Vector3d(-0.7, -0.7, -1.25), 1e-6));
  EXPECT_TRUE(walker_box.max().isApprox(Eigen::Vector3d(0.7, 0.7, 1.25), 1e-6));
  EXPECT_EQ(mesh.moving_parts[1].first_index, mesh.moving_parts[0].first_index + mesh.moving_parts[0].index_count);
  EXPECT_EQ(mesh.moving_parts[1].first_index + mesh.moving_parts[1].index_count, mesh.indices.size());
}

TEST(SceneMesh, IsDeterministic) {
  Scene scene;
  scene.shapes.push_back(heightfield({0, 0, 0}, 10.0));
  scene.shapes.push_back(shape_of(ShapeType::sphere, {3, -3, 2}, {5, 6, 7}));
  const SceneMesh a = build_scene_mesh(scene);
  const SceneMesh b = build_scene_mesh(scene);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.indices, b.indices);
}

TEST(SceneMesh, RejectsTooFewSegments) {
  MeshOptions options;
  options.round_segments = 7;
  EXPECT_THROW(build_scene_mesh(Scene{}, options), std::invalid_argument);
}

}  // namespace
}  // namespace campo
