#include "render/scan_view.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"

namespace campo {

namespace {

const cv::Scalar kReturn = figure::rgb(214, 39, 40);
const cv::Scalar kRoute = figure::rgb(130, 130, 130);
const cv::Scalar kHeading = figure::rgb(31, 119, 180);
const cv::Scalar kNearest = figure::rgb(230, 150, 20);

}  // namespace

figure::Canvas draw_scan_view(const ScanView& view, int size_px) {
  if (!(view.range_m > 0.0)) throw std::invalid_argument("draw_scan_view: range_m must be positive");
  figure::Canvas image({size_px, size_px});
  const int legend_px = 28;
  const cv::Point2d centre(0.5 * size_px, 0.5 * (size_px - legend_px));
  const double px_per_m = 0.46 * (size_px - legend_px) / view.range_m;
  // Vehicle frame (x forward, y left) -> drawing: forward up, left to the left.
  const auto to = [&](const Eigen::Vector2d& p) { return centre + cv::Point2d(-p.y(), -p.x()) * px_per_m; };
  const auto along = [](double deg, double r) {
    const double a = deg * M_PI / 180.0;
    return Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
  };
  const double ring_m = figure::nice_step(view.range_m, 5.0);
  for (double r = ring_m; r <= view.range_m + 1e-9; r += ring_m) {
    image.circle(centre, r * px_per_m, figure::kGridInk, 1);
    figure::put_text(image, figure::format_number(r, ring_m) + " m", to(along(45.0, r)) + cv::Point2d(3, 0),
                     figure::kSmallFont, figure::kMutedInk);
  }
  if (view.nearest_m && *view.nearest_m > 0.0) {
    // Dashed: 36 arcs, each a short polyline, and as many gaps.
    const int n = 72, steps = 4;
    for (int i = 0; i < n; i += 2) {
      std::vector<cv::Point2d> arc;
      for (int k = 0; k <= steps; ++k) arc.push_back(to(along((i + double(k) / steps) * 360.0 / n, *view.nearest_m)));
      image.polyline(arc, kNearest, 2);
    }
  }
  if (view.route_deg) {
    image.dashed_polyline({to(Eigen::Vector2d::Zero()), to(along(*view.route_deg, view.range_m))}, kRoute, 2, 10.0, 6.0);
  }
  for (const Eigen::Vector2d& p : view.points_m) {
    if (p.norm() > view.range_m) continue;
    image.fill_circle(to(p), 3.0, kReturn);
  }
  const Eigen::Vector2d half = 0.5 * view.footprint_m;
  const std::vector<cv::Point2d> body{to({half.x(), half.y()}), to({-half.x(), half.y()}),
                                      to({-half.x(), -half.y()}), to({half.x(), -half.y()})};
  image.fill_polygon(body, figure::rgb(250, 250, 250));
  image.polyline(body, figure::kInk, 2, true);
  if (view.gap_heading_deg) {
    image.arrow(to(Eigen::Vector2d::Zero()), to(along(*view.gap_heading_deg, 0.6 * view.range_m)), kHeading, 3, 0.08);
  }
  // Legend: what the marks are.
  const double y = size_px - legend_px / 2.0;
  double x = 12.0;
  const auto entry = [&](const cv::Scalar& color, const std::string& text) {
    image.fill_circle({x + 5, y}, 4.0, color);
    figure::put_text(image, text, {x + 14, y}, figure::kSmallFont, figure::kInk);
    x += 24 + figure::text_size(text, figure::kSmallFont).width;
  };
  entry(kReturn, "returns");
  entry(kRoute, "route");
  entry(kHeading, "gap heading");
  entry(kNearest, "nearest reading");
  if (!view.status.empty()) {
    figure::put_text(image, view.status, {12.0, 16.0}, figure::kLabelFont, figure::kInk);
  }
  return image;
}

}  // namespace campo
