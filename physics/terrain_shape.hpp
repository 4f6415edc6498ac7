#pragma once
/// Bullet's heightfield with one shortcut: a box above the highest terrain
/// under it gets no triangles. Bullet's own listing visits every cell under
/// a body's box and tests each triangle against it, so a drone flying over
/// rolling terrain paid for the triangles beneath it at every step; the
/// shortcut hands the collision callbacks exactly what they would have kept
/// (nothing), so the physics is the same, bit for bit.
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include "campo/scene.hpp"
#include "physics/height_blocks.hpp"

namespace campo {

class TerrainShape final : public btHeightfieldTerrainShape {
 public:
  /// `grid` must outlive the shape.
  explicit TerrainShape(const HeightGrid& grid);

  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabb_min,
                           const btVector3& aabb_max) const override;

 private:
  HeightBlocks blocks_;
};

}  // namespace campo
