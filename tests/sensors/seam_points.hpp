#pragma once
// Where a heightfield's triangles meet, for watertightness tests: every interior vertex,
// the midpoints of the cell edges leaving it in +x and +y, and the cell's centre (on the
// diagonal that splits it), in the heightfield's local frame with their heights.
#include <vector>

#include <Eigen/Core>

#include "campo/scene.hpp"

namespace campo::test_support {

inline std::vector<Eigen::Vector3d> seam_points(const HeightGrid& g) {
  std::vector<Eigen::Vector3d> points;
  for (int r = 1; r + 1 < g.rows; ++r) {
    for (int c = 1; c + 1 < g.cols; ++c) {
      const double x0 = (c - 0.5 * (g.cols - 1)) * g.spacing_x_m;
      const double y0 = (r - 0.5 * (g.rows - 1)) * g.spacing_y_m;
      for (const auto& [fu, fv] : {std::pair{0.0, 0.0}, {0.5, 0.0}, {0.0, 0.5}, {0.5, 0.5}}) {
        const double x = x0 + fu * g.spacing_x_m, y = y0 + fv * g.spacing_y_m;
        points.emplace_back(x, y, *g.height_at(x, y));
      }
    }
  }
  return points;
}

}  // namespace campo::test_support
