#include "render/scan_view.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"

namespace campo {

namespace {

const cv::Scalar kReturn = figure::rgb(214, 39, 40);
const cv::Scalar kRoute = figure::rgb(130, 130, 130);
const cv::Scalar kHeading = figure::rgb(31, 119, 180);
const cv::Scalar kNearest = figure::rgb(230, 150, 20);

}  // namespace

cv::Mat draw_scan_view(const ScanView& view, int size_px) {
  if (!(view.range_m > 0.0)) throw std::invalid_argument("draw_scan_view: range_m must be positive");
  cv::Mat image(size_px, size_px, CV_8UC3, figure::kWhite);
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
    cv::circle(image, figure::fixed(centre), static_cast<int>(std::lround(r * px_per_m)) << figure::kShift,
               figure::kGridInk, 1, cv::LINE_AA, figure::kShift);
    figure::put_text(image, figure::format_number(r, ring_m) + " m", to(along(45.0, r)) + cv::Point2d(3, 0),
                     figure::kSmallFont, figure::kMutedInk);
  }
  if (view.nearest_m && *view.nearest_m > 0.0) {
    const int n = 72;
    for (int i = 0; i < n; i += 2) {
      cv::line(image, figure::fixed(to(along(i * 360.0 / n, *view.nearest_m))),
               figure::fixed(to(along((i + 1) * 360.0 / n, *view.nearest_m))), kNearest, 2, cv::LINE_AA,
               figure::kShift);
    }
  }
  if (view.route_deg) {
    figure::dashed_polyline(image, {to(Eigen::Vector2d::Zero()), to(along(*view.route_deg, view.range_m))}, kRoute, 2,
                            10.0, 6.0);
  }
  for (const Eigen::Vector2d& p : view.points_m) {
    if (p.norm() > view.range_m) continue;
    cv::circle(image, figure::fixed(to(p)), 3 << figure::kShift, kReturn, cv::FILLED, cv::LINE_AA, figure::kShift);
  }
  const Eigen::Vector2d half = 0.5 * view.footprint_m;
  const std::vector<cv::Point> body = figure::fixed(std::vector<cv::Point2d>{
      to({half.x(), half.y()}), to({-half.x(), half.y()}), to({-half.x(), -half.y()}), to({half.x(), -half.y()})});
  cv::fillConvexPoly(image, body, figure::rgb(250, 250, 250), cv::LINE_AA, figure::kShift);
  cv::polylines(image, body, true, figure::kInk, 2, cv::LINE_AA, figure::kShift);
  if (view.gap_heading_deg) {
    cv::arrowedLine(image, figure::fixed(to(Eigen::Vector2d::Zero())),
                    figure::fixed(to(along(*view.gap_heading_deg, 0.6 * view.range_m))), kHeading, 3, cv::LINE_AA,
                    figure::kShift, 0.08);
  }
  // Legend: what the marks are.
  const double y = size_px - legend_px / 2.0;
  double x = 12.0;
  const auto entry = [&](const cv::Scalar& color, const std::string& text) {
    cv::circle(image, figure::fixed({x + 5, y}), 4 << figure::kShift, color, cv::FILLED, cv::LINE_AA, figure::kShift);
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
