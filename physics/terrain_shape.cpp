#include "physics/terrain_shape.hpp"

namespace campo {

TerrainShape::TerrainShape(const HeightGrid& grid)
    : btHeightfieldTerrainShape(grid.cols, grid.rows, grid.heights_m.data(), grid.min_height_m(),
                                grid.max_height_m(), 2, false),
      blocks_(grid) {
  setLocalScaling(btVector3(grid.spacing_x_m, grid.spacing_y_m, 1.0));
  buildAccelerator();
}

void TerrainShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabb_min,
                                       const btVector3& aabb_max) const {
  // Bullet's callbacks keep only triangles whose box meets the query box; none
  // reaches a box whose bottom is above every vertex under it.
  if (aabb_min.z() > blocks_.highest(aabb_min.x(), aabb_max.x(), aabb_min.y(), aabb_max.y())) return;
  btHeightfieldTerrainShape::processAllTriangles(callback, aabb_min, aabb_max);
}

}  // namespace campo
