#include "render/figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"
#include "render/figure_scene.hpp"

namespace campo {

using figure::Align;
using figure::Footprint;
using figure::Ground;
using figure::LegendEntry;
using figure::rgb;

cv::Point2d FigureLayout::to_px(const Eigen::Vector2d& p) const {
  return {plot_px.x - 0.5 + (p.x() - min.x()) * px_per_unit.x(),
          plot_px.y + plot_px.height - 0.5 - (p.y() - min.y()) * px_per_unit.y()};
}

cv::Point2d DepthFigureLayout::to_px(std::size_t panel, cv::Point2d pixel) const {
  const cv::Rect& r = panels_px.at(panel);
  return {r.x + (pixel.x + 0.5) * scale - 0.5, r.y + (pixel.y + 0.5) * scale - 0.5};
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
  // Tableau 10 without green and red, which mark start and goal.
  static const std::array<cv::Scalar, 8> palette{rgb(31, 119, 180), rgb(255, 127, 14), rgb(148, 103, 189),
                                                 rgb(23, 190, 207), rgb(140, 86, 75),  rgb(227, 119, 194),
                                                 rgb(188, 189, 34), rgb(127, 127, 127)};
  return palette[index % palette.size()];
}

namespace {

const cv::Scalar kTrackHalo = rgb(40, 40, 40);
const cv::Scalar kPlannedWaypoint = rgb(31, 119, 180);
const cv::Scalar kDiscardedWaypoint = rgb(200, 40, 120);
const cv::Scalar kPlannedPath = rgb(60, 60, 60);
const cv::Scalar kNominalRoute = rgb(190, 0, 150);  // straight legs through the mission (001 Fig. 5.3/5.7/5.11)
const cv::Scalar kSensorHit = rgb(214, 39, 40);
const cv::Scalar kVehicleLine = rgb(31, 119, 180);
const cv::Scalar kNeutralMarker = rgb(120, 120, 120);  // legend symbols whose colour is the run's
const cv::Scalar kAvoiding = rgb(255, 196, 100);  // pale amber band under the track while avoiding
constexpr int kAvoidingBandPx = 15;               // its width: 5 px of amber each side of the track's halo
constexpr int kMinColorbarPx = 160;
constexpr int kMaxColorbarPx = 320;
constexpr int kLegendGapPx = 24;  // between the plot and the legend
constexpr int kScaleBlockPx = 52; // scale bar and north arrow
constexpr int kPanelGapPx = 24;   // between the blocks of the legend column
constexpr int kPanelInnerPx = kFigurePanelPx - kLegendGapPx - 20;  // width of the legend box
constexpr double kSameSpotM = 0.25;  // markers closer than this are drawn once in overlays

cv::Scalar to_bgr(const Color& c) { return {255.0 * c.b, 255.0 * c.g, 255.0 * c.r}; }
cv::Scalar to_scalar(const cv::Vec3b& v) { return {double(v[0]), double(v[1]), double(v[2])}; }
Eigen::Vector2d xy(const Eigen::Vector3d& p) { return p.head<2>(); }

void check_style(const FigureStyle& style) {
  if (style.max_size_px < 200 || style.max_size_px > 8000) {
    throw std::invalid_argument("FigureStyle: max_size_px must be in [200, 8000], got " +
                                std::to_string(style.max_size_px));
  }
  if (!(style.margin_m >= 0.0) || !std::isfinite(style.margin_m)) {
    throw std::invalid_argument("FigureStyle: margin_m must be a finite number >= 0");
  }
}

bool contains_near(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p) {
  return std::any_of(points.begin(), points.end(), [&](const auto& q) { return (xy(q) - xy(p)).norm() < kSameSpotM; });
}

bool is_reached(const RunView& run, std::size_t index) {
  return std::find(run.reached.begin(), run.reached.end(), static_cast<int>(index)) != run.reached.end();
}

// The track's positions from time `from` to `to`, interpolated at both ends; empty when
// the track is or the interval is inverted.
std::vector<Eigen::Vector3d> track_between(const std::vector<TrackPoint>& track, double from, double to) {
  std::vector<Eigen::Vector3d> out;
  if (track.empty() || !(from <= to)) return out;
  const auto by_time = [](const TrackPoint& p, double t) { return p.time_s < t; };
  const auto at = [&](double t) -> Eigen::Vector3d {
    const auto next = std::lower_bound(track.begin(), track.end(), t, by_time);
    if (next == track.begin()) return next->position_m;
    if (next == track.end()) return track.back().position_m;
    const TrackPoint& a = *(next - 1);
    const double span = next->time_s - a.time_s;
    const double f = span > 0.0 ? (t - a.time_s) / span : 1.0;
    return a.position_m + f * (next->position_m - a.position_m);
  };
  out.push_back(at(from));
  for (auto it = std::upper_bound(track.begin(), track.end(), from, [](double t, const TrackPoint& p) { return t < p.time_s; });
       it != track.end() && it->time_s < to; ++it) {
    out.push_back(it->position_m);
  }
  out.push_back(at(to));
  return out;
}

// ---------------------------------------------------------------- legend symbols

LegendEntry line_entry(const cv::Scalar& color, int thickness, std::string text, bool dashed = false) {
  return {[=](cv::Mat& image, cv::Point2d c) {
            const std::vector<cv::Point2d> line{c + cv::Point2d(-16, 0), c + cv::Point2d(16, 0)};
            if (dashed) figure::dashed_polyline(image, line, color, thickness, 7.0, 4.0);
            else figure::polyline(image, line, color, thickness);
          },
          std::move(text)};
}

LegendEntry patch_entry(const cv::Scalar& fill, const cv::Scalar& edge, std::string text) {
  return {[=](cv::Mat& image, cv::Point2d c) {
            const cv::Rect box(static_cast<int>(c.x) - 12, static_cast<int>(c.y) - 7, 24, 14);
            cv::rectangle(image, box, fill, cv::FILLED);
            cv::rectangle(image, box, edge, 1, cv::LINE_8);
          },
          std::move(text)};
}

LegendEntry marker_entry(std::function<void(cv::Mat&, cv::Point2d)> marker, std::string text) {
  return {std::move(marker), std::move(text)};
}

LegendEntry gradient_entry(std::string text) {
  return {[](cv::Mat& image, cv::Point2d c) {
            figure::polyline(image, {c + cv::Point2d(-16, 0), c + cv::Point2d(16, 0)}, kTrackHalo, 5);
            for (int i = 0; i < 8; ++i) {
              const cv::Point2d a = c + cv::Point2d(-16 + 4 * i, 0), b = a + cv::Point2d(4, 0);
              cv::line(image, figure::fixed(a), figure::fixed(b), to_scalar(sequential_color(i / 7.0)), 3, cv::LINE_AA,
                       figure::kShift);
            }
          },
          std::move(text)};
}

void sensor_hit_marker(cv::Mat& image, cv::Point2d c) {
  cv::circle(image, figure::fixed(c), 2 << figure::kShift, kSensorHit, cv::FILLED, cv::LINE_AA, figure::kShift);
}

// ---------------------------------------------------------------- maps

// Everything a map shows, decided before the layout because the legend's size depends on it.
struct MapPlan {
  explicit MapPlan(const Scene& scene) : ground(scene) {}
  std::vector<const RunView*> runs;
  bool overlay = false;
  Eigen::AlignedBox2d bounds;
  Ground ground;
  double contour_interval_m = 0.0;
  std::vector<Footprint> footprints;        // visible solids, lowest top first
  std::vector<std::size_t> movers;          // indices of visible movers
  std::vector<Footprint> mover_footprints;  // at their first point, aligned with `movers`
  std::vector<Eigen::Vector3d> starts;      // distinct
  std::vector<Waypoint> mission;            // distinct operator waypoints; the last is the goal
  std::vector<bool> mission_reached;        // single-run maps only
  bool colorbar = false;
  TrackColoring coloring = TrackColoring::time;
  double value_lo = 0.0, value_hi = 1.0;    // range of the track colouring
  std::string colorbar_caption;
  std::vector<LegendEntry> legend;
  const HeightMapView* height_map = nullptr;  // a height-map figure: cells coloured, obstacles outlined
};

Eigen::AlignedBox2d map_bounds(const Scene& scene, const std::vector<const RunView*>& runs,
                               const std::vector<Footprint>& solids, double margin_m) {
  Eigen::AlignedBox2d box;
  // A mission given on a grid (seed 001's fields) shows the whole grid.
  if (!runs.empty()) {
    for (const VehicleDef& vehicle : scene.vehicles) {
      if (vehicle.mission_area_m) box.extend(*vehicle.mission_area_m);
    }
  }
  for (const RunView* run : runs) {
    for (const auto& p : run->track) box.extend(xy(p.position_m));
    for (const auto& w : run->mission) box.extend(xy(w.position_m));
    for (const auto& p : run->planned) box.extend(xy(p));
    for (const auto& p : run->discarded) box.extend(xy(p));
    for (const auto& p : run->planned_path) box.extend(xy(p));
  }
  if (box.isEmpty()) {  // nothing recorded: the whole scene
    for (const auto& f : solids) box.extend(f.box_m);
  }
  if (box.isEmpty()) box = Eigen::AlignedBox2d(Eigen::Vector2d(-10.0, -10.0), Eigen::Vector2d(10.0, 10.0));
  // At least 2 m across, so that a single point still gives a readable map.
  const Eigen::Vector2d grow = (Eigen::Vector2d::Constant(2.0) - box.sizes()).cwiseMax(0.0) / 2.0;
  box = Eigen::AlignedBox2d(box.min() - grow, box.max() + grow);
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(margin_m);
  box = Eigen::AlignedBox2d(box.min() - margin, box.max() + margin);
  // Obstacles cut by the border are shown whole when that grows the map by at most the margin.
  const Eigen::AlignedBox2d limit(box.min() - margin, box.max() + margin);
  Eigen::AlignedBox2d grown = box;
  for (const auto& f : solids) {
    if (f.box_m.intersects(box) && limit.contains(f.box_m)) grown.extend(f.box_m);
  }
  return grown;
}

// The nominal route of a run: straight legs from its start through every mission waypoint.
bool has_nominal_route(const RunView& run) { return !run.track.empty() && !run.mission.empty(); }
std::vector<Eigen::Vector3d> nominal_route(const RunView& run) {
  std::vector<Eigen::Vector3d> route{run.track.front().position_m};
  for (const Waypoint& w : run.mission) route.push_back(w.position_m);
  return route;
}

void add_symbol_entries(MapPlan& plan, const Scene& scene) {
  auto& legend = plan.legend;
  const bool overlay = plan.overlay;
  const auto any = [&](auto member) {
    return std::any_of(plan.runs.begin(), plan.runs.end(), [&](const RunView* r) { return !(r->*member).empty(); });
  };
  // A height map shows what was mapped and flown, not the planner's steps.
  const bool steps = !plan.height_map;
  if (steps && std::any_of(plan.runs.begin(), plan.runs.end(), [](const RunView* r) { return r->planned_path.size() >= 2; })) {
    legend.push_back(line_entry(overlay ? kNeutralMarker : kPlannedPath, 1, "planned path", true));
  }
  if (steps && !overlay && has_nominal_route(*plan.runs.front())) {
    legend.push_back(line_entry(kNominalRoute, 2, "nominal route", true));
  }
  if (!plan.movers.empty()) {
    const cv::Scalar c = figure::shade(to_bgr(scene.movers[plan.movers.front()].shape.color), 0.7);
    legend.push_back(line_entry(c, 2, "moving obstacle path", true));
  }
  if (plan.height_map) {
    if (!plan.footprints.empty()) legend.push_back(line_entry(figure::kInk, 1, "obstacle in the scene"));
  } else if (!plan.footprints.empty()) {
    // The colour of the largest obstacle stands for all.
    const auto area = [](const Footprint& f) { return f.box_m.volume(); };
    const Footprint& largest = *std::max_element(plan.footprints.begin(), plan.footprints.end(),
                                                 [&](const Footprint& a, const Footprint& b) { return area(a) < area(b); });
    const cv::Scalar c = to_bgr(largest.shape->color);
    legend.push_back(patch_entry(c, figure::shade(c, 0.6), "obstacle"));
  }
  if (plan.contour_interval_m > 0.0) {
    legend.push_back(line_entry(plan.ground.contour_color(), 1,
                                "contours every " + figure::format_number(plan.contour_interval_m, plan.contour_interval_m) + " m"));
  }
  if (!plan.starts.empty()) legend.push_back(marker_entry(figure::start_marker, "start"));
  const std::size_t intermediate = plan.mission.empty() ? 0 : plan.mission.size() - 1;
  const auto count_reached = [&](bool reached) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < intermediate; ++i) n += plan.mission_reached[i] == reached;
    return n;
  };
  if (overlay && intermediate > 0) {
    legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, false); },
                                  "mission waypoint"));
  } else if (!overlay) {
    if (count_reached(true) > 0) {
      legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, true); },
                                    "waypoint, reached"));
    }
    if (count_reached(false) > 0) {
      legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, false); },
                                    "waypoint, not reached"));
    }
  }
  if (!plan.mission.empty()) {
    const bool reached = overlay || plan.mission_reached.back();
    legend.push_back(marker_entry([reached](cv::Mat& m, cv::Point2d c) { figure::goal_marker(m, c, reached); },
                                  reached ? "goal" : "goal, not reached"));
  }
  const cv::Scalar planned = overlay ? kNeutralMarker : kPlannedWaypoint;
  const cv::Scalar discarded = overlay ? kNeutralMarker : kDiscardedWaypoint;
  if (steps && any(&RunView::planned)) {
    legend.push_back(marker_entry([planned](cv::Mat& m, cv::Point2d c) { figure::diamond_marker(m, c, planned); },
                                  "planned waypoint"));
  }
  if (steps && any(&RunView::discarded)) {
    legend.push_back(marker_entry([discarded](cv::Mat& m, cv::Point2d c) { figure::cross_marker(m, c, discarded); },
                                  "discarded waypoint"));
  }
  if (!overlay && steps && any(&RunView::sensor_hits)) {
    legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d c) { sensor_hit_marker(m, c); }, "LIDAR hit"));
  }
}

