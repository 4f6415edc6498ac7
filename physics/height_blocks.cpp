#include "physics/height_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace campo {

namespace {

// The cell of a heightfield coordinate `v` along an axis of `vertices`
// vertices `spacing` apart (vertex k at (k - (vertices - 1) / 2) spacing),
// clamped to the grid.
int cell_of(double v, double spacing, int vertices) {
  return static_cast<int>(std::clamp(std::floor(v / spacing + 0.5 * (vertices - 1)), 0.0, double(vertices - 2)));
}

}  // namespace

HeightBlocks::HeightBlocks(const HeightGrid& grid)
    : grid_(&grid),
      cols_(grid.cols),
      rows_(grid.rows),
      dx_(grid.spacing_x_m),
      dy_(grid.spacing_y_m),
      blocks_x_((grid.cols - 2) / kBlock + 1),
      blocks_y_((grid.rows - 2) / kBlock + 1),
      mid_m_(0.5 * (grid.min_height_m() + grid.max_height_m())),
      top_m_(static_cast<std::size_t>(blocks_x_) * blocks_y_, -std::numeric_limits<double>::infinity()) {
  // A block's cells span vertices [k kBlock, (k+1) kBlock]: shared edges count in both.
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < cols_; ++c) {
      const double h = grid.at(c, r) - mid_m_;
      for (int by = std::max(0, (r - 1) / kBlock); by <= std::min(blocks_y_ - 1, r / kBlock); ++by) {
        for (int bx = std::max(0, (c - 1) / kBlock); bx <= std::min(blocks_x_ - 1, c / kBlock); ++bx) {
          double& top = top_m_[static_cast<std::size_t>(by) * blocks_x_ + bx];
          top = std::max(top, h);
        }
      }
    }
  }
}

double HeightBlocks::highest(double x0, double x1, double y0, double y1) const {
  const int bx0 = cell_of(x0, dx_, cols_) / kBlock, bx1 = cell_of(x1, dx_, cols_) / kBlock;
  const int by0 = cell_of(y0, dy_, rows_) / kBlock, by1 = cell_of(y1, dy_, rows_) / kBlock;
  double top = -std::numeric_limits<double>::infinity();
  for (int by = by0; by <= by1; ++by) {
    for (int bx = bx0; bx <= bx1; ++bx) top = std::max(top, top_m_[static_cast<std::size_t>(by) * blocks_x_ + bx]);
  }
  return top;
}

void HeightBlocks::triangles_under(const btVector3& lo, const btVector3& hi, btTriangleCallback& callback,
                                   const Near* near) const {
  const int c0 = cell_of(lo.x(), dx_, cols_), c1 = cell_of(hi.x(), dx_, cols_);
  const int r0 = cell_of(lo.y(), dy_, rows_), r1 = cell_of(hi.y(), dy_, rows_);
  const auto vertex = [this](int c, int r) {
    return btVector3((c - 0.5 * (cols_ - 1)) * dx_, (r - 0.5 * (rows_ - 1)) * dy_, grid_->at(c, r) - mid_m_);
  };
  btVector3 v[3];
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (near) {
        // The cell's box from its four corners, and its distance from the near box (as the
        // clearance's box distance computes it: no larger than any of its triangles').
        const btVector3 a = vertex(c, r), b = vertex(c + 1, r), d = vertex(c, r + 1), e = vertex(c + 1, r + 1);
        btVector3 cell_lo = a, cell_hi = a;
        for (const btVector3* p : {&b, &d, &e}) {
          cell_lo.setMin(*p);
          cell_hi.setMax(*p);
        }
        double sum = 0.0;
        for (int i = 0; i < 3; ++i) {
          const double gap = std::max({0.0, static_cast<double>(cell_lo[i] - near->hi[i]),
                                       static_cast<double>(near->lo[i] - cell_hi[i])});
          sum += gap * gap;
        }
        if (std::sqrt(sum) >= near->limit_m) continue;
      }
      // Bullet's split of a cell (no flipped, diamond or zigzag edges).
      v[0] = vertex(c, r);
      v[1] = vertex(c, r + 1);
      v[2] = vertex(c + 1, r);
      callback.processTriangle(v, 0, 0);
      v[0] = vertex(c + 1, r);
      v[1] = vertex(c, r + 1);
      v[2] = vertex(c + 1, r + 1);
      callback.processTriangle(v, 0, 0);
    }
  }
}

}  // namespace campo
