#include "render/figure_style.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"

namespace campo {

using figure::rgb;

cv::Point2d FigureLayout::to_px(const Eigen::Vector2d& p) const {
  return {plot_px.x - 0.5 + (p.x() - min.x()) * px_per_unit.x(),
          plot_px.y + plot_px.height - 0.5 - (p.y() - min.y()) * px_per_unit.y()};
}

cv::Vec3b sequential_color(double fraction) {
  static const cv::Mat lut = [] {
    cv::Mat ramp(1, 256, CV_8U), colours;
    for (int i = 0; i < 256; ++i) ramp.at<uchar>(0, i) = static_cast<uchar>(i);
    cv::applyColorMap(ramp, colours, cv::COLORMAP_VIRIDIS);
    return colours;
  }();
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  return lut.at<cv::Vec3b>(0, static_cast<int>(std::lround(f * 255.0)));
}

cv::Scalar run_color(std::size_t index) {
  // Tableau 10 without green and red, which mark start and goal, then four darker hues, so that the ten seeds
  // of a reproduction's overlay each get their own colour.
  static const std::array<cv::Scalar, kRunColors> palette{
      rgb(31, 119, 180), rgb(255, 127, 14), rgb(148, 103, 189), rgb(23, 190, 207), rgb(140, 86, 75),
      rgb(227, 119, 194), rgb(188, 189, 34), rgb(127, 127, 127), rgb(57, 59, 121),  rgb(140, 109, 49),
      rgb(0, 128, 128),   rgb(123, 65, 115)};
  return palette[index % palette.size()];
}

cv::Scalar vehicle_color(std::size_t index) {
  // Okabe & Ito (2008), "Color Universal Design": told apart with any of the common colour vision deficiencies.
  static const std::array<cv::Scalar, kVehicleColors> palette{
      rgb(0, 114, 178), rgb(230, 159, 0), rgb(204, 121, 167), rgb(86, 180, 233),
      rgb(0, 0, 0),     rgb(240, 228, 66), rgb(0, 158, 115),  rgb(213, 94, 0)};
  return palette[index % palette.size()];
}

}  // namespace campo