MapPlan plan_map(const Scene& scene, std::vector<const RunView*> runs, const FigureStyle& style, bool overlay) {
  check_style(style);
  MapPlan plan(scene);
  plan.runs = std::move(runs);
  plan.overlay = overlay;
  std::vector<Footprint> solids = figure::solid_footprints(scene);
  plan.bounds = style.bounds_m ? *style.bounds_m : map_bounds(scene, plan.runs, solids, style.margin_m);
  for (auto& f : solids) {
    if (f.box_m.intersects(plan.bounds)) plan.footprints.push_back(std::move(f));
  }
  for (std::size_t i = 0; i < scene.movers.size(); ++i) {
    Eigen::AlignedBox2d path;
    for (const auto& p : scene.movers[i].path_m) path.extend(xy(p));
    if (!path.intersects(plan.bounds)) continue;
    plan.movers.push_back(i);
    plan.mover_footprints.push_back(figure::footprint(scene.movers[i].shape));
  }
  plan.contour_interval_m = plan.ground.contour_interval(plan.bounds);

  for (const RunView* run : plan.runs) {
    if (!run->track.empty() && !contains_near(plan.starts, run->track.front().position_m)) {
      plan.starts.push_back(run->track.front().position_m);
    }
    for (std::size_t i = 0; i < run->mission.size(); ++i) {
      // Runs of one scene share their mission: list each waypoint once.
      const bool known = overlay && std::any_of(plan.mission.begin(), plan.mission.end(), [&](const Waypoint& w) {
        return (w.position_m - run->mission[i].position_m).norm() < kSameSpotM;
      });
      if (known) continue;
      plan.mission.push_back(run->mission[i]);
      plan.mission_reached.push_back(is_reached(*run, i));
    }
  }

  if (!overlay && plan.runs.front()->track.size() >= 2) {
    const auto& track = plan.runs.front()->track;
    plan.colorbar = true;
    plan.coloring = style.coloring;
    if (style.coloring == TrackColoring::time) {
      plan.value_lo = track.front().time_s;
      plan.value_hi = track.back().time_s;
      plan.colorbar_caption = "time (s)";
    } else {
      plan.value_lo = 0.0;
      plan.value_hi = 0.0;
      for (const auto& p : track) plan.value_hi = std::max(plan.value_hi, p.speed_mps);
      plan.colorbar_caption = "speed (m/s)";
    }
    if (!(plan.value_hi - plan.value_lo > 1e-9)) plan.value_hi = plan.value_lo + 1.0;
    plan.legend.push_back(gradient_entry(style.coloring == TrackColoring::time ? "track, by time" : "track, by speed"));
    if (!plan.runs.front()->avoiding_s.empty()) plan.legend.push_back(line_entry(kAvoiding, 11, "avoiding obstacle"));
  }
  if (overlay) {
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
      const RunView& r = *plan.runs[i];
      std::string text = r.label.empty() ? "run " + std::to_string(i + 1) : r.label;
      if (!r.outcome.empty()) text += " (" + r.outcome + ")";
      plan.legend.push_back(line_entry(run_color(i), 3, text));
    }
  }
  add_symbol_entries(plan, scene);
  return plan;
}

