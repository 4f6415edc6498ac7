#pragma once
/// A heightfield as Bullet holds it (centred on x, y; heights less the middle
/// of their range), with the highest vertex of each block of kBlock x kBlock
/// cells: what lies under a box is bounded without visiting its cells.
#include <vector>

#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <LinearMath/btVector3.h>

#include "campo/scene.hpp"

namespace campo {

class HeightBlocks {
 public:
  static constexpr int kBlock = 8;

  HeightBlocks() = default;
  /// `grid` must outlive the blocks.
  explicit HeightBlocks(const HeightGrid& grid);

  bool empty() const { return grid_ == nullptr; }
  /// The highest terrain over local x in [x0, x1], y in [y0, y1] (an upper
  /// bound: whole blocks count; a box beyond the grid gets its edge blocks).
  double highest(double x0, double x1, double y0, double y1) const;
  /// Hands every triangle of the cells under [lo, hi] (x, y) to `callback`,
  /// split as Bullet splits them, in the same order whatever `near`.
  /// `near`, when given, leaves out the cells whose bounding box lies at
  /// least `near->limit_m` from the box [near->lo, near->hi]: no triangle of
  /// them is nearer (its own box lies within the cell's).
  struct Near {
    btVector3 lo, hi;
    double limit_m;
  };
  void triangles_under(const btVector3& lo, const btVector3& hi, btTriangleCallback& callback,
                       const Near* near = nullptr) const;

 private:
  const HeightGrid* grid_ = nullptr;
  int cols_ = 0, rows_ = 0;  // vertices
  double dx_ = 1.0, dy_ = 1.0;
  int blocks_x_ = 0, blocks_y_ = 0;
  double mid_m_ = 0.0;  // Bullet centres the heights on the middle of their range
  std::vector<double> top_m_;
};

}  // namespace campo
