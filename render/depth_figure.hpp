#pragma once
/// A depth map as a report figure, with a planner's overlays.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "render/figure_canvas.hpp"

namespace campo {

/// Planner overlays on a depth map (seed 000 Fig. 5.2), all optional. Pixel
/// positions are depth-map pixels (column, row); continuous ones have
/// integers at pixel centres.
struct DepthOverlays {
  cv::Mat dilated;                       ///< CV_32F like the depth map
  cv::Mat thresholded;                   ///< CV_8U 0/255
  std::optional<double> threshold;       ///< the threshold t behind `thresholded`, for its caption
  std::optional<cv::Point> chosen_pixel; ///< the pixel a waypoint was chosen at
  std::vector<cv::Point> scan_line;      ///< pixels considered for the choice
  /// W', the projection of the waypoint being checked (continuous; may lie
  /// outside the map, where only the legend gives it).
  std::optional<cv::Point2d> waypoint_projection;
  /// Half-axes, pixels across and down, of W's projected safety sphere
  /// around W' (the neighbourhood ControllaVisibilita reads); 0: not drawn.
  cv::Size2d safety_ellipse_px;
  std::optional<cv::Point> new_waypoint_pixel;  ///< where a new waypoint was placed
};

/// A depth map (CV_32F in [0, 1], SPEC §6) as a report figure: grey or
/// colour-mapped, each panel a raster at the map's resolution embedded
/// with nearest neighbours (visible pixels, in PDF and SVG as well), the overlays vectors, with a value colour bar and
/// the overlays when given (each panel side by side: depth, dilated,
/// thresholded; the markers on every panel: scan line, W' with its safety
/// ellipse, chosen pixel ringed, new waypoint as a diamond). Colour mode: sequential_color, with no return (1) light grey and below
/// min range (0) black. Throws std::invalid_argument for an empty or
/// non-CV_32F depth map or overlays of another size.
figure::Canvas draw_depth(const cv::Mat& depth, const DepthOverlays& overlays, bool colour, const std::string& title);

/// Where draw_depth puts its parts: the title band (kFigureTitlePx high),
/// the panels with their captions below, then a legend row (wrapped) of the
/// overlays and, in colour, of the special values. Each panel is the depth
/// map upscaled with nearest neighbours by the smallest integer factor that
/// makes its longer side at least kDepthPanelMinPx. Panels are kDepthGapPx
/// apart and from the left edge; the colour bar starts kDepthGapPx right of
/// the last panel, and with its labels it takes kDepthColorbarPx.
struct DepthFigureLayout {
  cv::Size image_px;
  cv::Rect title_px;
  int scale = 1;                    ///< figure pixels per depth-map pixel
  std::vector<cv::Rect> panels_px;  ///< depth, then dilated and thresholded when given
  cv::Rect colorbar_px;
  cv::Rect legend_px;               ///< legend rows; empty when there is nothing to explain
  /// Drawing coordinates of depth-map position `pixel` (continuous, integers
  /// at pixel centres) in panel `panel`.
  cv::Point2d to_px(std::size_t panel, cv::Point2d pixel) const;
};
inline constexpr int kDepthPanelMinPx = 256;
inline constexpr int kDepthGapPx = 32;
inline constexpr int kDepthColorbarPx = 120;
DepthFigureLayout depth_layout(const cv::Mat& depth, const DepthOverlays& overlays, bool colour);

}  // namespace campo