FigureLayout layout_map(const MapPlan& plan, const FigureStyle& style) {
  const Eigen::Vector2d size = plan.bounds.sizes();
  const double px_per_m = style.max_size_px / size.maxCoeff();
  const int width = std::max(1, static_cast<int>(std::lround(size.x() * px_per_m)));
  int height = std::max(1, static_cast<int>(std::lround(size.y() * px_per_m)));
  const int legend_h = plan.legend.empty() ? 0 : figure::legend_height(plan.legend.size());
  const int colorbar_room = plan.colorbar ? kPanelGapPx + figure::kColorbarCaptionPx : 0;
  const int needed = legend_h + colorbar_room + (plan.colorbar ? kMinColorbarPx : 0) + kPanelGapPx + kScaleBlockPx;
  Eigen::Vector2d min = plan.bounds.min();
  // A flat map grows north and south to make room for the legend column.
  if (height < needed) {
    min.y() -= 0.5 * (needed - height) / px_per_m;
    height = needed;
  }
  FigureLayout l;
  l.image_px = {kFigureLeftPx + width + kFigurePanelPx, kFigureTitlePx + height + kFigureBottomPx};
  l.title_px = {0, 0, l.image_px.width, kFigureTitlePx};
  l.plot_px = {kFigureLeftPx, kFigureTitlePx, width, height};
  const int panel_x = kFigureLeftPx + width + kLegendGapPx;
  if (legend_h > 0) l.legend_px = {panel_x, kFigureTitlePx, kPanelInnerPx, legend_h};
  int y = kFigureTitlePx + legend_h + colorbar_room;
  if (plan.colorbar) {
    const int bar = std::min(kMaxColorbarPx, height - (needed - kMinColorbarPx));
    l.colorbar_px = {panel_x + 8, y, 20, bar};
    y += bar;
  }
  l.scalebar_px = {panel_x, y + kPanelGapPx, kPanelInnerPx, kScaleBlockPx};
  l.min = min;
  l.px_per_unit = Eigen::Vector2d::Constant(px_per_m);
  return l;
}

