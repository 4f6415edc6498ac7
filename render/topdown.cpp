#include "render/topdown.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace campo {

namespace {

// World <-> pixel mapping with y up.
struct MapFrame {
  Eigen::Vector2d min_m;
  double px_per_m;
  int height_px;
  cv::Point to_px(const Eigen::Vector2d& p) const {
    return {static_cast<int>(std::lround((p.x() - min_m.x()) * px_per_m)),
            height_px - 1 - static_cast<int>(std::lround((p.y() - min_m.y()) * px_per_m))};
  }
  Eigen::Vector2d to_m(int col, int row) const {
    return {min_m.x() + (col + 0.5) / px_per_m, min_m.y() + (height_px - 1 - row + 0.5) / px_per_m};
  }
};

cv::Scalar bgr(const Color& c, double scale = 1.0) {
  return {255.0 * c.b * scale, 255.0 * c.g * scale, 255.0 * c.r * scale};
}

// Scale-bar length: the 1-2-5 step nearest to a fifth of the map width.
double nice_length(double width_m) {
  const double target = width_m / 5.0;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (double step : {1.0, 2.0, 5.0, 10.0}) {
    if (step * decade >= target * 0.7) return step * decade;
  }
  return 10.0 * decade;
}

void draw_footprint(cv::Mat& image, const MapFrame& f, const Shape& s) {
  const cv::Scalar fill = bgr(s.color), edge = bgr(s.color, 0.55);
  if (s.type == ShapeType::cuboid) {
    std::vector<cv::Point> corners;
    for (const auto& [sx, sy] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
      const Eigen::Vector3d local(sx * 0.5 * s.size_m.x(), sy * 0.5 * s.size_m.y(), 0.0);
      corners.push_back(f.to_px((s.pose * local).head<2>()));
    }
    cv::fillConvexPoly(image, corners, fill, cv::LINE_AA);
    cv::polylines(image, corners, true, edge, 1, cv::LINE_AA);
  } else if (s.type == ShapeType::cylinder || s.type == ShapeType::cone || s.type == ShapeType::sphere) {
    const int r = std::max(1, static_cast<int>(std::lround(s.radius_m * f.px_per_m)));
    const cv::Point c = f.to_px(s.pose.translation().head<2>());
    cv::circle(image, c, r, fill, cv::FILLED, cv::LINE_AA);
    cv::circle(image, c, r, edge, 1, cv::LINE_AA);
  }
}

}  // namespace

