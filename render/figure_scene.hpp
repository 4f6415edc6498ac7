#pragma once
/// Scene content as the report figures see it from above: obstacle
/// footprints and the ground under a raster of pixels, with terrain shading
/// and contour lines. Private to render/.
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"

namespace campo::figure {

/// What a solid shape covers seen from above.
struct Footprint {
  const Shape* shape = nullptr;
  std::vector<Eigen::Vector2d> outline_m;  ///< convex, world x/y
  Eigen::AlignedBox2d box_m;               ///< bounds of the outline
  double bottom_m = 0.0;                   ///< lowest point of the shape
  double top_m = 0.0;                      ///< highest point of the shape
  bool contains(const Eigen::Vector2d& p) const;
};

/// Footprint of a cuboid, cylinder, cone, sphere or mesh (any orientation;
/// a mesh's is the convex hull of its vertices seen from above).
Footprint footprint(const Shape& shape);
/// Footprints of the scene's solid shapes (no planes or heightfields),
/// lowest top first so that taller shapes are drawn over lower ones.
std::vector<Footprint> solid_footprints(const Scene& scene);

/// The ground of a scene (its heightfields and planes) and how to draw it.
class Ground {
 public:
  explicit Ground(const Scene& scene);
  cv::Scalar color() const { return color_; }  ///< BGR of the terrain shape
  std::optional<double> height(double x, double y) const { return ground_.ground_height(x, y); }
  /// Contour interval for the heights over `box`: a 1-2-5 step giving about
  /// ten levels; 0 when there is no relief.
  double contour_interval(const Eigen::AlignedBox2d& box) const;
  /// The ground as a raster (CV_8UC4 BGRA) of `size` pixels, whose pixel
  /// (0, 0) is centred at `top_left_m`: hillshade lit from the north-west
  /// (from heights smoothed over about a grid cell, so that the triangles do
  /// not show), a light height tint, and contour lines every `interval_m`
  /// (every fifth one darker) when it is > 0. Transparent without ground.
  cv::Mat shading(cv::Size size, const Eigen::Vector2d& top_left_m, double px_per_m, double interval_m) const;
  /// Embeds shading(size, ...) on `canvas` over the pixels (0, 0) to `size`
  /// of its current region, one raster pixel per figure pixel (the shading is
  /// per pixel, so PDF and SVG hold it as an image). Nothing without ground.
  void paint(Canvas& canvas, cv::Size size, const Eigen::Vector2d& top_left_m, double px_per_m,
             double interval_m) const;
  /// Colour of the contour lines.
  cv::Scalar contour_color() const;

 private:
  bool empty() const { return ground_.shapes.empty(); }
  /// Heights (CV_32F, NaN where there is no ground) at the pixel centres of a
  /// raster whose pixel (0, 0) is centred at `top_left_m`, `m_per_px` apart
  /// (x east to the right, y north up).
  cv::Mat heights(const Eigen::Vector2d& top_left_m, double m_per_px, cv::Size size) const;

  Scene ground_;  // only the ground shapes, so height queries skip the obstacles
  bool relief_ = false;
  double spacing_m_ = 0.0;  // finest heightfield vertex spacing
  cv::Scalar color_;
};

}  // namespace campo::figure