// Drawing coordinates relative to the plot area, whose image view clips what lies outside.
struct PlotMapper {
  const FigureLayout& layout;
  cv::Point2d operator()(const Eigen::Vector2d& p) const {
    return layout.to_px(p) - cv::Point2d(layout.plot_px.x, layout.plot_px.y);
  }
  cv::Point2d operator()(const Eigen::Vector3d& p) const { return (*this)(xy(p)); }
  template <class Points>
  std::vector<cv::Point2d> all(const Points& points) const {
    std::vector<cv::Point2d> out;
    for (const auto& p : points) out.push_back((*this)(p));
    return out;
  }
};

void draw_footprint(cv::Mat& plot, const PlotMapper& to, const Footprint& f, const cv::Scalar& fill) {
  const std::vector<cv::Point> outline = figure::fixed(to.all(f.outline_m));
  cv::fillConvexPoly(plot, outline, fill, cv::LINE_AA, figure::kShift);
  cv::polylines(plot, outline, true, figure::shade(fill, 0.6), 1, cv::LINE_AA, figure::kShift);
}

// Points at least a pixel apart (the last always kept), so long tracks draw fast and smoothly.
std::vector<std::size_t> thin_out(const std::vector<cv::Point2d>& points) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (kept.empty() || i + 1 == points.size() || cv::norm(points[i] - points[kept.back()]) >= 1.0) kept.push_back(i);
  }
  return kept;
}

// Scale bar with its length above, and a north arrow on the right, in `box`.
void draw_scale_bar(cv::Mat& image, const cv::Rect& box, double px_per_m) {
  // The longest 1-2-5 length that fits left of the arrow.
  const double limit_m = (box.width - 60.0) / px_per_m;
  const double decade = std::pow(10.0, std::floor(std::log10(limit_m)));
  double length_m = decade;
  for (const double m : {5.0, 2.0}) {
    if (m * decade <= limit_m) {
      length_m = m * decade;
      break;
    }
  }
  const double bar_px = length_m * px_per_m;
  const double x0 = box.x + 8.0, y0 = box.y + 30.0;
  cv::rectangle(image, figure::fixed({x0, y0}), figure::fixed({x0 + bar_px / 2, y0 + 7}), figure::kInk, cv::FILLED,
                cv::LINE_AA, figure::kShift);
  cv::rectangle(image, figure::fixed({x0, y0}), figure::fixed({x0 + bar_px, y0 + 7}), figure::kInk, 1, cv::LINE_AA,
                figure::kShift);
  figure::put_text(image, "0", {x0, box.y + 16.0}, figure::kTickFont, figure::kInk, Align::centre);
  figure::put_text(image, figure::format_number(length_m, length_m) + " m", {x0 + bar_px, box.y + 16.0},
                   figure::kTickFont, figure::kInk, Align::centre);
  const cv::Point2d tip(box.x + box.width - 24.0, box.y + 18.0), tail(tip.x, box.y + 46.0);
  cv::arrowedLine(image, figure::fixed(tail), figure::fixed(tip), figure::kInk, 2, cv::LINE_AA, figure::kShift, 0.35);
  figure::put_text(image, "N", {tip.x, box.y + 6.0}, figure::kLabelFont, figure::kInk, Align::centre);
}

// Numbered operator waypoints, the goal last. Waypoints on the same spot
// (e.g. at two altitudes) share one marker labelled with all their numbers;
// so does one under a start marker, which is drawn over it.
void draw_mission(cv::Mat& plot, const PlotMapper& to, const MapPlan& plan) {
  const std::size_t n = plan.mission.size();
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < n; ++i) {
    const cv::Point2d p = to(plan.mission[i].position_m);
    const auto same = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return cv::norm(to(plan.mission[g.front()].position_m) - p) < 4.0;
    });
    if (same != groups.end()) same->push_back(i);
    else groups.push_back({i});
  }
  for (const auto& group : groups) {
    const cv::Point2d p = to(plan.mission[group.front()].position_m);
    const bool has_goal = group.back() + 1 == n;
    if (has_goal) figure::goal_marker(plot, p, plan.overlay || plan.mission_reached.back());
    else figure::waypoint_marker(plot, p, static_cast<int>(group.front() + 1), !plan.overlay && plan.mission_reached[group.front()]);
    const bool under_start = std::any_of(plan.starts.begin(), plan.starts.end(),
                                         [&](const Eigen::Vector3d& s) { return cv::norm(to(s) - p) < 12.0; });
    if (group.size() == 1 && !under_start && (!has_goal || n == 1)) continue;
    std::string numbers;
    for (std::size_t i : group) numbers += (numbers.empty() ? "" : ", ") + std::to_string(i + 1);
    // Right of the marker, or left of it when that would leave the plot.
    const bool fits = p.x + 15.0 + figure::text_size(numbers, figure::kTickFont).width < plot.cols - 2;
    figure::put_text(plot, numbers, p + cv::Point2d(fits ? 15 : -15, -12), figure::kTickFont, figure::kInk,
                     fits ? Align::left : Align::right, true);
  }
}

// Mapped cells as filled squares coloured by height; unmapped cells keep the ground.
void paint_height_map(cv::Mat& plot, const PlotMapper& to, const HeightMapView& map, double lo, double hi) {
  for (int row = 0; row < map.rows; ++row) {
    for (int col = 0; col < map.columns; ++col) {
      const double top = map.top_m[static_cast<std::size_t>(row) * map.columns + col];
      if (std::isnan(top)) continue;
      const Eigen::Vector2d sw = map.origin_m + map.cell_size_m * Eigen::Vector2d(col, row);
      const cv::Point2d a = to(sw), b = to(Eigen::Vector2d(sw + Eigen::Vector2d::Constant(map.cell_size_m)));
      cv::rectangle(plot, figure::fixed(a), figure::fixed(b), to_scalar(sequential_color((top - lo) / (hi - lo))),
                    cv::FILLED, cv::LINE_8, figure::kShift);
    }
  }
}

