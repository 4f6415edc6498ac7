#pragma once
/// Heightfield terrain from data: a CSV grid, a greyscale PNG, or an analytic
/// expression of x and y. Failures throw std::runtime_error with a message
/// that says what was wrong (the loader adds file and JSON pointer).
#include <filesystem>
#include <string>

#include <Eigen/Geometry>

#include "campo/scene.hpp"

namespace campo {

/// Maximum vertices of any heightfield grid (hostile-input limit).
inline constexpr long kMaxHeightfieldVertices = 4096L * 4096L;

/// Grid of `size_m` sampled every `spacing_m` (rounded to a whole number of
/// cells) where vertex heights are `expression` (muParser syntax: sin, cos,
/// exp, sqrt, abs, min, max, _pi, ^ ...) of the vertex's world x and y in
/// metres, minus the heightfield pose's z. `pose` places the grid centre.
HeightGrid heightgrid_from_expression(const std::string& expression, const Eigen::Vector2d& size_m,
                                      double spacing_m, const Eigen::Isometry3d& pose);

/// Grid from a CSV file of heights in metres: one line per grid row, comma
/// separated; the first line is the northern edge (largest y), the first
/// column the western edge (smallest x). All lines must have the same count.
HeightGrid heightgrid_from_csv(const std::filesystem::path& path, double spacing_m);

/// Grid from a greyscale PNG (8 or 16 bit): the top row is the northern edge;
/// height = min_height_m + (pixel / max pixel value) * height_scale_m; the
/// image spans `size_m`.
HeightGrid heightgrid_from_png(const std::filesystem::path& path, const Eigen::Vector2d& size_m,
                               double height_scale_m, double min_height_m);

}  // namespace campo