cv::Mat draw_topdown(const Scene& scene, const std::vector<Eigen::Vector3d>& path_m,
                     const std::vector<Waypoint>& mission, const TopdownStyle& style) {
  // Bounds: path and mission with a margin, grown to whole obstacles nearby.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = Eigen::Vector2d::Constant(-1e300);
  const auto grow = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const auto& p : path_m) grow(p.head<2>());
  for (const auto& wp : mission) grow(wp.position_m.head<2>());
  if (lo.x() > hi.x()) {  // nothing to centre on: the whole scene
    for (const auto& s : scene.shapes) {
      if (s.type != ShapeType::plane) grow(s.pose.translation().head<2>());
    }
  }
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  lo -= Eigen::Vector2d::Constant(style.margin_m);
  hi += Eigen::Vector2d::Constant(style.margin_m);
  const Eigen::Vector2d size = (hi - lo).cwiseMax(1.0);
  const double px_per_m = style.max_size_px / size.maxCoeff();
  const int legend_px = 60;
  const int map_width = static_cast<int>(std::lround(size.x() * px_per_m));
  const int map_height = static_cast<int>(std::lround(size.y() * px_per_m));
  const int width = std::max(map_width, style.min_width_px);
  // A narrow map is centred on the image, which is widened for the legend.
  const double pad_m = 0.5 * (width - map_width) / px_per_m;
  lo.x() -= pad_m;
  const MapFrame frame{lo, px_per_m, map_height};

  cv::Mat image(map_height + legend_px, width, CV_8UC3, cv::Scalar(245, 245, 245));
  cv::Mat map = image.rowRange(0, map_height);

  // Terrain: height shading with contour-like banding every metre.
  const Shape* terrain = nullptr;
  for (const auto& s : scene.shapes) {
    if (s.type == ShapeType::heightfield) terrain = &s;
  }
  if (terrain) {
    const double zmin = terrain->terrain->min_height_m(), zmax = terrain->terrain->max_height_m();
    const double span = std::max(zmax - zmin, 1e-6);
    for (int row = 0; row < map.rows; ++row) {
      auto* px = map.ptr<cv::Vec3b>(row);
      for (int col = 0; col < map.cols; ++col) {
        const Eigen::Vector2d p = frame.to_m(col, row);
        const auto h = scene.ground_height(p.x(), p.y());
        if (!h) continue;
        const double shade = 0.75 + 0.25 * (*h - terrain->pose.translation().z() - zmin) / span;
        const bool band = std::fmod(std::abs(*h), 1.0) < 0.04;
        const Color c = terrain->color;
        const double k = band ? 0.8 * shade : shade;
        px[col] = cv::Vec3b(cv::saturate_cast<uchar>(255 * (0.5 + 0.5 * c.b) * k),
                            cv::saturate_cast<uchar>(255 * (0.5 + 0.5 * c.g) * k),
                            cv::saturate_cast<uchar>(255 * (0.5 + 0.5 * c.r) * k));
      }
    }
  }
  for (const auto& s : scene.shapes) draw_footprint(map, frame, s);
  for (const auto& m : scene.movers) {
    std::vector<cv::Point> line;
    for (const auto& p : m.path_m) line.push_back(frame.to_px(p.head<2>()));
    cv::polylines(map, line, false, bgr(m.shape.color), 1, cv::LINE_AA);
  }

  // Nominal route (dashed look via thin grey) and waypoints.
  std::vector<cv::Point> route;
  if (!path_m.empty()) route.push_back(frame.to_px(path_m.front().head<2>()));
  for (const auto& wp : mission) route.push_back(frame.to_px(wp.position_m.head<2>()));
  cv::polylines(map, route, false, cv::Scalar(150, 150, 150), 1, cv::LINE_AA);
  std::vector<cv::Point> flown;
  for (const auto& p : path_m) flown.push_back(frame.to_px(p.head<2>()));
  cv::polylines(map, flown, false, cv::Scalar(200, 90, 20), 2, cv::LINE_AA);
  for (std::size_t i = 0; i < mission.size(); ++i) {
    const cv::Point c = frame.to_px(mission[i].position_m.head<2>());
    cv::circle(map, c, 6, cv::Scalar(0, 140, 255), 2, cv::LINE_AA);
    cv::putText(map, std::to_string(i + 1), c + cv::Point(8, -6), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 90, 200), 1, cv::LINE_AA);
  }
  if (!path_m.empty()) {
    cv::circle(map, frame.to_px(path_m.front().head<2>()), 7, cv::Scalar(40, 160, 40), cv::FILLED, cv::LINE_AA);
    cv::drawMarker(map, frame.to_px(path_m.back().head<2>()), cv::Scalar(30, 30, 200), cv::MARKER_TILTED_CROSS, 14, 2);
  }

  // Legend strip: title, scale bar, symbols.
  const int y0 = map_height;
  cv::line(image, {0, y0}, {image.cols, y0}, cv::Scalar(180, 180, 180));
  cv::putText(image, style.title, {10, y0 + 22}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
  const double bar_m = nice_length(width / px_per_m);
  const int bar_px = static_cast<int>(std::lround(bar_m * px_per_m));
  cv::line(image, {10, y0 + 45}, {10 + bar_px, y0 + 45}, cv::Scalar(20, 20, 20), 3);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", bar_m);
  cv::putText(image, label, {16 + bar_px, y0 + 50}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
  int x = std::max(200, image.cols - 480);
  const auto legend = [&](const cv::Scalar& color, const char* text, bool line) {
    if (line) cv::line(image, {x, y0 + 45}, {x + 20, y0 + 45}, color, 2, cv::LINE_AA);
    else cv::circle(image, {x + 10, y0 + 45}, 6, color, cv::FILLED, cv::LINE_AA);
    cv::putText(image, text, {x + 26, y0 + 50}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
    x += 30 + static_cast<int>(8.5 * std::string_view(text).size());
  };
  legend(cv::Scalar(200, 90, 20), "path", true);
  legend(cv::Scalar(150, 150, 150), "route", true);
  legend(cv::Scalar(0, 140, 255), "waypoints", false);
  legend(cv::Scalar(40, 160, 40), "start", false);
  legend(cv::Scalar(30, 30, 200), "end", false);
  return image;
}

}  // namespace campo