cv::Mat draw_map_figure(const Scene& scene, const MapPlan& plan, const FigureLayout& layout,
                        const std::string& title) {
  cv::Mat image(layout.image_px, CV_8UC3, figure::kWhite);
  cv::Mat plot = image(layout.plot_px);
  const PlotMapper to{layout};
  const double px_per_m = layout.px_per_unit.x();

  const Eigen::Vector2d top_left = layout.min + Eigen::Vector2d(0.5, layout.plot_px.height - 0.5) / px_per_m;
  plan.ground.paint(plot, top_left, px_per_m, plan.contour_interval_m);
  if (plan.height_map) {
    paint_height_map(plot, to, *plan.height_map, plan.value_lo, plan.value_hi);
    for (const auto& f : plan.footprints) {
      cv::polylines(plot, figure::fixed(to.all(f.outline_m)), true, figure::kInk, 1, cv::LINE_AA, figure::kShift);
    }
  } else {
    for (const auto& f : plan.footprints) draw_footprint(plot, to, f, to_bgr(f.shape->color));
  }
  for (std::size_t k = 0; k < plan.movers.size(); ++k) {
    const Mover& m = scene.movers[plan.movers[k]];
    const cv::Scalar c = to_bgr(m.shape.color);
    draw_footprint(plot, to, plan.mover_footprints[k], figure::lighten(c, 0.3));
    figure::dashed_polyline(plot, to.all(m.path_m), figure::shade(c, 0.7), 2, 10.0, 6.0);
  }

  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const RunView& run = *plan.runs[i];
    const cv::Scalar own = run_color(i);
    if (!plan.overlay && !plan.height_map) {
      // Under everything else of the run, so the planned path and the track stay visible.
      for (const auto& [from, until] : run.avoiding_s) {
        const std::vector<cv::Point2d> band = to.all(track_between(run.track, from, until));
        std::vector<cv::Point2d> thinned;
        for (std::size_t k : thin_out(band)) thinned.push_back(band[k]);
        if (thinned.size() == 1) thinned.push_back(thinned.front());  // a single spot: a round blob
        figure::polyline(plot, thinned, kAvoiding, kAvoidingBandPx);
      }
    }
    if (!plan.height_map) {
      figure::dashed_polyline(plot, to.all(run.planned_path), plan.overlay ? own : kPlannedPath, 1, 7.0, 5.0);
    }
    std::vector<cv::Point2d> track;
    for (const auto& p : run.track) track.push_back(to(p.position_m));
    const std::vector<std::size_t> kept = thin_out(track);
    std::vector<cv::Point2d> line;
    for (std::size_t k : kept) line.push_back(track[k]);
    if (plan.overlay || plan.height_map) {
      figure::polyline(plot, line, figure::kWhite, 5);
      figure::polyline(plot, line, plan.height_map ? kTrackHalo : own, plan.height_map ? 2 : 3);
      continue;
    }
    figure::polyline(plot, line, kTrackHalo, 5);
    for (std::size_t k = 1; k < kept.size(); ++k) {
      const TrackPoint& p = run.track[kept[k]];
      const double value = plan.coloring == TrackColoring::time ? p.time_s : p.speed_mps;
      const double f = (value - plan.value_lo) / (plan.value_hi - plan.value_lo);
      cv::line(plot, figure::fixed(line[k - 1]), figure::fixed(line[k]), to_scalar(sequential_color(f)), 3,
               cv::LINE_AA, figure::kShift);
    }
  }
  if (!plan.overlay && !plan.height_map) {
    for (const auto& p : plan.runs.front()->sensor_hits) sensor_hit_marker(plot, to(p));
  }
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const RunView& run = *plan.runs[i];
    if (plan.height_map) break;  // the height map shows what was mapped, not the planner's steps
    for (const auto& p : run.planned) {
      figure::diamond_marker(plot, to(p), plan.overlay ? run_color(i) : kPlannedWaypoint);
    }
    for (const auto& p : run.discarded) {
      figure::cross_marker(plot, to(p), plan.overlay ? run_color(i) : kDiscardedWaypoint);
    }
  }
  // Over the track, the hits and the planned waypoints, thin and dashed, so that where the track leaves it both show.
  if (!plan.overlay && !plan.height_map && has_nominal_route(*plan.runs.front())) {
    figure::dashed_polyline(plot, to.all(nominal_route(*plan.runs.front())), kNominalRoute, 2, 9.0, 6.0);
  }
  draw_mission(plot, to, plan);
  for (const auto& s : plan.starts) figure::start_marker(plot, to(s));

  const figure::PlotFrame frame{layout.plot_px, layout.min.x(), layout.min.x() + layout.plot_px.width / px_per_m,
                                layout.min.y(), layout.min.y() + layout.plot_px.height / px_per_m};
  figure::draw_axes(image, frame, "x, east (m)", "y, north (m)");
  if (!plan.legend.empty()) figure::draw_legend(image, layout.legend_px, plan.legend);
  draw_scale_bar(image, layout.scalebar_px, px_per_m);
  if (plan.colorbar) {
    figure::draw_colorbar(image, layout.colorbar_px, plan.value_lo, plan.value_hi, plan.colorbar_caption,
                          sequential_color);
  }
  figure::put_title(image, title, layout.title_px);
  return image;
}

std::string run_title(const FigureStyle& style, const RunView& run, const std::string& what) {
  if (!style.title.empty()) return style.title;
  std::string title = run.label.empty() ? what : run.label + " - " + what;
  if (!run.outcome.empty()) title += " (" + run.outcome + ")";
  return title;
}

std::vector<const RunView*> pointers(const std::vector<RunView>& runs) {
  std::vector<const RunView*> out;
  for (const auto& r : runs) out.push_back(&r);
  return out;
}

// ---------------------------------------------------------------- side view

struct Profile {
  std::vector<double> distance_m;  // horizontal, along the track
  std::vector<double> altitude_m;
  std::vector<double> ground_m;    // NaN where there is no ground
  cv::Scalar ground_color;
  struct Crossing {
    std::size_t solid;        // index into `solids`
    std::size_t first, last;  // samples above or below it
  };
  std::vector<Footprint> solids;   // lowest top first
  std::vector<Crossing> crossings; // in the order of `solids`
  std::vector<std::pair<double, std::size_t>> waypoints;  // (distance of closest approach, mission index)
  double x0 = 0.0, x1 = 1.0, y0 = 0.0, y1 = 1.0;
  std::vector<LegendEntry> legend;
};

// Runs of consecutive samples where `keep(i)` holds, as [first, last] index pairs.
template <class Keep>
std::vector<std::pair<std::size_t, std::size_t>> runs_where(std::size_t n, Keep keep) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < n;) {
    if (!keep(i)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < n && keep(j + 1)) ++j;
    out.emplace_back(i, j);
    i = j + 1;
  }
  return out;
}

