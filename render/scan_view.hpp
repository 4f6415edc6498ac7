#pragma once
/// A planar range scan seen from above around the vehicle, with follow-the-gap's
/// choice: the sensor panel of a rover's video frames.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "render/figure_canvas.hpp"

namespace campo {

/// What the panel shows, in the vehicle's frame (x forward, y left), metres
/// and degrees counter-clockwise from straight ahead.
struct ScanView {
  double range_m = 5.0;                    ///< radius shown, > 0
  Eigen::Vector2d footprint_m{1.5, 1.0};   ///< vehicle length and width, drawn at the centre
  std::vector<Eigen::Vector2d> points_m;   ///< the scan's returns
  std::optional<double> route_deg;         ///< direction of the route
  std::optional<double> gap_heading_deg;   ///< the heading the chosen gap gives
  std::optional<double> nearest_m;         ///< the nearest reading, as a ring
  std::string status;                      ///< one line under the plot, e.g. "avoiding: gap on the left"
};

/// The panel (size_px square): range rings every 1-2-5 metres,
/// forward up, the vehicle at the centre, the returns as dots, the route
/// (dashed grey) and chosen heading (blue arrow), the nearest reading as a
/// dashed amber ring and a legend line. std::invalid_argument for range_m <= 0.
figure::Canvas draw_scan_view(const ScanView& view, int size_px = 640);

}  // namespace campo
