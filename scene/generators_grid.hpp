#pragma once
/// Private helper shared by the heightfield generators: the vertex layout of a
/// grid that covers a given size with cells of about a given spacing.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Core>

#include "scene/heightfield_sources.hpp"

namespace campo {

struct GridLayout {
  int cols = 0;              ///< vertices along x
  int rows = 0;              ///< vertices along y
  double spacing_x_m = 0.0;  ///< size_x / (cols - 1), metres
  double spacing_y_m = 0.0;
};

/// round(size / spacing) cells per axis (at least one), and the spacing
/// stretched so the grid spans `size_m` exactly. Throws `Error` for
/// non-positive input or more than kMaxHeightfieldVertices vertices, before
/// anything is allocated.
template <class Error>
GridLayout grid_layout(const Eigen::Vector2d& size_m, double spacing_m) {
  const auto fail = [&](const std::string& what) {
    std::ostringstream message;
    message << what << " (size " << size_m.x() << " x " << size_m.y() << " m, spacing " << spacing_m
            << " m)";
    throw Error(message.str());
  };
  if (!(size_m.allFinite() && size_m.minCoeff() > 0.0)) fail("grid size must be finite and > 0");
  if (!(std::isfinite(spacing_m) && spacing_m > 0.0)) fail("grid spacing must be finite and > 0");
  // Counted in doubles so an absurd ratio cannot overflow before the check.
  const double cells_x = std::max(1.0, std::round(size_m.x() / spacing_m));
  const double cells_y = std::max(1.0, std::round(size_m.y() / spacing_m));
  if ((cells_x + 1.0) * (cells_y + 1.0) > static_cast<double>(kMaxHeightfieldVertices)) {
    fail("grid would have more than " + std::to_string(kMaxHeightfieldVertices) + " vertices");
  }
  GridLayout layout;
  layout.cols = static_cast<int>(cells_x) + 1;
  layout.rows = static_cast<int>(cells_y) + 1;
  layout.spacing_x_m = size_m.x() / cells_x;
  layout.spacing_y_m = size_m.y() / cells_y;
  return layout;
}

/// Local x (or y) of vertex `index` of `count` vertices centred on the origin,
/// as HeightGrid defines it.
inline double grid_vertex_coordinate(int index, int count, double spacing_m) {
  return (index - 0.5 * (count - 1)) * spacing_m;
}

}  // namespace campo