Profile profile_of(const Scene& scene, const RunView& run) {
  Profile p;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Ground ground(scene);
  double s = 0.0;
  Eigen::AlignedBox2d track_box;
  for (std::size_t i = 0; i < run.track.size(); ++i) {
    const Eigen::Vector3d& q = run.track[i].position_m;
    if (i > 0) s += (xy(q) - xy(run.track[i - 1].position_m)).norm();
    p.distance_m.push_back(s);
    p.altitude_m.push_back(q.z());
    const auto g = ground.height(q.x(), q.y());
    p.ground_m.push_back(g ? *g : nan);
    track_box.extend(xy(q));
  }
  p.ground_color = ground.color();
  p.solids = figure::solid_footprints(scene);
  for (std::size_t k = 0; k < p.solids.size(); ++k) {
    const Footprint& f = p.solids[k];
    if (!f.box_m.intersects(track_box)) continue;
    for (const auto& [a, b] : runs_where(run.track.size(), [&](std::size_t i) { return f.contains(xy(run.track[i].position_m)); })) {
      p.crossings.push_back({k, a, b});
    }
  }
  for (std::size_t w = 0; w < run.mission.size(); ++w) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t at = 0;
    for (std::size_t i = 0; i < run.track.size(); ++i) {
      const double d = (run.track[i].position_m - run.mission[w].position_m).norm();
      if (d < best) {
        best = d;
        at = i;
      }
    }
    if (!run.track.empty()) p.waypoints.emplace_back(p.distance_m[at], w);
  }

  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const auto extend = [&](double v) {
    if (std::isnan(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  for (std::size_t i = 0; i < p.distance_m.size(); ++i) {
    extend(p.altitude_m[i]);
    extend(p.ground_m[i]);
  }
  for (const auto& c : p.crossings) extend(p.solids[c.solid].top_m);
  for (const auto& [d, w] : p.waypoints) extend(run.mission[w].position_m.z());
  if (!(hi >= lo)) {  // no track
    lo = 0.0;
    hi = 1.0;
  }
  const double pad = std::max(0.1 * (hi - lo), 0.3);
  p.y0 = lo - pad;
  p.y1 = hi + pad;
  const double length = std::max(s, 1.0);
  p.x0 = -0.02 * length;
  p.x1 = 1.02 * length;

  if (!run.track.empty()) p.legend.push_back(line_entry(kVehicleLine, 2, "vehicle altitude"));
  if (std::any_of(p.ground_m.begin(), p.ground_m.end(), [](double g) { return !std::isnan(g); })) {
    p.legend.push_back(patch_entry(figure::lighten(p.ground_color, 0.45), figure::shade(p.ground_color, 0.6),
                                   "ground beneath track"));
  }
  if (!p.crossings.empty()) {
    const cv::Scalar c = to_bgr(p.solids[p.crossings.back().solid].shape->color);
    p.legend.push_back(patch_entry(c, figure::shade(c, 0.6), "obstacle on the track"));
  }
  if (!run.track.empty()) p.legend.push_back(marker_entry(figure::start_marker, "start"));
  bool reached = false, missed = false;
  for (const auto& [d, w] : p.waypoints) {
    if (w + 1 == run.mission.size()) continue;
    (is_reached(run, w) ? reached : missed) = true;
  }
  if (reached) {
    p.legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, true); },
                                    "waypoint, reached"));
  }
  if (missed) {
    p.legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, false); },
                                    "waypoint, not reached"));
  }
  if (!p.waypoints.empty()) {
    const bool goal = is_reached(run, run.mission.size() - 1);
    p.legend.push_back(marker_entry([goal](cv::Mat& m, cv::Point2d c) { figure::goal_marker(m, c, goal); },
                                    goal ? "goal" : "goal, not reached"));
  }
  return p;
}

bool has_ground(const Profile& p) {
  return std::any_of(p.ground_m.begin(), p.ground_m.end(), [](double g) { return !std::isnan(g); });
}

FigureLayout layout_side_view(const Profile& p, const FigureStyle& style) {
  const int width = style.max_size_px;
  const int legend_h = p.legend.empty() ? 0 : figure::legend_height(p.legend.size());
  const int height = std::max({240, static_cast<int>(std::lround(0.35 * style.max_size_px)), legend_h});
  FigureLayout l;
  l.image_px = {kFigureLeftPx + width + kFigurePanelPx, kFigureTitlePx + height + kFigureBottomPx};
  if (has_ground(p) && !p.distance_m.empty()) {
    const int agl_h = std::max(120, static_cast<int>(std::lround(0.12 * style.max_size_px)));
    l.agl_plot_px = {kFigureLeftPx, kFigureTitlePx + height + kFigureBottomPx, width, agl_h};
    l.image_px.height += agl_h + kFigureBottomPx;
  }
  l.title_px = {0, 0, l.image_px.width, kFigureTitlePx};
  l.plot_px = {kFigureLeftPx, kFigureTitlePx, width, height};
  if (legend_h > 0) {
    l.legend_px = {kFigureLeftPx + width + kLegendGapPx, kFigureTitlePx, kPanelInnerPx, legend_h};
  }
  l.min = {p.x0, p.y0};
  l.px_per_unit = {width / (p.x1 - p.x0), height / (p.y1 - p.y0)};
  return l;
}

