// Static meshes on the planners' occupancy grid (scene/occupancy_grid):
// a box and a cylinder given as meshes cover the cells the same primitives
// cover; a closed mesh counts where its solid spans the height band, an open
// one only where its surface lies within the band.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "scene/occupancy_grid.hpp"
#include "tests/mesh_file_writers.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

const fs::path& mesh_dir() {
  static const fs::path dir = [] {
    const fs::path d = test_support::process_temp_dir("campo_mesh_occupancy");
    test_support::write_file(d / "box.obj", test_support::obj_text(test_support::box_mesh()));
    test_support::write_file(d / "cylinder.stl",
                             test_support::stl_binary_bytes(test_support::cylinder_mesh(0.5, 1.0, 256)));
    test_support::SimpleMesh roof = test_support::box_mesh();
    roof.triangles = {roof.triangles[2], roof.triangles[3]};  // only the top face (z = +0.5)
    test_support::write_file(d / "roof.obj", test_support::obj_text(roof));
    return d;
  }();
  return dir;
}

OccupancyGrid grid_of(const std::string& objects) {
  const Scene scene = parse_scene(nlohmann::json::parse(R"j({"objects": [)j" + objects + "]}"), "inline.json", mesh_dir());
  OccupancyConfig config;
  config.resolution_m = 0.1;
  config.vehicle_height_m = 2.0;
  return build_occupancy_grid(scene, config);
}

int occupied_count(const OccupancyGrid& g) {
  int n = 0;
  for (const auto v : g.occupied) n += v;
  return n;
}

// Cells where two grids of the same extent differ.
int differences(const OccupancyGrid& a, const OccupancyGrid& b) {
  EXPECT_EQ(a.cols, b.cols);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_TRUE(a.origin_m.isApprox(b.origin_m));
  int n = 0;
  for (std::size_t i = 0; i < std::min(a.occupied.size(), b.occupied.size()); ++i) n += a.occupied[i] != b.occupied[i];
  return n;
}

const std::string kDrone = R"({"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]}})";

TEST(MeshOccupancy, BoxAndCylinderMeshesCoverTheirPrimitivesCells) {
  const OccupancyGrid cuboid = grid_of(
      R"({"alias": "b", "type": "cuboid", "size_m": [2, 3, 5], "pose": {"position_m": [3.013, 1.027, 2.5], "rpy_deg": [0, 0, 30]}},)" + kDrone);
  const OccupancyGrid box = grid_of(
      R"({"alias": "b", "type": "mesh", "file": "box.obj", "scale": [2, 3, 5], "pose": {"position_m": [3.013, 1.027, 2.5], "rpy_deg": [0, 0, 30]}},)" + kDrone);
  EXPECT_GT(occupied_count(cuboid), 500);  // 6 m^2 at 0.01 m^2 a cell, and the rim
  EXPECT_EQ(differences(cuboid, box), 0);

  const OccupancyGrid cylinder = grid_of(
      R"({"alias": "c", "type": "cylinder", "radius_m": 1.5, "height_m": 4, "pose": {"position_m": [-2.031, 0.517, 2]}},)" + kDrone);
  const OccupancyGrid mesh = grid_of(
      R"({"alias": "c", "type": "mesh", "file": "cylinder.stl", "scale": [3, 3, 4], "pose": {"position_m": [-2.031, 0.517, 2]}},)" + kDrone);
  EXPECT_GT(occupied_count(cylinder), 600);
  // The 256-gon lies within 0.1 mm of the circle: a cell or two where it grazes a lattice point.
  EXPECT_LE(differences(cylinder, mesh), 2);
}

TEST(MeshOccupancy, TheSolidOrTheSurfaceWithinTheBand) {
  // A closed tower from z = -1 to 20: neither floor nor roof within the band
  // [0.05, 2] m, but the solid spans it.
  const OccupancyGrid tower = grid_of(
      R"({"alias": "t", "type": "mesh", "file": "box.obj", "scale": [1.01, 1.01, 21], "pose": {"position_m": [2.003, 0.002, 9.5]}},)" + kDrone);
  EXPECT_TRUE(tower.is_occupied(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_FALSE(tower.is_occupied(Eigen::Vector2d(3.0, 0.0)));
  // The same box's top face alone, open: high above the band, nothing; within it, its footprint.
  const OccupancyGrid high_roof = grid_of(
      R"({"alias": "r", "type": "mesh", "file": "roof.obj", "scale": [1.01, 1.01, 21], "pose": {"position_m": [2.003, 0.002, 9.5]}},)" + kDrone);
  EXPECT_FALSE(high_roof.is_occupied(Eigen::Vector2d(2.0, 0.0)));
  const OccupancyGrid low_roof = grid_of(
      R"({"alias": "r", "type": "mesh", "file": "roof.obj", "scale": [1.01, 1.01, 1], "pose": {"position_m": [2.003, 0.002, 1.0]}},)" + kDrone);
  EXPECT_TRUE(low_roof.is_occupied(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_FALSE(low_roof.is_occupied(Eigen::Vector2d(2.8, 0.0)));
}

}  // namespace
}  // namespace campo
