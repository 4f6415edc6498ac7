#pragma once
/// Parts several report figures share: colours and legend-column sizes,
/// legend entries, the style check and titles. Private to render/.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"

namespace campo::figure {

/// Planned intermediate waypoints on maps and the new waypoint on depth maps.
inline const cv::Scalar kPlannedWaypoint = rgb(31, 119, 180);
/// Gap between the plot and the legend column of maps and side views, pixels.
inline constexpr int kLegendGapPx = 24;
/// Width of the legend box in that column, pixels.
inline constexpr int kPanelInnerPx = kFigurePanelPx - kLegendGapPx - 20;

/// A scene colour (RGB in [0, 1]) as a BGR scalar.
inline cv::Scalar to_bgr(const Color& c) { return {255.0 * c.b, 255.0 * c.g, 255.0 * c.r}; }
/// The horizontal part (x, y) of a point.
inline Eigen::Vector2d xy(const Eigen::Vector3d& p) { return p.head<2>(); }

/// std::invalid_argument unless max_size_px is in [200, 8000] and margin_m is finite and >= 0.
void check_style(const FigureStyle& style);
/// Whether the run reached mission waypoint `index`.
bool is_reached(const RunView& run, std::size_t index);
/// Indices of the points at least a pixel apart (the last always kept), so
/// long tracks draw fast and smoothly.
std::vector<std::size_t> thin_out(const std::vector<cv::Point2d>& points);
/// style.title, or one made from the run's label, `what` and the run's outcome.
std::string run_title(const FigureStyle& style, const RunView& run, const std::string& what);

/// Legend entry: a short line, solid or dashed.
LegendEntry line_entry(const cv::Scalar& color, int thickness, std::string text, bool dashed = false);
/// Legend entry: a filled patch with an edge.
LegendEntry patch_entry(const cv::Scalar& fill, const cv::Scalar& edge, std::string text);
/// Legend entry: a marker drawn by `marker` around the symbol's centre.
LegendEntry marker_entry(std::function<void(Canvas&, cv::Point2d)> marker, std::string text);

}  // namespace campo::figure