// The height above the ground beneath the track, on the profile's distance
// axis, over the band between its smallest and largest value (shaded, both
// labelled), with the ground itself as the zero line.
void draw_height_above_ground(cv::Mat& image, const Profile& p, const cv::Rect& plot_px) {
  std::vector<double> agl(p.distance_m.size(), std::numeric_limits<double>::quiet_NaN());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < agl.size(); ++i) {
    if (std::isnan(p.ground_m[i])) continue;
    agl[i] = p.altitude_m[i] - p.ground_m[i];
    lo = std::min(lo, agl[i]);
    hi = std::max(hi, agl[i]);
  }
  const double pad = std::max(0.15 * (hi - lo), 0.3);
  const figure::PlotFrame frame{plot_px, p.x0, p.x1, std::min(0.0, lo - pad), hi + pad};
  figure::draw_grid(image, frame);
  cv::Mat plot = image(plot_px);
  const cv::Point2d origin(plot_px.x, plot_px.y);
  const auto to = [&](double s, double h) { return frame.to_px(s, h) - origin; };
  const cv::Scalar band = figure::lighten(kVehicleLine, 0.8);
  cv::rectangle(plot, figure::fixed(to(p.x0, hi)), figure::fixed(to(p.x1, lo)), band, cv::FILLED,
                cv::LINE_AA, figure::kShift);
  const cv::Scalar ground_edge = figure::shade(p.ground_color, 0.6);
  figure::polyline(plot, {to(p.x0, 0.0), to(p.x1, 0.0)}, ground_edge, 2);
  for (const auto& [a, b] : runs_where(agl.size(), [&](std::size_t i) { return !std::isnan(agl[i]); })) {
    std::vector<cv::Point2d> curve;
    for (std::size_t i = a; i <= b; ++i) curve.push_back(to(p.distance_m[i], agl[i]));
    std::vector<cv::Point2d> line;
    for (std::size_t k : thin_out(curve)) line.push_back(curve[k]);
    figure::polyline(plot, line, kVehicleLine, 2);
  }
  figure::draw_axes(image, frame, "distance along track, horizontal (m)", "above ground (m)");
  const double label_x = plot_px.x + plot_px.width + 12.0;
  figure::put_text(image, "highest " + figure::format_number(hi, 0.01) + " m", {label_x, origin.y + to(p.x1, hi).y},
                   figure::kLabelFont, figure::kInk);
  figure::put_text(image, "lowest " + figure::format_number(lo, 0.01) + " m", {label_x, origin.y + to(p.x1, lo).y},
                   figure::kLabelFont, figure::kInk);
}

cv::Mat draw_side_figure(const RunView& run, const Profile& p, const FigureLayout& layout,
                         const std::string& title) {
  cv::Mat image(layout.image_px, CV_8UC3, figure::kWhite);
  const figure::PlotFrame frame{layout.plot_px, p.x0, p.x1, p.y0, p.y1};
  figure::draw_grid(image, frame);
  cv::Mat plot = image(layout.plot_px);
  const cv::Point2d origin(layout.plot_px.x, layout.plot_px.y);
  const auto to = [&](double s, double z) { return frame.to_px(s, z) - origin; };
  const std::size_t n = p.distance_m.size();
  // Half-way to the neighbouring samples, so that a run of one sample still has a width.
  const auto left_edge = [&](std::size_t i) { return i == 0 ? p.distance_m[0] : 0.5 * (p.distance_m[i - 1] + p.distance_m[i]); };
  const auto right_edge = [&](std::size_t i) {
    return i + 1 == n ? p.distance_m[i] : 0.5 * (p.distance_m[i] + p.distance_m[i + 1]);
  };

  // Obstacles over their vertical extent; the ground drawn next hides what is buried.
  for (const auto& c : p.crossings) {
    const Footprint& f = p.solids[c.solid];
    const double top = f.top_m, bottom = std::max(f.bottom_m, p.y0 - 2.0 / layout.px_per_unit.y());
    const std::vector<cv::Point2d> block{to(left_edge(c.first), bottom), to(left_edge(c.first), top),
                                         to(right_edge(c.last), top), to(right_edge(c.last), bottom)};
    const cv::Scalar colour = to_bgr(f.shape->color);
    const std::vector<cv::Point> outline = figure::fixed(block);
    cv::fillConvexPoly(plot, outline, colour, cv::LINE_AA, figure::kShift);
    cv::polylines(plot, outline, true, figure::shade(colour, 0.6), 1, cv::LINE_AA, figure::kShift);
  }
  const cv::Scalar fill = figure::lighten(p.ground_color, 0.45), edge = figure::shade(p.ground_color, 0.6);
  for (const auto& [a, b] : runs_where(n, [&](std::size_t i) { return !std::isnan(p.ground_m[i]); })) {
    std::vector<cv::Point2d> surface;
    for (std::size_t i = a; i <= b; ++i) surface.push_back(to(p.distance_m[i], p.ground_m[i]));
    std::vector<cv::Point2d> area = surface;
    area.push_back(to(p.distance_m[b], p.y0) + cv::Point2d(0, 2));
    area.push_back(to(p.distance_m[a], p.y0) + cv::Point2d(0, 2));
    const std::vector<std::vector<cv::Point>> polygons{figure::fixed(area)};
    cv::fillPoly(plot, polygons, fill, cv::LINE_AA, figure::kShift);
    figure::polyline(plot, surface, edge, 2);
  }
  std::vector<cv::Point2d> curve;
  for (std::size_t i = 0; i < n; ++i) curve.push_back(to(p.distance_m[i], p.altitude_m[i]));
  std::vector<cv::Point2d> line;
  for (std::size_t k : thin_out(curve)) line.push_back(curve[k]);
  figure::polyline(plot, line, kVehicleLine, 2);
  for (const auto& [d, w] : p.waypoints) {
    const cv::Point2d at = to(d, run.mission[w].position_m.z());
    if (w + 1 == run.mission.size()) {
      figure::goal_marker(plot, at, is_reached(run, w));
    } else {
      figure::waypoint_marker(plot, at, static_cast<int>(w + 1), is_reached(run, w));
    }
  }
  if (n > 0) figure::start_marker(plot, curve.front());

  figure::draw_axes(image, frame, "distance along track, horizontal (m)", "altitude (m)");
  if (!layout.agl_plot_px.empty()) draw_height_above_ground(image, p, layout.agl_plot_px);
  if (!p.legend.empty()) figure::draw_legend(image, layout.legend_px, p.legend);
  figure::put_title(image, title, layout.title_px);
  return image;
}

// ---------------------------------------------------------------- depth maps

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
void draw_ring(cv::Mat& image, cv::Point2d c, double radius) {
  const int r = static_cast<int>(std::lround(radius * (1 << figure::kShift)));
  cv::circle(image, figure::fixed(c), r, figure::kWhite, 5, cv::LINE_AA, figure::kShift);
  cv::circle(image, figure::fixed(c), r, kRing, 2, cv::LINE_AA, figure::kShift);
}

// W' as a plus on a white halo.
void draw_projection(cv::Mat& image, cv::Point2d c) {
  for (int pass = 0; pass < 2; ++pass) {
    for (const cv::Point2d d : {cv::Point2d(5, 0), cv::Point2d(0, 5)}) {
      cv::line(image, figure::fixed(c - d), figure::fixed(c + d), pass == 0 ? figure::kWhite : kProjection,
               pass == 0 ? 5 : 2, cv::LINE_AA, figure::kShift);
    }
  }
}

