#include "render/figure_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"

namespace campo::figure {

bool Footprint::contains(const Eigen::Vector2d& p) const {
  if (!box_m.contains(p)) return false;
  // Convex outline in counter-clockwise order: inside = left of every edge.
  for (std::size_t i = 0; i < outline_m.size(); ++i) {
    const Eigen::Vector2d a = outline_m[i], b = outline_m[(i + 1) % outline_m.size()];
    const Eigen::Vector2d e = b - a, q = p - a;
    if (e.x() * q.y() - e.y() * q.x() < 0.0) return false;
  }
  return true;
}

Footprint footprint(const Shape& shape) {
  // Points on the shape's silhouette-defining edges, in the shape frame.
  std::vector<Eigen::Vector3d> local;
  constexpr int kRim = 48;
  const auto rim = [&](double r, double z) {
    for (int i = 0; i < kRim; ++i) {
      const double a = 2.0 * CV_PI * i / kRim;
      local.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  };
  switch (shape.type) {
    case ShapeType::cuboid:
      for (int i = 0; i < 8; ++i) {
        local.emplace_back((i & 1 ? 0.5 : -0.5) * shape.size_m.x(), (i & 2 ? 0.5 : -0.5) * shape.size_m.y(),
                           (i & 4 ? 0.5 : -0.5) * shape.size_m.z());
      }
      break;
    case ShapeType::cylinder:
      rim(shape.radius_m, -0.5 * shape.height_m);
      rim(shape.radius_m, 0.5 * shape.height_m);
      break;
    case ShapeType::cone:
      rim(shape.radius_m, -0.5 * shape.height_m);
      local.emplace_back(0.0, 0.0, 0.5 * shape.height_m);
      break;
    case ShapeType::sphere:
      break;  // a circle in the world frame, below
    case ShapeType::mesh:
      // Its vertices: the footprint is the convex hull of the mesh seen from
      // above (an L-shaped building shows as its hull; Footprint is convex).
      local = shape.mesh->vertices_m;
      break;
    case ShapeType::plane:
    case ShapeType::heightfield:
      return {};
  }
  Footprint f;
  f.shape = &shape;
  const Eigen::Vector3d centre = shape.pose.translation();
  std::vector<cv::Point2f> points;
  if (shape.type == ShapeType::sphere) {
    for (int i = 0; i < kRim; ++i) {
      const double a = 2.0 * CV_PI * i / kRim;
      points.emplace_back(static_cast<float>(shape.radius_m * std::cos(a)), static_cast<float>(shape.radius_m * std::sin(a)));
    }
    f.bottom_m = centre.z() - shape.radius_m;
    f.top_m = centre.z() + shape.radius_m;
  } else {
    f.bottom_m = std::numeric_limits<double>::infinity();
    f.top_m = -std::numeric_limits<double>::infinity();
    for (const auto& p : local) {
      // Relative to the centre so that float keeps millimetres far from the origin.
      const Eigen::Vector3d w = shape.pose.linear() * p;
      points.emplace_back(static_cast<float>(w.x()), static_cast<float>(w.y()));
      f.bottom_m = std::min(f.bottom_m, centre.z() + w.z());
      f.top_m = std::max(f.top_m, centre.z() + w.z());
    }
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull, /*clockwise=*/false);
  // convexHull's orientation flag is for a y-down image; make the outline counter-clockwise with y up.
  double area2 = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    area2 += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
  }
  if (area2 < 0.0) std::reverse(hull.begin(), hull.end());
  for (const auto& p : hull) {
    f.outline_m.emplace_back(centre.x() + p.x, centre.y() + p.y);
    f.box_m.extend(f.outline_m.back());
  }
  return f;
}

std::vector<Footprint> solid_footprints(const Scene& scene) {
  std::vector<Footprint> out;
  for (const auto& s : scene.shapes) {
    if (s.type != ShapeType::plane && s.type != ShapeType::heightfield) out.push_back(footprint(s));
  }
  std::stable_sort(out.begin(), out.end(), [](const Footprint& a, const Footprint& b) { return a.top_m < b.top_m; });
  return out;
}

Ground::Ground(const Scene& scene) {
  const Shape* colour_source = nullptr;
  for (const auto& s : scene.shapes) {
    if (s.type != ShapeType::plane && s.type != ShapeType::heightfield) continue;
    ground_.shapes.push_back(s);
    if (s.type == ShapeType::heightfield) {
      const double spacing = std::min(s.terrain->spacing_x_m, s.terrain->spacing_y_m);
      spacing_m_ = relief_ ? std::min(spacing_m_, spacing) : spacing;
      relief_ = true;
    }
    if (!colour_source || (s.type == ShapeType::heightfield && colour_source->type != ShapeType::heightfield)) {
      colour_source = &s;
    }
  }
  const Color c = colour_source ? colour_source->color : Color{};
  color_ = cv::Scalar(255.0 * c.b, 255.0 * c.g, 255.0 * c.r);
}

cv::Mat Ground::heights(const Eigen::Vector2d& top_left_m, double m_per_px, cv::Size size) const {
  cv::Mat h(size, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  if (empty()) return h;
  for (int r = 0; r < size.height; ++r) {
    auto* row = h.ptr<float>(r);
    const double y = top_left_m.y() - r * m_per_px;
    for (int c = 0; c < size.width; ++c) {
      if (const auto z = height(top_left_m.x() + c * m_per_px, y)) row[c] = static_cast<float>(*z);
    }
  }
  return h;
}

double Ground::contour_interval(const Eigen::AlignedBox2d& box) const {
  if (!relief_) return 0.0;
  constexpr int kSamples = 96;
  const Eigen::Vector2d size = box.sizes();
  const cv::Mat h = heights({box.min().x(), box.max().y()}, std::max(size.x(), size.y()) / (kSamples - 1),
                            {kSamples, kSamples});
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (auto it = h.begin<float>(); it != h.end<float>(); ++it) {
    if (std::isnan(*it)) continue;
    lo = std::min<double>(lo, *it);
    hi = std::max<double>(hi, *it);
  }
  return hi - lo > 1e-3 ? nice_step(hi - lo, 10.0) : 0.0;
}

cv::Scalar Ground::contour_color() const { return shade(color_, 0.45); }

void Ground::paint(Canvas& canvas, cv::Size size, const Eigen::Vector2d& top_left_m, double px_per_m,
                   double interval_m) const {
  if (empty() || size.width <= 0 || size.height <= 0) return;
  canvas.image(shading(size, top_left_m, px_per_m, interval_m), cv::Rect({0, 0}, size), /*smooth=*/false);
}

cv::Mat Ground::shading(cv::Size size, const Eigen::Vector2d& top_left_m, double px_per_m, double interval_m) const {
  cv::Mat plot(size, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  if (empty()) return plot;
  // Heights over the plot and a border as wide as the smoothing reaches, so
  // that the shading near the plot's edges sees the terrain beyond them.
  // The smoothing follows the terrain's vertex spacing up to kMaxSmoothing_px:
  // on coarse terrain a wider blur would cost time and padding with the
  // spacing (a 20 m grid at 10 px/m: sigma 120 px, 360 px of padding) for no visible gain.
  constexpr double kMaxSmoothing_px = 8.0;
  const double sigma = relief_ ? std::clamp(0.6 * spacing_m_ * px_per_m, 1.0, kMaxSmoothing_px) : 0.0;
  const int pad = 1 + static_cast<int>(std::ceil(3.0 * sigma));
  const cv::Mat padded = heights(top_left_m + Eigen::Vector2d(-pad, pad) / px_per_m, 1.0 / px_per_m,
                                 {plot.cols + 2 * pad, plot.rows + 2 * pad});
  const cv::Mat heights = padded(cv::Rect(pad, pad, plot.cols, plot.rows));
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (auto it = heights.begin<float>(); it != heights.end<float>(); ++it) {
    if (std::isnan(*it)) continue;
    lo = std::min(lo, *it);
    hi = std::max(hi, *it);
  }
  const double span = hi > lo ? hi - lo : 1.0;
  // Relief terrain a little darker than flat ground, so that both stay light.
  const cv::Scalar base = lighten(color_, relief_ ? 0.55 : 0.8);
  const cv::Scalar ink = contour_color();
  // Light from the north-west, 45 degrees up; relief exaggerated for gentle terrain.
  const Eigen::Vector3d light = Eigen::Vector3d(-1.0, 1.0, std::sqrt(2.0)).normalized();
  constexpr double kExaggeration = 2.0;
  // Smoothed heights for the shading, so that the grid's triangles do not show:
  // a Gaussian over the ground only (normalised by the blurred mask).
  cv::Mat smooth = padded;
  if (relief_) {
    const cv::Mat valid = padded == padded;  // false at NaN
    cv::Mat mask, filled = cv::Mat::zeros(padded.size(), CV_32F);
    valid.convertTo(mask, CV_32F, 1.0 / 255.0);
    padded.copyTo(filled, valid);
    cv::GaussianBlur(filled, filled, {}, sigma);
    cv::GaussianBlur(mask, mask, {}, sigma);
    smooth = filled / cv::max(mask, 1e-6);  // a new buffer: `padded` keeps its NaNs
  }
  // Slopes (m per m) at plot pixel (r, c) by central differences; one-sided next to no ground.
  const auto slope = [&](const cv::Mat& z, int r, int c) {
    r += pad;
    c += pad;
    const auto at = [&](int rr, int cc) {
      const float v = z.at<float>(rr, cc);
      return std::isnan(v) ? z.at<float>(r, c) : v;
    };
    return Eigen::Vector2d(0.5 * (at(r, c + 1) - at(r, c - 1)) * px_per_m, 0.5 * (at(r - 1, c) - at(r + 1, c)) * px_per_m);
  };
  for (int r = 0; r < plot.rows; ++r) {
    const auto* h = heights.ptr<float>(r);
    auto* px = plot.ptr<cv::Vec4b>(r);
    for (int c = 0; c < plot.cols; ++c) {
      if (std::isnan(h[c])) continue;
      const Eigen::Vector2d g = slope(smooth, r, c);
      const Eigen::Vector3d normal = Eigen::Vector3d(-kExaggeration * g.x(), -kExaggeration * g.y(), 1.0).normalized();
      double k = std::clamp(1.0 + 0.6 * (normal.dot(light) - light.z()), 0.72, 1.1);
      k *= 0.95 + 0.07 * (h[c] - lo) / span;
      cv::Scalar colour = shade(base, k);
      if (interval_m > 0.0) {
        // Anti-aliased contour: distance to the nearest level in pixels, from the gradient.
        const double f = h[c] / interval_m;
        const double level = std::round(f);
        const double per_px = slope(padded, r, c).norm() / px_per_m / interval_m;
        if (per_px > 1e-9) {
          const bool index = static_cast<long long>(level) % 5 == 0;
          const double distance_px = std::abs(f - level) / per_px;
          const double half_width = index ? 0.8 : 0.45;
          const double a = std::clamp(half_width + 0.5 - distance_px, 0.0, 1.0) * (index ? 0.8 : 0.5);
          colour = colour * (1.0 - a) + ink * a;
        }
      }
      px[c] = cv::Vec4b(cv::saturate_cast<uchar>(colour[0]), cv::saturate_cast<uchar>(colour[1]),
                        cv::saturate_cast<uchar>(colour[2]), 255);
    }
  }
  return plot;
}

}  // namespace campo::figure
