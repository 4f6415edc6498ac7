// The bundled scene of mesh buildings (scenes/mesh_buildings.json): its
// buildings are the closed meshes tools/make_mesh_buildings.py writes, they
// block the straight line to the goal, and the tower and the L-shaped block
// leave a passage of a little over 2 m between them.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "campo/world.hpp"

namespace campo {
namespace {

const Shape& named(const Scene& scene, const std::string& alias) {
  for (const Shape& s : scene.shapes) {
    if (s.alias == alias) return s;
  }
  throw std::runtime_error("no shape " + alias);
}

double volume_of(const TriangleMesh& m) {
  double six_v = 0.0;
  for (const auto& t : m.triangles) six_v += m.vertices_m[t[0]].dot(m.vertices_m[t[1]].cross(m.vertices_m[t[2]]));
  return six_v / 6.0;
}

TEST(MeshBuildingsScene, BuildingsAreTheClosedMeshesAsAuthored) {
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/mesh_buildings.json");
  const Shape& house = named(scene, "house");
  const Shape& block = named(scene, "block");
  const Shape& tower = named(scene, "tower");
  for (const Shape* s : {&house, &block, &tower}) {
    ASSERT_EQ(s->type, ShapeType::mesh);
    EXPECT_TRUE(s->mesh->closed) << s->alias;
    EXPECT_TRUE(s->is_static);
    EXPECT_EQ(s->mesh->source_sha256.size(), 64u);
  }
  // House: 8 x 6 m, walls 3.5 m, ridge 6 m: a box plus a triangular prism.
  EXPECT_NEAR(house.mesh->bounds_m.max().z(), 6.0, 1e-12);
  EXPECT_NEAR(volume_of(*house.mesh), 8 * 6 * 3.5 + 0.5 * 6 * 2.5 * 8, 1e-9);
  // L block: 12 x 4 plus 4 x 6 m, 7 m tall.
  EXPECT_NEAR(volume_of(*block.mesh), (12 * 4 + 4 * 6) * 7.0, 1e-9);
  // Tower: a regular octagon of circumradius 2.5 m (area 2 sqrt(2) r^2), 16 m tall.
  EXPECT_NEAR(volume_of(*tower.mesh), 2 * std::sqrt(2.0) * 2.5 * 2.5 * 16, 1e-3);  // corners written to 1 um

  World world(scene);
  // The straight line at flight height meets the house's west wall (x = 4).
  const auto straight = world.ray_test({0, 0, 2.5}, {34, 0, 2.5});
  ASSERT_TRUE(straight.has_value());
  EXPECT_EQ(scene.shapes.at(static_cast<std::size_t>(straight->shape)).alias, "house");
  EXPECT_NEAR(straight->distance_m, 4.0, 1e-4);
  // Across the passage at x = 20: the tower's flat north face (apothem 2.5 cos 22.5 deg
  // from y = -5) and the block's south face (y = -0.5).
  const auto south = world.ray_test({20, -1.5, 2.5}, {20, -10, 2.5});
  const auto north = world.ray_test({20, -1.5, 2.5}, {20, 10, 2.5});
  ASSERT_TRUE(south && north);
  EXPECT_NEAR(north->point_m.y() - south->point_m.y(), 4.5 - 2.5 * std::cos(std::numbers::pi / 8), 1e-4);
}

}  // namespace
}  // namespace campo