// An ellipse of half-axes `axes` (figure pixels) around `c`, on a white halo.
void draw_ellipse(cv::Mat& image, cv::Point2d c, cv::Size2d axes) {
  const cv::Size fixed_axes(static_cast<int>(std::lround(axes.width * (1 << figure::kShift))),
                            static_cast<int>(std::lround(axes.height * (1 << figure::kShift))));
  cv::ellipse(image, figure::fixed(c), fixed_axes, 0.0, 0.0, 360.0, figure::kWhite, 4, cv::LINE_AA, figure::kShift);
  cv::ellipse(image, figure::fixed(c), fixed_axes, 0.0, 0.0, 360.0, kProjection, 2, cv::LINE_AA, figure::kShift);
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
        [ellipse](cv::Mat& m, cv::Point2d p) {
          if (ellipse) draw_ellipse(m, p, {13.0, 8.0});
          draw_projection(m, p);
        },
        "W' (" + pixel_text(*overlays.waypoint_projection, 0.1) + ")" + (ellipse ? ", safety sphere" : "")));
  }
  if (overlays.chosen_pixel) {
    const cv::Point c = *overlays.chosen_pixel;
    legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d p) { draw_ring(m, p, 7.0); },
                                  "chosen pixel (column " + std::to_string(c.x) + ", row " + std::to_string(c.y) + ")"));
  }
  if (!overlays.scan_line.empty()) legend.push_back(line_entry(kScanLine, 2, "scan line"));
  if (overlays.new_waypoint_pixel) {
    legend.push_back(marker_entry([](cv::Mat& m, cv::Point2d p) { figure::diamond_marker(m, p, kPlannedWaypoint); },
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

cv::Mat depth_panel(const cv::Mat& values, bool colour, int scale) {
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
  cv::Mat big;
  cv::resize(small, big, {}, scale, scale, cv::INTER_NEAREST);
  return big;
}

cv::Vec3b grey(double f) {
  const uchar g = cv::saturate_cast<uchar>(255.0 * f);
  return {g, g, g};
}

}  // namespace

FigureLayout map_layout(const Scene& scene, const RunView& run, const FigureStyle& style) {
  return layout_map(plan_map(scene, {&run}, style, false), style);
}

cv::Mat draw_map(const Scene& scene, const RunView& run, const FigureStyle& style) {
  const MapPlan plan = plan_map(scene, {&run}, style, false);
  return draw_map_figure(scene, plan, layout_map(plan, style), run_title(style, run, "map"));
}

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

namespace {

MapPlan plan_height_map(const Scene& scene, const RunView& run, const FigureStyle& style) {
  if (run.height_map.empty()) throw std::invalid_argument("the run recorded no height map");
  MapPlan plan = plan_map(scene, {&run}, style, false);
  plan.height_map = &run.height_map;
  plan.value_lo = std::numeric_limits<double>::infinity();
  plan.value_hi = -plan.value_lo;
  for (const double top : run.height_map.top_m) {
    if (std::isnan(top)) continue;
    plan.value_lo = std::min(plan.value_lo, top);
    plan.value_hi = std::max(plan.value_hi, top);
  }
  if (!(plan.value_hi > plan.value_lo)) {
    plan.value_lo = std::isfinite(plan.value_lo) ? plan.value_lo : 0.0;
    plan.value_hi = plan.value_lo + 1.0;
  }
  plan.colorbar = true;
  plan.colorbar_caption = "mapped top, z (m)";
  plan.legend.clear();
  plan.legend.push_back(line_entry(kTrackHalo, 2, "track"));
  add_symbol_entries(plan, scene);
  return plan;
}

}  // namespace

FigureLayout height_map_layout(const Scene& scene, const RunView& run, const FigureStyle& style) {
  return layout_map(plan_height_map(scene, run, style), style);
}

cv::Mat draw_height_map(const Scene& scene, const RunView& run, const FigureStyle& style) {
  const MapPlan plan = plan_height_map(scene, run, style);
  return draw_map_figure(scene, plan, layout_map(plan, style), run_title(style, run, "reconstructed height map"));
}

FigureLayout overlay_layout(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style) {
  return layout_map(plan_map(scene, pointers(runs), style, true), style);
}

cv::Mat draw_overlay(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style) {
  const MapPlan plan = plan_map(scene, pointers(runs), style, true);
  const std::string title = !style.title.empty() ? style.title
                            : runs.size() == 1   ? "1 run"
                                                 : std::to_string(runs.size()) + " runs";
  return draw_map_figure(scene, plan, layout_map(plan, style), title);
}

FigureLayout side_view_layout(const Scene& scene, const RunView& run, const FigureStyle& style) {
  check_style(style);
  return layout_side_view(profile_of(scene, run), style);
}

cv::Mat draw_side_view(const Scene& scene, const RunView& run, const FigureStyle& style) {
  check_style(style);
  const Profile p = profile_of(scene, run);
  return draw_side_figure(run, p, layout_side_view(p, style), run_title(style, run, "altitude profile"));
}

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

cv::Mat draw_depth(const cv::Mat& depth, const DepthOverlays& overlays, bool colour, const std::string& title) {
  const DepthFigureLayout l = depth_layout(depth, overlays, colour);
  cv::Mat image(l.image_px, CV_8UC3, figure::kWhite);
  std::vector<std::pair<const cv::Mat*, std::string>> panels{{&depth, "depth map"}};
  if (!overlays.dilated.empty()) panels.emplace_back(&overlays.dilated, "dilated");
  if (!overlays.thresholded.empty()) {
    panels.emplace_back(&overlays.thresholded,
                        overlays.threshold ? "thresholded at t = " + figure::format_number(*overlays.threshold, 0.001)
                                           : "thresholded");
  }
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const cv::Rect& r = l.panels_px[i];
    depth_panel(*panels[i].first, colour, l.scale).copyTo(image(r));
    cv::rectangle(image, {r.x - 1, r.y - 1}, {r.x + r.width, r.y + r.height}, figure::kInk, 1, cv::LINE_8);
    const std::string caption =
        panels.size() == 1 ? panels[i].second : std::string("(") + char('a' + i) + ") " + panels[i].second;
    figure::put_text(image, caption, {r.x + 0.5 * r.width, r.y + r.height + 0.5 * kDepthCaptionPx}, figure::kLabelFont,
                     figure::kInk, Align::centre);
    // Overlays on every panel, clipped to it, so the choice can be followed across the steps.
    cv::Mat view = image(r);
    const cv::Point2d origin(r.x, r.y);
    std::vector<cv::Point2d> scan;
    for (const auto& p : overlays.scan_line) scan.push_back(l.to_px(i, p) - origin);
    figure::polyline(view, scan, kScanLine, 2);
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
