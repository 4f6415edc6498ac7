// TerrainShape's shortcut against Bullet's own heightfield: for boxes above,
// grazing and inside a rough slope, the triangles a collision callback keeps
// (those whose box meets the query box, as Bullet's convex-concave callback
// keeps them) are the same.
#include "physics/terrain_shape.hpp"

#include <random>
#include <vector>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <LinearMath/btAabbUtil2.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

// Keeps the triangles that meet the box, in the order they come.
struct KeptTriangles final : btTriangleCallback {
  btVector3 lo, hi;
  std::vector<btVector3> vertices;
  void processTriangle(btVector3* triangle, int, int) override {
    if (TestTriangleAgainstAabb2(triangle, lo, hi)) vertices.insert(vertices.end(), triangle, triangle + 3);
  }
};

// A slope with rough bumps: the highest terrain under a box depends on where it is.
HeightGrid rough_slope() {
  HeightGrid grid;
  grid.cols = 41;
  grid.rows = 33;
  grid.spacing_x_m = 0.5;
  grid.spacing_y_m = 0.75;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> bump(-0.3, 0.3);
  grid.heights_m.resize(static_cast<std::size_t>(grid.cols) * grid.rows);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) grid.heights_m[static_cast<std::size_t>(r) * grid.cols + c] = 0.2 * c + bump(rng);
  }
  return grid;
}

TEST(TerrainShape, KeepsExactlyTheTrianglesBulletWould) {
  const HeightGrid grid = rough_slope();
  const TerrainShape shortcut(grid);
  btHeightfieldTerrainShape bullet(grid.cols, grid.rows, grid.heights_m.data(), grid.min_height_m(),
                                   grid.max_height_m(), 2, false);
  bullet.setLocalScaling(btVector3(grid.spacing_x_m, grid.spacing_y_m, 1.0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-12.0, 12.0), y(-14.0, 14.0), z(-5.0, 5.0), size(0.05, 2.0);
  // Boxes clear of the terrain though within its height range: where only the local bound skips the cells.
  const double half_range = 0.5 * (grid.max_height_m() - grid.min_height_m());
  int clear_within_range = 0;
  for (int i = 0; i < 2000; ++i) {
    const btVector3 lo(x(rng), y(rng), z(rng));
    const btVector3 hi = lo + btVector3(size(rng), size(rng), size(rng));
    KeptTriangles ours, theirs;
    ours.lo = theirs.lo = lo;
    ours.hi = theirs.hi = hi;
    shortcut.processAllTriangles(&ours, lo, hi);
    bullet.processAllTriangles(&theirs, lo, hi);
    ASSERT_EQ(ours.vertices.size(), theirs.vertices.size()) << i;
    for (std::size_t k = 0; k < ours.vertices.size(); ++k) ASSERT_EQ(ours.vertices[k], theirs.vertices[k]) << i;
    clear_within_range += theirs.vertices.empty() && lo.z() > -half_range && lo.z() < half_range;
  }
  EXPECT_GT(clear_within_range, 200);
}

}  // namespace
}  // namespace campo
