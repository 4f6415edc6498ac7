#include "render/sequence_figure.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/map_figure.hpp"
#include "render/map_plot.hpp"

namespace campo {

using figure::check_style;
using figure::PlotMapper;
using figure::xy;

cv::Mat draw_sequence(const Scene& scene, const RunView& run, const std::vector<SequencePanel>& panels,
                      const Eigen::Vector2d& footprint_m, const FigureStyle& style) {
  if (panels.empty()) throw std::invalid_argument("draw_sequence: no panels");
  if (run.track.empty()) throw std::invalid_argument("draw_sequence: the run has no track");
  check_style(style);
  const auto [first, last] = std::minmax_element(panels.begin(), panels.end(), [](const auto& a, const auto& b) {
    return a.time_s < b.time_s;
  });
  // One frame for every panel: the track between the first and last instant and the movers then.
  Eigen::AlignedBox2d box;
  for (const TrackPoint& p : run.track) {
    if (p.time_s >= first->time_s && p.time_s <= last->time_s) box.extend(xy(p.position_m));
  }
  const auto track_at = [&](double t) {
    const auto it = std::upper_bound(run.track.begin(), run.track.end(), t,
                                     [](double time, const TrackPoint& p) { return time < p.time_s; });
    return it == run.track.begin() ? run.track.front() : *std::prev(it);
  };
  for (const SequencePanel& panel : panels) {
    box.extend(xy(track_at(panel.time_s).position_m));
    for (const Mover& m : scene.movers) box.extend(xy(m.position_at(panel.time_s)));
  }
  const Eigen::Vector2d grow = Eigen::Vector2d::Constant(style.margin_m + 0.5 * footprint_m.maxCoeff());
  FigureStyle panel_style = style;
  panel_style.bounds_m = Eigen::AlignedBox2d(box.min() - grow, box.max() + grow);

  std::vector<cv::Mat> images;
  for (const SequencePanel& panel : panels) {
    // The scene with every mover where it was then; the run up to then.
    Scene then = scene;
    for (Mover& m : then.movers) m.shape.pose.translation() = m.position_at(panel.time_s);
    RunView upto = run;
    upto.track.clear();
    for (const TrackPoint& p : run.track) {
      if (p.time_s <= panel.time_s) upto.track.push_back(p);
    }
    if (upto.track.empty()) upto.track.push_back(run.track.front());
    upto.avoiding_s.clear();
    for (const auto& [from, until] : run.avoiding_s) {
      if (from <= panel.time_s) upto.avoiding_s.emplace_back(from, std::min(until, panel.time_s));
    }
    panel_style.title = panel.caption;
    cv::Mat image = draw_map(then, upto, panel_style);
    const FigureLayout layout = map_layout(then, upto, panel_style);
    cv::Mat plot = image(layout.plot_px);
    const PlotMapper to{layout};
    // The vehicle: its footprint at its recorded heading, and the chosen direction.
    const TrackPoint& at = upto.track.back();
    const double yaw = at.yaw_deg * M_PI / 180.0;
    const Eigen::Vector2d ahead(std::cos(yaw), std::sin(yaw)), left(-ahead.y(), ahead.x());
    const Eigen::Vector2d centre = xy(at.position_m);
    const Eigen::Vector2d half = 0.5 * footprint_m;
    std::vector<Eigen::Vector2d> corners{centre + half.x() * ahead + half.y() * left,
                                         centre - half.x() * ahead + half.y() * left,
                                         centre - half.x() * ahead - half.y() * left,
                                         centre + half.x() * ahead - half.y() * left};
    const std::vector<cv::Point> outline = figure::fixed(to.all(corners));
    cv::fillConvexPoly(plot, outline, figure::rgb(250, 250, 250), cv::LINE_AA, figure::kShift);
    cv::polylines(plot, outline, true, figure::kInk, 2, cv::LINE_AA, figure::kShift);
    cv::line(plot, figure::fixed(to(centre)), figure::fixed(to(Eigen::Vector2d(centre + half.x() * ahead))),
             figure::kInk, 2, cv::LINE_AA, figure::kShift);
    if (panel.heading_deg) {
      const double h = *panel.heading_deg * M_PI / 180.0;
      const Eigen::Vector2d tip = centre + 3.0 * Eigen::Vector2d(std::cos(h), std::sin(h));
      cv::arrowedLine(plot, figure::fixed(to(centre)), figure::fixed(to(tip)), figure::rgb(20, 110, 200), 3,
                      cv::LINE_AA, figure::kShift, 0.15);
    }
    images.push_back(std::move(image));
  }
  // Two panels a row, each padded to the largest.
  int w = 0, h = 0;
  for (const cv::Mat& m : images) {
    w = std::max(w, m.cols);
    h = std::max(h, m.rows);
  }
  const int columns = images.size() == 1 ? 1 : 2;
  const int rows = static_cast<int>((images.size() + columns - 1) / columns);
  cv::Mat out(rows * h, columns * w, CV_8UC3, figure::kWhite);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const int c = static_cast<int>(i) % columns, r = static_cast<int>(i) / columns;
    images[i].copyTo(out(cv::Rect(c * w, r * h, images[i].cols, images[i].rows)));
  }
  return out;
}

}  // namespace campo
