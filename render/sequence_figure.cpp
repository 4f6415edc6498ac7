#include "render/sequence_figure.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/map_figure.hpp"
#include "render/map_plot.hpp"

namespace campo {

using figure::check_style;
using figure::PlotMapper;
using figure::xy;

figure::Canvas draw_sequence(const Scene& scene, const RunView& run, const std::vector<SequencePanel>& panels,
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

  // Each panel's scene (every mover where it was then) and run (up to then); the plans point into them.
  std::vector<Scene> thens;
  std::vector<RunView> uptos;
  thens.reserve(panels.size());
  uptos.reserve(panels.size());
  std::vector<figure::MapPlan> plans;
  std::vector<FigureLayout> layouts;
  for (const SequencePanel& panel : panels) {
    Scene& then = thens.emplace_back(scene);
    for (Mover& m : then.movers) m.shape.pose.translation() = m.position_at(panel.time_s);
    RunView& upto = uptos.emplace_back(run);
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
    plans.push_back(figure::plan_map(then, {&upto}, panel_style, false));
    layouts.push_back(figure::layout_map(plans.back(), panel_style));
  }
  // Two panels a row, each in a cell as large as the largest, drawn into regions of one canvas (vectors stay
  // vectors in PDF and SVG).
  int w = 0, h = 0;
  for (const FigureLayout& l : layouts) {
    w = std::max(w, l.image_px.width);
    h = std::max(h, l.image_px.height);
  }
  const int columns = panels.size() == 1 ? 1 : 2;
  const int rows = static_cast<int>((panels.size() + columns - 1) / columns);
  figure::Canvas out({columns * w, rows * h});
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const SequencePanel& panel = panels[i];
    const FigureLayout& layout = layouts[i];
    const int c = static_cast<int>(i) % columns, r = static_cast<int>(i) / columns;
    auto cell = out.region(cv::Rect(cv::Point(c * w, r * h), layout.image_px));
    panel_style.title = panel.caption;
    figure::draw_map_figure(out, thens[i], plans[i], layout, figure::run_title(panel_style, uptos[i], "map"));
    auto plot = out.region(layout.plot_px);
    const PlotMapper to{layout};
    // The vehicle: its footprint at its recorded heading, and the chosen direction.
    const figure::VehicleOutline vehicle = figure::vehicle_outline(uptos[i].track.back(), footprint_m);
    const Eigen::Vector2d& centre = vehicle.centre;
    const Eigen::Vector2d& ahead = vehicle.ahead;
    const Eigen::Vector2d& half = vehicle.half;
    const std::vector<cv::Point2d> outline = to.all(vehicle.corners);
    out.fill_polygon(outline, figure::rgb(250, 250, 250));
    out.polyline(outline, figure::kInk, 2, /*closed=*/true);
    out.line(to(centre), to(Eigen::Vector2d(centre + half.x() * ahead)), figure::kInk, 2);
    if (panel.heading_deg) {
      const double heading = *panel.heading_deg * M_PI / 180.0;
      const Eigen::Vector2d tip = centre + 3.0 * Eigen::Vector2d(std::cos(heading), std::sin(heading));
      out.arrow(to(centre), to(tip), figure::rgb(20, 110, 200), 3, 0.15);
    }
  }
  return out;
}

}  // namespace campo
