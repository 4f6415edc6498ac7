#include "render/depth_figure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/figure_style.hpp"

namespace campo {

using figure::Align;
using figure::kPlannedWaypoint;
using figure::LegendEntry;
using figure::line_entry;
using figure::marker_entry;
using figure::patch_entry;
using figure::rgb;

cv::Point2d DepthFigureLayout::to_px(std::size_t panel, cv::Point2d pixel) const {
  const cv::Rect& r = panels_px.at(panel);
  return {r.x + (pixel.x + 0.5) * scale - 0.5, r.y + (pixel.y + 0.5) * scale - 0.5};
}

namespace {

const cv::Scalar kNoReturn = rgb(238, 238, 238);
const cv::Scalar kTooNear = rgb(0, 0, 0);
const cv::Scalar kRing = rgb(230, 25, 25);
const cv::Scalar kScanLine = rgb(255, 150, 0);
const cv::Scalar kProjection = rgb(220, 0, 220);  // W' and its safety ellipse
constexpr int kDepthCaptionPx = 36;

void check_depth(const cv::Mat& depth, const DepthOverlays& overlays) {
  if (depth.empty() || depth.type() != CV_32F) {
    throw std::invalid_argument("draw_depth: expected a non-empty CV_32F depth map");
  }
  if (!overlays.dilated.empty() && (overlays.dilated.type() != CV_32F || overlays.dilated.size() != depth.size())) {
    throw std::invalid_argument("draw_depth: the dilated map must be CV_32F of the depth map's size");
  }
  if (!overlays.thresholded.empty() &&
      (overlays.thresholded.type() != CV_8U || overlays.thresholded.size() != depth.size())) {
    throw std::invalid_argument("draw_depth: the thresholded map must be CV_8U of the depth map's size");
  }
}

// Outside the pixel's square (half-diagonal 0.71 scale), so the pixel stays visible.
double ring_radius(int scale) { return 0.75 * scale + 6.0; }

// Red on a white halo: reads over grey, colour map and black and white alike.
void draw_ring(figure::Canvas& canvas, cv::Point2d c, double radius) {
  canvas.circle(c, radius, figure::kWhite, 5);
  canvas.circle(c, radius, kRing, 2);
}

// W' as a plus on a white halo.
void draw_projection(figure::Canvas& canvas, cv::Point2d c) {
  for (int pass = 0; pass < 2; ++pass) {
    for (const cv::Point2d d : {cv::Point2d(5, 0), cv::Point2d(0, 5)}) {
      canvas.line(c - d, c + d, pass == 0 ? figure::kWhite : kProjection, pass == 0 ? 5 : 2);
    }
  }
}

// An ellipse of half-axes `axes` (figure pixels) around `c`, on a white halo: a closed polygon fine enough
// (about 2 pixels a side) to read as a curve at any size.
void draw_ellipse(figure::Canvas& canvas, cv::Point2d c, cv::Size2d axes) {
  const int sides = std::clamp(static_cast<int>(std::ceil(M_PI * (axes.width + axes.height) / 2.0)), 24, 720);
  std::vector<cv::Point2d> outline;
  for (int i = 0; i < sides; ++i) {
    const double a = 2.0 * M_PI * i / sides;
    outline.emplace_back(c.x + axes.width * std::cos(a), c.y + axes.height * std::sin(a));
  }
  canvas.polyline(outline, figure::kWhite, 4, true);
  canvas.polyline(outline, kProjection, 2, true);
}

std::string pixel_text(cv::Point2d p, double step) {
  return "column " + figure::format_number(p.x, step) + ", row " + figure::format_number(p.y, step);
}

bool has_ellipse(const DepthOverlays& overlays) {
  return overlays.safety_ellipse_px.width > 0.0 && overlays.safety_ellipse_px.height > 0.0;
}

std::vector<LegendEntry> depth_legend(const DepthOverlays& overlays, bool colour) {
  std::vector<LegendEntry> legend;
  if (overlays.waypoint_projection) {
    const bool ellipse = has_ellipse(overlays);
    legend.push_back(marker_entry(
        [ellipse](figure::Canvas& m, cv::Point2d p) {
          if (ellipse) draw_ellipse(m, p, {13.0, 8.0});
          draw_projection(m, p);
        },
        "W' (" + pixel_text(*overlays.waypoint_projection, 0.1) + ")" + (ellipse ? ", safety sphere" : "")));
  }
  if (overlays.chosen_pixel) {
    const cv::Point c = *overlays.chosen_pixel;
    legend.push_back(marker_entry([](figure::Canvas& m, cv::Point2d p) { draw_ring(m, p, 7.0); },
                                  "chosen pixel (column " + std::to_string(c.x) + ", row " + std::to_string(c.y) + ")"));
  }
  if (!overlays.scan_line.empty()) legend.push_back(line_entry(kScanLine, 2, "scan line"));
  if (overlays.new_waypoint_pixel) {
    legend.push_back(marker_entry([](figure::Canvas& m, cv::Point2d p) { figure::diamond_marker(m, p, kPlannedWaypoint); },
                                  "new waypoint (" + pixel_text(*overlays.new_waypoint_pixel, 1.0) + ")"));
  }
  if (colour) {
    legend.push_back(patch_entry(kNoReturn, figure::kMutedInk, "no return (1)"));
    legend.push_back(patch_entry(kTooNear, figure::kMutedInk, "below min range (0)"));
  }
  return legend;
}

// Left-to-right rows of legend entries within `width`: the row of each entry.
constexpr int kFlowRowPx = 28;
int flow_width(const LegendEntry& e) { return 44 + figure::text_size(e.text, figure::kLabelFont).width + 24; }
std::vector<int> flow_rows(const std::vector<LegendEntry>& entries, int width) {
  std::vector<int> rows;
  int row = 0, x = 0;
  for (const auto& e : entries) {
    if (x > 0 && x + flow_width(e) > width) {
      ++row;
      x = 0;
    }
    rows.push_back(row);
    x += flow_width(e);
  }
  return rows;
}

// The panel at the map's resolution: the figure embeds it scaled with nearest neighbours.
cv::Mat depth_panel(const cv::Mat& values, bool colour) {
  cv::Mat small(values.size(), CV_8UC3);
  for (int r = 0; r < values.rows; ++r) {
    for (int c = 0; c < values.cols; ++c) {
      cv::Vec3b& px = small.at<cv::Vec3b>(r, c);
      if (values.type() == CV_8U) {
        px = values.at<uchar>(r, c) ? cv::Vec3b(255, 255, 255) : cv::Vec3b(0, 0, 0);
        continue;
      }
      const float v = values.at<float>(r, c);
      const bool no_return = !(v < 1.0f);  // NaN included
      if (!colour) {
        const uchar g = no_return ? 255 : cv::saturate_cast<uchar>(255.0 * std::max(0.0f, v));
        px = cv::Vec3b(g, g, g);
      } else if (no_return) {
        px = cv::Vec3b(kNoReturn[0], kNoReturn[1], kNoReturn[2]);
      } else if (v <= 0.0f) {
        px = cv::Vec3b(kTooNear[0], kTooNear[1], kTooNear[2]);
      } else {
        px = sequential_color(v);
      }
    }
  }
  return small;
}

cv::Vec3b grey(double f) {
  const uchar g = cv::saturate_cast<uchar>(255.0 * f);
  return {g, g, g};
}

}  // namespace

DepthFigureLayout depth_layout(const cv::Mat& depth, const DepthOverlays& overlays, bool colour) {
  check_depth(depth, overlays);
  DepthFigureLayout l;
  const int n = 1 + !overlays.dilated.empty() + !overlays.thresholded.empty();
  l.scale = std::max(1, (kDepthPanelMinPx + std::max(depth.rows, depth.cols) - 1) / std::max(depth.rows, depth.cols));
  const cv::Size panel(depth.cols * l.scale, depth.rows * l.scale);
  const int top = kFigureTitlePx + 12;
  for (int i = 0; i < n; ++i) l.panels_px.emplace_back(kDepthGapPx + i * (panel.width + kDepthGapPx), top, panel.width, panel.height);
  const int panels_right = l.panels_px.back().x + panel.width;
  l.colorbar_px = {panels_right + kDepthGapPx, top, 20, panel.height};
  const int width = panels_right + kDepthGapPx + kDepthColorbarPx;
  const std::vector<LegendEntry> legend = depth_legend(overlays, colour);
  const int legend_top = top + panel.height + kDepthCaptionPx;
  int legend_h = 0;
  if (!legend.empty()) {
    legend_h = (flow_rows(legend, width - 2 * kDepthGapPx).back() + 1) * kFlowRowPx;
    l.legend_px = {kDepthGapPx, legend_top, width - 2 * kDepthGapPx, legend_h};
  }
  l.image_px = {width, legend_top + legend_h + 12};
  l.title_px = {0, 0, width, kFigureTitlePx};
  return l;
}

figure::Canvas draw_depth(const cv::Mat& depth, const DepthOverlays& overlays, bool colour, const std::string& title) {
  const DepthFigureLayout l = depth_layout(depth, overlays, colour);
  figure::Canvas image(l.image_px);
  std::vector<std::pair<const cv::Mat*, std::string>> panels{{&depth, "depth map"}};
  if (!overlays.dilated.empty()) panels.emplace_back(&overlays.dilated, "dilated");
  if (!overlays.thresholded.empty()) {
    panels.emplace_back(&overlays.thresholded,
                        overlays.threshold ? "thresholded at t = " + figure::format_number(*overlays.threshold, 0.001)
                                           : "thresholded");
  }
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const cv::Rect& r = l.panels_px[i];
    image.image(depth_panel(*panels[i].first, colour), r);
    image.rectangle({r.x - 1, r.y - 1, r.width + 2, r.height + 2}, figure::kInk, 1);
    const std::string caption =
        panels.size() == 1 ? panels[i].second : std::string("(") + char('a' + i) + ") " + panels[i].second;
    figure::put_text(image, caption, {r.x + 0.5 * r.width, r.y + r.height + 0.5 * kDepthCaptionPx}, figure::kLabelFont,
                     figure::kInk, Align::centre);
    // Overlays on every panel, clipped to it, so the choice can be followed across the steps.
    const auto view_clip = image.region(r);
    figure::Canvas& view = image;
    const cv::Point2d origin(r.x, r.y);
    std::vector<cv::Point2d> scan;
    for (const auto& p : overlays.scan_line) scan.push_back(l.to_px(i, p) - origin);
    view.polyline(scan, kScanLine, 2);
    if (overlays.waypoint_projection) {
      const cv::Point2d c = l.to_px(i, *overlays.waypoint_projection) - origin;
      if (has_ellipse(overlays)) draw_ellipse(view, c, overlays.safety_ellipse_px * double(l.scale));
      draw_projection(view, c);
    }
    if (overlays.chosen_pixel) draw_ring(view, l.to_px(i, *overlays.chosen_pixel) - origin, ring_radius(l.scale));
    if (overlays.new_waypoint_pixel) {
      figure::diamond_marker(view, l.to_px(i, *overlays.new_waypoint_pixel) - origin, kPlannedWaypoint);
    }
  }
  figure::draw_colorbar(image, l.colorbar_px, 0.0, 1.0, "", colour ? sequential_color : grey);
  figure::put_text_vertical(image, "range / max range", {l.colorbar_px.x + 86.0, l.colorbar_px.y + 0.5 * l.colorbar_px.height},
                            figure::kLabelFont, figure::kInk);
  const std::vector<LegendEntry> legend = depth_legend(overlays, colour);
  if (!legend.empty()) {
    const std::vector<int> rows = flow_rows(legend, l.legend_px.width);
    int x = 0, row = 0;
    for (std::size_t i = 0; i < legend.size(); ++i) {
      if (rows[i] != row) {
        row = rows[i];
        x = 0;
      }
      const double cy = l.legend_px.y + (row + 0.5) * kFlowRowPx;
      legend[i].symbol(image, {l.legend_px.x + x + 16.0, cy});
      figure::put_text(image, legend[i].text, {l.legend_px.x + x + 44.0, cy}, figure::kLabelFont, figure::kInk);
      x += flow_width(legend[i]);
    }
  }
  figure::put_title(image, title.empty() ? "Depth map" : title, l.title_px);
  return image;
}

}  // namespace campo
