#include "render/figure_parts.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace campo::figure {

void check_style(const FigureStyle& style) {
  if (style.max_size_px < 200 || style.max_size_px > 8000) {
    throw std::invalid_argument("FigureStyle: max_size_px must be in [200, 8000], got " +
                                std::to_string(style.max_size_px));
  }
  if (!(style.margin_m >= 0.0) || !std::isfinite(style.margin_m)) {
    throw std::invalid_argument("FigureStyle: margin_m must be a finite number >= 0");
  }
}

bool is_reached(const RunView& run, std::size_t index) {
  return std::find(run.reached.begin(), run.reached.end(), static_cast<int>(index)) != run.reached.end();
}

std::vector<std::size_t> thin_out(const std::vector<cv::Point2d>& points) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (kept.empty() || i + 1 == points.size() || cv::norm(points[i] - points[kept.back()]) >= 1.0) kept.push_back(i);
  }
  return kept;
}

std::string run_title(const FigureStyle& style, const RunView& run, const std::string& what) {
  if (!style.title.empty()) return style.title;
  std::string title = run.label.empty() ? what : run.label + " - " + what;
  if (!run.outcome.empty()) title += " (" + run.outcome + ")";
  return title;
}

LegendEntry line_entry(const cv::Scalar& color, int thickness, std::string text, bool dashed) {
  return {[=](Canvas& canvas, cv::Point2d c) {
            const std::vector<cv::Point2d> line{c + cv::Point2d(-16, 0), c + cv::Point2d(16, 0)};
            if (dashed) canvas.dashed_polyline(line, color, thickness, 7.0, 4.0);
            else canvas.polyline(line, color, thickness);
          },
          std::move(text)};
}

LegendEntry patch_entry(const cv::Scalar& fill, const cv::Scalar& edge, std::string text) {
  return {[=](Canvas& canvas, cv::Point2d c) {
            const cv::Rect box(static_cast<int>(c.x) - 12, static_cast<int>(c.y) - 7, 24, 14);
            canvas.fill_rectangle(box, fill);
            canvas.rectangle(box, edge, 1.0);
          },
          std::move(text)};
}

LegendEntry marker_entry(std::function<void(Canvas&, cv::Point2d)> marker, std::string text) {
  return {std::move(marker), std::move(text)};
}

}  // namespace campo::figure
