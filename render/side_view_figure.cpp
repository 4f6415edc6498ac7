#include "render/side_view_figure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/figure_scene.hpp"

namespace campo {

using figure::check_style;
using figure::Footprint;
using figure::Ground;
using figure::is_reached;
using figure::kLegendGapPx;
using figure::kPanelInnerPx;
using figure::LegendEntry;
using figure::line_entry;
using figure::marker_entry;
using figure::patch_entry;
using figure::rgb;
using figure::run_title;
using figure::thin_out;
using figure::to_bgr;
using figure::xy;

namespace {

const cv::Scalar kVehicleLine = rgb(31, 119, 180);
const cv::Scalar kMissionLine = rgb(90, 90, 90);
const cv::Scalar kToGoalLine = rgb(214, 39, 40);  // the goal star's red

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
  // (distance along the track, mission index): a waypoint at the track's closest approach to it; a goal not reached
  // beyond the track's end (goal_distance_m).
  std::vector<std::pair<double, std::size_t>> waypoints;
  // A goal not reached: the track's end (distance, altitude), from where the straight line to the goal is drawn.
  std::optional<std::pair<double, double>> goal_beyond;
  std::vector<double> mission_m;   // the altitude the mission asks for, NaN where unknown
  std::vector<std::pair<double, double>> collisions;  // (distance along the track, altitude) of each point touched
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
    if (run.track.empty()) continue;
    if (w + 1 == run.mission.size() && !is_reached(run, w)) {
      const double d = goal_distance_m(p.distance_m.back(), run.track.back().position_m, run.mission[w].position_m);
      p.waypoints.emplace_back(d, w);
      p.goal_beyond.emplace(p.distance_m.back(), run.track.back().position_m.z());
      s = std::max(s, d);
    } else {
      p.waypoints.emplace_back(p.distance_m[at], w);
    }
  }
  // The mission's altitude: knots at the start and at each waypoint's closest approach after the previous one's (a
  // waypoint revisited later, as 001's laps do, is taken in the order flown).
  if (!run.track.empty() && !run.mission.empty()) {
    std::vector<std::pair<double, double>> knots{{0.0, run.track.front().position_m.z()}};
    std::size_t from = 0;
    for (std::size_t m = 0; m < run.mission.size(); ++m) {
      const Waypoint& w = run.mission[m];
      if (m + 1 == run.mission.size() && p.goal_beyond) {  // a goal not reached: where its marker is
        knots.emplace_back(p.waypoints.back().first, w.position_m.z());
        break;
      }
      double best = std::numeric_limits<double>::infinity();
      std::size_t at = from;
      for (std::size_t i = from; i < run.track.size(); ++i) {
        const double d = (run.track[i].position_m - w.position_m).norm();
        if (d < best) best = d, at = i;
      }
      knots.emplace_back(p.distance_m[at], w.position_m.z());
      from = at;
    }
    p.mission_m = mission_altitude_m(p.distance_m, knots);
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
  // A collision at the distance of the last sample before it, plus how far ahead of it the point lies along the
  // track's heading there (its sideways offset is not distance along the track).
  for (const auto& [t, point] : run.collisions) {
    if (run.track.empty()) break;
    std::size_t i = 0;
    while (i + 1 < run.track.size() && run.track[i + 1].time_s <= t) ++i;
    const std::size_t j = i > 0 ? i - 1 : 0, k = i > 0 ? i : std::min<std::size_t>(1, run.track.size() - 1);
    Eigen::Vector2d heading = xy(run.track[k].position_m) - xy(run.track[j].position_m);
    const Eigen::Vector2d offset = xy(point) - xy(run.track[i].position_m);
    const double ahead = heading.norm() > 1e-9 ? std::max(0.0, offset.dot(heading.normalized())) : offset.norm();
    const double d = p.distance_m[i] + ahead;
    p.collisions.emplace_back(d, point.z());
    extend(point.z());
    s = std::max(s, d);
  }
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
  if (std::any_of(p.mission_m.begin(), p.mission_m.end(), [](double z) { return !std::isnan(z); })) {
    p.legend.push_back(line_entry(kMissionLine, 1, "mission altitude", true));
  }
  if (std::any_of(p.ground_m.begin(), p.ground_m.end(), [](double g) { return !std::isnan(g); })) {
    p.legend.push_back(patch_entry(figure::lighten(p.ground_color, 0.45), figure::shade(p.ground_color, 0.6),
                                   "ground beneath track"));
  }
  if (!p.crossings.empty()) {
    const cv::Scalar c = to_bgr(p.solids[p.crossings.back().solid].shape->color);
    p.legend.push_back(patch_entry(c, figure::shade(c, 0.6), "obstacle on the track"));
  }
  if (!run.track.empty()) p.legend.push_back(marker_entry(figure::start_marker, "start"));
  if (p.goal_beyond) p.legend.push_back(line_entry(kToGoalLine, 1, "straight on to the goal", true));
  if (!p.collisions.empty()) p.legend.push_back(marker_entry(figure::collision_marker, "collision"));
  bool reached = false, missed = false;
  for (const auto& [d, w] : p.waypoints) {
    if (w + 1 == run.mission.size()) continue;
    (is_reached(run, w) ? reached : missed) = true;
  }
  if (reached) {
    p.legend.push_back(marker_entry([](figure::Canvas& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, true); },
                                    "waypoint, reached"));
  }
  if (missed) {
    p.legend.push_back(marker_entry([](figure::Canvas& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, false); },
                                    "waypoint, not reached"));
  }
  if (!p.waypoints.empty()) {
    const bool goal = is_reached(run, run.mission.size() - 1);
    p.legend.push_back(marker_entry([goal](figure::Canvas& m, cv::Point2d c) { figure::goal_marker(m, c, goal); },
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
// labelled right of the panel), with the ground itself as the zero line.
void draw_height_above_ground(figure::Canvas& canvas, const Profile& p, const cv::Rect& plot_px) {
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
  figure::draw_grid(canvas, frame);
  const cv::Point2d origin(plot_px.x, plot_px.y);
  {
    const auto clip = canvas.region(plot_px);
    const auto to = [&](double s, double h) { return frame.to_px(s, h) - origin; };
    canvas.fill_box(to(p.x0, hi), to(p.x1, lo), figure::lighten(kVehicleLine, 0.8));
    canvas.line(to(p.x0, 0.0), to(p.x1, 0.0), figure::shade(p.ground_color, 0.6), 2);
    for (const auto& [a, b] : runs_where(agl.size(), [&](std::size_t i) { return !std::isnan(agl[i]); })) {
      std::vector<cv::Point2d> curve;
      for (std::size_t i = a; i <= b; ++i) curve.push_back(to(p.distance_m[i], agl[i]));
      std::vector<cv::Point2d> line;
      for (std::size_t k : thin_out(curve)) line.push_back(curve[k]);
      canvas.polyline(line, kVehicleLine, 2);
    }
  }
  figure::draw_axes(canvas, frame, "distance along track, horizontal (m)", "above ground (m)");
  // Nearly equal values (a run that held its height) would print one label over the other: apart, or one label
  // when they read the same.
  const double label_x = plot_px.x + plot_px.width + 12.0;
  const std::string high = figure::format_number(hi, 0.01), low = figure::format_number(lo, 0.01);
  const double y_hi = frame.to_px(p.x1, hi).y, y_lo = frame.to_px(p.x1, lo).y;
  if (high == low) {
    figure::put_text(canvas, "highest and lowest " + high + " m", {label_x, 0.5 * (y_hi + y_lo)}, figure::kLabelFont,
                     figure::kInk);
    return;
  }
  const auto [at_hi, at_lo] = labels_apart_px(y_hi, y_lo, kAglLabelGapPx);
  figure::put_text(canvas, "highest " + high + " m", {label_x, at_hi}, figure::kLabelFont, figure::kInk);
  figure::put_text(canvas, "lowest " + low + " m", {label_x, at_lo}, figure::kLabelFont, figure::kInk);
}

// Drawing coordinates of (distance, altitude) relative to the plot area, which the canvas's region clips to.
struct ProfileMapper {
  const figure::PlotFrame& frame;
  cv::Point2d origin;
  cv::Point2d operator()(double s, double z) const { return frame.to_px(s, z) - origin; }
};

// The obstacles a profile's track passed over, under or through, over their vertical extent, and the ground
// beneath it, which hides what is buried.
void draw_profile_ground(figure::Canvas& canvas, const ProfileMapper& to, const Profile& p, const FigureLayout& layout,
                         double y0) {
  const std::size_t n = p.distance_m.size();
  // Half-way to the neighbouring samples, so that a run of one sample still has a width.
  const auto left_edge = [&](std::size_t i) { return i == 0 ? p.distance_m[0] : 0.5 * (p.distance_m[i - 1] + p.distance_m[i]); };
  const auto right_edge = [&](std::size_t i) {
    return i + 1 == n ? p.distance_m[i] : 0.5 * (p.distance_m[i] + p.distance_m[i + 1]);
  };
  for (const auto& c : p.crossings) {
    const Footprint& f = p.solids[c.solid];
    const double top = f.top_m, bottom = std::max(f.bottom_m, y0 - 2.0 / layout.px_per_unit.y());
    const std::vector<cv::Point2d> block{to(left_edge(c.first), bottom), to(left_edge(c.first), top),
                                         to(right_edge(c.last), top), to(right_edge(c.last), bottom)};
    const cv::Scalar colour = to_bgr(f.shape->color);
    canvas.fill_polygon(block, colour);
    canvas.polyline(block, figure::shade(colour, 0.6), 1, true);
  }
  const cv::Scalar fill = figure::lighten(p.ground_color, 0.45), edge = figure::shade(p.ground_color, 0.6);
  for (const auto& [a, b] : runs_where(n, [&](std::size_t i) { return !std::isnan(p.ground_m[i]); })) {
    std::vector<cv::Point2d> surface;
    for (std::size_t i = a; i <= b; ++i) surface.push_back(to(p.distance_m[i], p.ground_m[i]));
    std::vector<cv::Point2d> area = surface;
    area.push_back(to(p.distance_m[b], y0) + cv::Point2d(0, 2));
    area.push_back(to(p.distance_m[a], y0) + cv::Point2d(0, 2));
    canvas.fill_polygon(area, fill);
    canvas.polyline(surface, edge, 2);
  }
}

// A profile's run: the mission's altitude dashed in `mission_colour`, the altitude in `colour`, its waypoints and
// goal, its start and its collisions.
void draw_profile_run(figure::Canvas& canvas, const ProfileMapper& to, const RunView& run, const Profile& p,
                      const cv::Scalar& colour, const cv::Scalar& mission_colour) {
  const std::size_t n = p.distance_m.size();
  for (const auto& [a, b] : runs_where(p.mission_m.size(), [&](std::size_t i) { return !std::isnan(p.mission_m[i]); })) {
    std::vector<cv::Point2d> nominal;
    for (std::size_t i = a; i <= b; ++i) nominal.push_back(to(p.distance_m[i], p.mission_m[i]));
    std::vector<cv::Point2d> thin;
    for (std::size_t k : thin_out(nominal)) thin.push_back(nominal[k]);
    canvas.dashed_polyline(thin, mission_colour, 1, 8.0, 5.0);
  }
  std::vector<cv::Point2d> curve;
  for (std::size_t i = 0; i < n; ++i) curve.push_back(to(p.distance_m[i], p.altitude_m[i]));
  std::vector<cv::Point2d> line;
  for (std::size_t k : thin_out(curve)) line.push_back(curve[k]);
  canvas.polyline(line, colour, 2);
  for (const auto& [d, w] : p.waypoints) {
    const cv::Point2d at = to(d, run.mission[w].position_m.z());
    if (w + 1 == run.mission.size()) {
      if (p.goal_beyond) {  // the goal not reached: the straight line still to go, from the track's end
        canvas.dashed_polyline({to(p.goal_beyond->first, p.goal_beyond->second), at}, kToGoalLine, 1, 4.0, 4.0);
      }
      figure::goal_marker(canvas, at, is_reached(run, w));
    } else {
      figure::waypoint_marker(canvas, at, static_cast<int>(w + 1), is_reached(run, w));
    }
  }
  if (n > 0) figure::start_marker(canvas, curve.front());
  for (const auto& [d, z] : p.collisions) figure::collision_marker(canvas, to(d, z));
}

figure::Canvas draw_side_figure(const RunView& run, const Profile& p, const FigureLayout& layout,
                                const std::string& title) {
  figure::Canvas canvas(layout.image_px);
  const figure::PlotFrame frame{layout.plot_px, p.x0, p.x1, p.y0, p.y1};
  figure::draw_grid(canvas, frame);
  {
    const auto clip = canvas.region(layout.plot_px);
    const ProfileMapper to{frame, cv::Point2d(layout.plot_px.x, layout.plot_px.y)};
    draw_profile_ground(canvas, to, p, layout, p.y0);
    draw_profile_run(canvas, to, run, p, kVehicleLine, kMissionLine);
  }

  figure::draw_axes(canvas, frame, "distance along track, horizontal (m)", "altitude (m)");
  if (!layout.agl_plot_px.empty()) draw_height_above_ground(canvas, p, layout.agl_plot_px);
  if (!p.legend.empty()) figure::draw_legend(canvas, layout.legend_px, p.legend);
  figure::put_title(canvas, title, layout.title_px);
  return canvas;
}

// The vehicles' profiles on shared axes, with the legend of them all: one entry per vehicle in its colour, then
// the symbols any of them shows, once each (the vehicle altitude entry of each profile left out).
Profile fleet_frame(const std::vector<RunView>& vehicles, const std::vector<Profile>& profiles) {
  Profile all;
  all.x0 = all.y0 = std::numeric_limits<double>::infinity();
  all.x1 = all.y1 = -all.x0;
  for (std::size_t i = 0; i < profiles.size(); ++i) {
    const Profile& p = profiles[i];
    all.x0 = std::min(all.x0, p.x0);
    all.x1 = std::max(all.x1, p.x1);
    all.y0 = std::min(all.y0, p.y0);
    all.y1 = std::max(all.y1, p.y1);
    const RunView& v = vehicles[i];
    std::string text = v.label.empty() ? "vehicle " + std::to_string(i + 1) : v.label;
    if (!v.outcome.empty()) text += " (" + v.outcome + ")";
    all.legend.push_back(line_entry(vehicle_color(i), 2, text));
  }
  if (profiles.empty()) all.x0 = all.y0 = 0.0, all.x1 = all.y1 = 1.0;
  std::vector<std::string> texts;
  for (const Profile& p : profiles) {
    for (const LegendEntry& e : p.legend) {
      if (e.text == "vehicle altitude" || std::find(texts.begin(), texts.end(), e.text) != texts.end()) continue;
      texts.push_back(e.text);
      all.legend.push_back(e);
    }
  }
  return all;
}

}  // namespace

figure::Canvas draw_fleet_side_view(const Scene& scene, const std::vector<RunView>& vehicles, const FigureStyle& style) {
  check_style(style);
  std::vector<Profile> profiles;
  for (const RunView& v : vehicles) profiles.push_back(profile_of(scene, v));
  const Profile all = fleet_frame(vehicles, profiles);
  const FigureLayout layout = layout_side_view(all, style);
  figure::Canvas canvas(layout.image_px);
  const figure::PlotFrame frame{layout.plot_px, all.x0, all.x1, all.y0, all.y1};
  figure::draw_grid(canvas, frame);
  {
    const auto clip = canvas.region(layout.plot_px);
    const ProfileMapper to{frame, cv::Point2d(layout.plot_px.x, layout.plot_px.y)};
    for (const Profile& p : profiles) draw_profile_ground(canvas, to, p, layout, all.y0);
    for (std::size_t i = 0; i < profiles.size(); ++i) {
      const cv::Scalar colour = vehicle_color(i);
      draw_profile_run(canvas, to, vehicles[i], profiles[i], colour, figure::lighten(colour, 0.35));
    }
  }
  figure::draw_axes(canvas, frame, "distance along each track, horizontal (m)", "altitude (m)");
  if (!all.legend.empty()) figure::draw_legend(canvas, layout.legend_px, all.legend);
  figure::put_title(canvas, !style.title.empty() ? style.title : std::to_string(vehicles.size()) + " vehicles - altitude profiles",
                    layout.title_px);
  return canvas;
}

std::vector<double> mission_altitude_m(const std::vector<double>& distance_m,
                                       const std::vector<std::pair<double, double>>& knots) {
  std::vector<double> out(distance_m.size(), std::numeric_limits<double>::quiet_NaN());
  if (knots.empty()) return out;
  for (std::size_t i = 0; i < distance_m.size(); ++i) {
    const double s = distance_m[i];
    if (s < knots.front().first || s > knots.back().first) continue;
    // The last knot at or before s, so that a climb at one distance (two knots there) takes the later altitude.
    std::size_t k = 0;
    while (k + 1 < knots.size() && knots[k + 1].first <= s) ++k;
    if (k + 1 == knots.size()) {
      out[i] = knots[k].second;
      continue;
    }
    const auto& [s0, z0] = knots[k];
    const auto& [s1, z1] = knots[k + 1];
    out[i] = s1 > s0 ? z0 + (z1 - z0) * (s - s0) / (s1 - s0) : z1;
  }
  return out;
}

FigureLayout side_view_layout(const Scene& scene, const RunView& run, const FigureStyle& style) {
  check_style(style);
  return layout_side_view(profile_of(scene, run), style);
}

double goal_distance_m(double track_length_m, const Eigen::Vector3d& track_end_m, const Eigen::Vector3d& goal_m) {
  return track_length_m + (xy(goal_m) - xy(track_end_m)).norm();
}

std::pair<double, double> labels_apart_px(double upper_px, double lower_px, double min_gap_px) {
  const double gap = lower_px - upper_px;
  if (gap >= min_gap_px) return {upper_px, lower_px};
  const double mid = 0.5 * (upper_px + lower_px);
  return {mid - 0.5 * min_gap_px, mid + 0.5 * min_gap_px};
}

figure::Canvas draw_side_view(const Scene& scene, const RunView& run, const FigureStyle& style) {
  check_style(style);
  const Profile p = profile_of(scene, run);
  return draw_side_figure(run, p, layout_side_view(p, style), run_title(style, run, "altitude profile"));
}

}  // namespace campo
