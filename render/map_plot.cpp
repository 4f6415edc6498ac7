#include "render/map_plot.hpp"

#include <cctype>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <set>
#include <utility>

namespace campo::figure {
namespace {

const cv::Scalar kDiscardedWaypoint = rgb(200, 40, 120);
const cv::Scalar kPlannedPath = rgb(60, 60, 60);
const cv::Scalar kNominalRoute = rgb(190, 0, 150);  // straight legs through the mission (001 Fig. 5.3/5.7/5.11)
const cv::Scalar kSensorHit = rgb(214, 39, 40);
const cv::Scalar kNeutralMarker = rgb(120, 120, 120);  // legend symbols whose colour is the run's
const cv::Scalar kAvoiding = rgb(255, 196, 100);  // pale amber band under the track while avoiding
constexpr int kAvoidingBandPx = 15;               // its width: 5 px of amber each side of the track's halo
constexpr int kMinColorbarPx = 160;
constexpr int kMaxColorbarPx = 320;
constexpr int kScaleBlockPx = 52; // scale bar and north arrow
constexpr int kPanelGapPx = 24;   // between the blocks of the legend column

// Overlay labels without what they all share: sweep run names ("vineyard__lookahead_m-0.2__seed-1") differ only in
// their middle, which a legend cut at its end would hide. Parts are separated by "__"; labels are kept whole when
// fewer than two, any is empty, or nothing would be left of one.
std::vector<std::string> distinct_parts(const std::vector<std::string>& labels) {
  if (labels.size() < 2) return labels;
  std::vector<std::vector<std::string>> parts;
  for (const std::string& label : labels) {
    if (label.empty()) return labels;
    std::vector<std::string> p;
    for (std::size_t from = 0;;) {
      const std::size_t at = label.find("__", from);
      p.push_back(label.substr(from, at == std::string::npos ? std::string::npos : at - from));
      if (at == std::string::npos) break;
      from = at + 2;
    }
    parts.push_back(std::move(p));
  }
  const auto shared = [&](auto index) {
    for (const auto& p : parts) {
      if (index(p) == nullptr || *index(p) != *index(parts.front())) return false;
    }
    return true;
  };
  std::size_t head = 0, tail = 0;
  while (shared([&](const std::vector<std::string>& p) { return head < p.size() ? &p[head] : nullptr; })) ++head;
  while (shared([&](const std::vector<std::string>& p) { return tail < p.size() ? &p[p.size() - 1 - tail] : nullptr; })) ++tail;
  std::vector<std::string> out;
  for (const auto& p : parts) {
    if (head + tail >= p.size()) return labels;
    std::string text;
    for (std::size_t i = head; i < p.size() - tail; ++i) text += (text.empty() ? "" : ", ") + p[i];
    out.push_back(text);
  }
  return out;
}
constexpr double kSameSpotM = 0.25;  // markers closer than this are drawn once in overlays

cv::Scalar to_scalar(const cv::Vec3b& v) { return {double(v[0]), double(v[1]), double(v[2])}; }

bool contains_near(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p) {
  return std::any_of(points.begin(), points.end(), [&](const auto& q) { return (xy(q) - xy(p)).norm() < kSameSpotM; });
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

LegendEntry gradient_entry(std::string text) {
  return {[](Canvas& canvas, cv::Point2d c) {
            canvas.line(c + cv::Point2d(-16, 0), c + cv::Point2d(16, 0), kTrackHalo, 5);
            for (int i = 0; i < 8; ++i) {
              const cv::Point2d a = c + cv::Point2d(-16 + 4 * i, 0), b = a + cv::Point2d(4, 0);
              canvas.line(a, b, to_scalar(sequential_color(i / 7.0)), 3);
            }
          },
          std::move(text)};
}

void sensor_hit_marker(Canvas& canvas, cv::Point2d c) { canvas.fill_circle(c, 2.0, kSensorHit); }

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

}  // namespace

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
  if (std::any_of(plan.runs.begin(), plan.runs.end(), [](const RunView* r) { return !r->collisions.empty(); })) {
    legend.push_back(marker_entry(figure::collision_marker, "collision"));
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
    // One entry per kind of obstacle (up to four, by area drawn), the kind read from the alias ("field/canopy_3"
    // -> "canopy", "box_row" -> "box_row"), so rows, boxes and posts read apart while a forest's trunks, drawn in
    // several shades, are one entry in the first shade; obstacles without a name are grouped by colour.
    // Solids above the flight band are a group of their own, drawn pale with a dashed edge.
    struct Group {
      cv::Scalar colour;
      bool above = false;
      double area = 0.0;
      std::string name;
    };
    std::vector<Group> groups;
    for (std::size_t i = 0; i < plan.footprints.size(); ++i) {
      const Footprint& f = plan.footprints[i];
      const cv::Scalar c = to_bgr(f.shape->color);
      const bool above = i < plan.above_band.size() && plan.above_band[i];
      std::string name = f.shape->alias.substr(f.shape->alias.find_last_of('/') + 1);
      while (!name.empty() && (std::isdigit(static_cast<unsigned char>(name.back())) || name.back() == '_')) {
        name.pop_back();
      }
      auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& x) {
        return x.above == above && x.name == name && (!name.empty() || x.colour == c);
      });
      if (g == groups.end()) {
        groups.push_back({c, above, 0.0, name});
        g = groups.end() - 1;
      }
      g->area += f.box_m.volume();
    }
    std::stable_sort(groups.begin(), groups.end(), [](const Group& a, const Group& b) { return a.area > b.area; });
    if (groups.size() > 4) groups.resize(4);
    for (const Group& g : groups) {
      if (g.above) {
        // Short enough for the legend column: "crown, above flight band".
        const std::string text = (g.name.empty() ? std::string("obstacle") : g.name) + ", above flight band";
        legend.push_back(patch_entry(figure::lighten(g.colour, kAboveBandLighten), figure::shade(g.colour, 0.6), text));
      } else {
        const std::string text = groups.size() == 1 || g.name.empty() ? "obstacle" : "obstacle: " + g.name;
        legend.push_back(patch_entry(g.colour, figure::shade(g.colour, 0.6), text));
      }
    }
  }
  if (plan.contour_interval_m > 0.0) {
    legend.push_back(line_entry(plan.ground.contour_color(), 1,
                                "contours every " + figure::format_number(plan.contour_interval_m, plan.contour_interval_m) + " m"));
  }
  if (!plan.starts.empty()) legend.push_back(marker_entry(figure::start_marker, "start"));
  const std::size_t intermediate = plan.mission.empty() ? 0 : plan.mission.size() - 1;
  const auto count_reached = [&](bool reached) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < plan.mission.size(); ++i) {
      const bool goal = plan.fleet ? i + 1 == plan.mission.size() || plan.mission_owner[i + 1] != plan.mission_owner[i]
                                   : i >= intermediate;
      if (!goal) n += plan.mission_reached[i] == reached;
    }
    return n;
  };
  if (overlay && !plan.fleet && intermediate > 0) {
    legend.push_back(marker_entry([](Canvas& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, false); },
                                  "mission waypoint"));
  } else if (!overlay || plan.fleet) {
    if (count_reached(true) > 0) {
      legend.push_back(marker_entry([](Canvas& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, true); },
                                    "waypoint, reached"));
    }
    if (count_reached(false) > 0) {
      legend.push_back(marker_entry([](Canvas& m, cv::Point2d c) { figure::waypoint_marker(m, c, 0, false); },
                                    "waypoint, not reached"));
    }
  }
  if (plan.fleet) {
    // Each vehicle's goal is the last waypoint it owns.
    bool reached = false, missed = false;
    for (std::size_t i = 0; i < plan.mission.size(); ++i) {
      const bool goal = i + 1 == plan.mission.size() || plan.mission_owner[i + 1] != plan.mission_owner[i];
      if (goal) (plan.mission_reached[i] ? reached : missed) = true;
    }
    if (reached) legend.push_back(marker_entry([](Canvas& m, cv::Point2d c) { figure::goal_marker(m, c, true); }, "goal"));
    if (missed) {
      legend.push_back(marker_entry([](Canvas& m, cv::Point2d c) { figure::goal_marker(m, c, false); }, "goal, not reached"));
    }
  } else if (!plan.mission.empty()) {
    const bool reached = overlay || plan.mission_reached.back();
    legend.push_back(marker_entry([reached](Canvas& m, cv::Point2d c) { figure::goal_marker(m, c, reached); },
                                  reached ? "goal" : "goal, not reached"));
  }
  const cv::Scalar planned = overlay ? kNeutralMarker : kPlannedWaypoint;
  const cv::Scalar discarded = overlay ? kNeutralMarker : kDiscardedWaypoint;
  if (steps && any(&RunView::planned)) {
    legend.push_back(marker_entry([planned](Canvas& m, cv::Point2d c) { figure::diamond_marker(m, c, planned); },
                                  "planned waypoint"));
  }
  if (steps && any(&RunView::discarded)) {
    legend.push_back(marker_entry([discarded](Canvas& m, cv::Point2d c) { figure::cross_marker(m, c, discarded); },
                                  "discarded waypoint"));
  }
  if (!overlay && steps && any(&RunView::sensor_hits)) {
    legend.push_back(marker_entry([](Canvas& m, cv::Point2d c) { sensor_hit_marker(m, c); }, "LIDAR hit"));
  }
  // The wind the vehicles flew in: an arrow along the steady wind (north up, as the map), its speed and gusts.
  const WindConfig& wind = scene.world.wind;
  if (wind.speed_mps > 0.0 || wind.gust != GustModel::none) {
    const double toward = wind.direction_deg * std::numbers::pi / 180.0;
    const cv::Point2d along(std::cos(toward), -std::sin(toward));
    const auto speed = [](double mps) {
      char text[32];
      std::snprintf(text, sizeof text, "%.3g m/s", mps);
      return std::string(text);
    };
    std::string text = wind.speed_mps > 0.0 ? "wind " + speed(wind.speed_mps) : std::string("wind");
    if (wind.gust == GustModel::one_minus_cos) text += ", 1-cos gust";
    if (wind.gust == GustModel::dryden) {
      text += ", turbulence " + speed(wind.turbulence_intensity_mps);
    }
    legend.push_back(marker_entry(
        [along, steady = wind.speed_mps > 0.0](Canvas& m, cv::Point2d c) {
          if (steady) m.arrow(c - 9.0 * along, c + 9.0 * along, figure::kInk, 2, 0.45);
          else m.circle(c, 4.0, figure::kInk, 1.5);  // gusts only: no steady direction
        },
        text));
  }
}

cv::Scalar plan_color(const MapPlan& plan, std::size_t index) {
  return plan.fleet ? vehicle_color(index) : run_color(index);
}

MapPlan plan_map(const Scene& scene, std::vector<const RunView*> runs, const FigureStyle& style, bool overlay,
                 bool fleet) {
  check_style(style);
  MapPlan plan(scene);
  plan.runs = std::move(runs);
  plan.overlay = overlay || fleet;
  plan.fleet = fleet;
  overlay = plan.overlay;
  std::vector<Footprint> solids = figure::solid_footprints(scene);
  plan.bounds = style.bounds_m ? *style.bounds_m : map_bounds(scene, plan.runs, solids, style.margin_m);
  for (auto& f : solids) {
    if (f.box_m.intersects(plan.bounds)) plan.footprints.push_back(std::move(f));
  }
  plan.band_top_agl_m = flight_band_top_agl(plan.runs, plan.ground);
  for (const Footprint& f : plan.footprints) plan.above_band.push_back(above_flight_band(f, plan.ground, plan.band_top_agl_m));
  for (std::size_t i = 0; i < scene.movers.size(); ++i) {
    Eigen::AlignedBox2d path;
    for (const auto& p : scene.movers[i].path_m) path.extend(xy(p));
    if (!path.intersects(plan.bounds)) continue;
    plan.movers.push_back(i);
    plan.mover_footprints.push_back(figure::footprint(scene.movers[i].shape));
  }
  plan.contour_interval_m = plan.ground.contour_interval(plan.bounds);

  for (std::size_t r = 0; r < plan.runs.size(); ++r) {
    const RunView* run = plan.runs[r];
    if (!run->track.empty() && !contains_near(plan.starts, run->track.front().position_m)) {
      plan.starts.push_back(run->track.front().position_m);
    }
    for (std::size_t i = 0; i < run->mission.size(); ++i) {
      // Runs of one scene share their mission: list each waypoint once. Vehicles each have their own.
      const bool known = overlay && !fleet && std::any_of(plan.mission.begin(), plan.mission.end(), [&](const Waypoint& w) {
        return (w.position_m - run->mission[i].position_m).norm() < kSameSpotM;
      });
      if (known) continue;
      plan.mission.push_back(run->mission[i]);
      plan.mission_reached.push_back(is_reached(*run, i));
      if (fleet) plan.mission_owner.push_back(r);
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
  if (fleet) {
    // One entry per vehicle, named by its alias; its footprint where it ended.
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
      const RunView& r = *plan.runs[i];
      std::string text = r.label.empty() ? "vehicle " + std::to_string(i + 1) : r.label;
      if (!r.outcome.empty()) text += " (" + r.outcome + ")";
      plan.legend.push_back(line_entry(vehicle_color(i), 3, text));
    }
    if (std::any_of(plan.runs.begin(), plan.runs.end(), [](const RunView* r) {
          return !r->track.empty() && r->footprint_m.minCoeff() > 0.0;
        })) {
      plan.legend.push_back(patch_entry(figure::lighten(kNeutralMarker, 0.55), kNeutralMarker, "vehicle, at its end"));
    }
  } else if (overlay) {
    std::vector<std::string> labels;
    for (const RunView* r : plan.runs) labels.push_back(r->label);
    labels = distinct_parts(labels);
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
      const RunView& r = *plan.runs[i];
      std::string text = labels[i].empty() ? "run " + std::to_string(i + 1) : labels[i];
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

std::optional<double> flight_band_top_agl(const std::vector<const RunView*>& runs, const Ground& ground) {
  std::optional<double> top;
  for (const RunView* run : runs) {
    for (const TrackPoint& p : run->track) {
      const double agl = p.position_m.z() - ground.height(p.position_m.x(), p.position_m.y()).value_or(0.0);
      top = std::max(top.value_or(agl), agl);
    }
  }
  return top;
}

bool above_flight_band(const Footprint& f, const Ground& ground, std::optional<double> band_top_agl_m) {
  if (!band_top_agl_m) return false;
  const Eigen::Vector2d c = f.box_m.center();
  return f.bottom_m - ground.height(c.x(), c.y()).value_or(0.0) > *band_top_agl_m;
}

void draw_footprint_above_band(Canvas& plot, const PlotMapper& to, const Footprint& f, const cv::Scalar& colour) {
  std::vector<cv::Point2d> outline = to.all(f.outline_m);
  plot.fill_polygon(outline, figure::lighten(colour, kAboveBandLighten));
  if (!outline.empty()) outline.push_back(outline.front());
  plot.dashed_polyline(outline, figure::shade(colour, 0.6), 1, 5.0, 4.0);
}

void draw_footprint(Canvas& plot, const PlotMapper& to, const Footprint& f, const cv::Scalar& fill) {
  const std::vector<cv::Point2d> outline = to.all(f.outline_m);
  plot.fill_polygon(outline, fill);
  plot.polyline(outline, figure::shade(fill, 0.6), 1, /*closed=*/true);
}

VehicleOutline vehicle_outline(const TrackPoint& at, const Eigen::Vector2d& footprint_m) {
  VehicleOutline o;
  const double yaw = at.yaw_deg * M_PI / 180.0;
  o.ahead = Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
  o.left = Eigen::Vector2d(-o.ahead.y(), o.ahead.x());
  o.centre = xy(at.position_m);
  o.half = 0.5 * footprint_m;
  o.corners = {o.centre + o.half.x() * o.ahead + o.half.y() * o.left, o.centre - o.half.x() * o.ahead + o.half.y() * o.left,
               o.centre - o.half.x() * o.ahead - o.half.y() * o.left, o.centre + o.half.x() * o.ahead - o.half.y() * o.left};
  return o;
}

void draw_vehicle_footprint(Canvas& plot, const PlotMapper& to, const TrackPoint& at, const Eigen::Vector2d& footprint_m,
                            const cv::Scalar& colour, bool fill) {
  const VehicleOutline o = vehicle_outline(at, footprint_m);
  const std::vector<cv::Point2d> outline = to.all(o.corners);
  if (fill) plot.fill_polygon(outline, figure::lighten(colour, 0.55));
  plot.polyline(outline, colour, 2, /*closed=*/true);
  plot.line(to(o.centre), to(Eigen::Vector2d(o.centre + o.half.x() * o.ahead)), colour, 2);
}

void draw_run_marks(Canvas& plot, const PlotMapper& to, const MapPlan& plan) {
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const RunView& run = *plan.runs[i];
    const cv::Scalar own = plan_color(plan, i);
    if (!plan.overlay && !plan.height_map) {
      // Under everything else of the run, so the planned path and the track stay visible.
      for (const auto& [from, until] : run.avoiding_s) {
        const std::vector<cv::Point2d> band = to.all(track_between(run.track, from, until));
        std::vector<cv::Point2d> thinned;
        for (std::size_t k : thin_out(band)) thinned.push_back(band[k]);
        if (thinned.size() == 1) thinned.push_back(thinned.front());  // a single spot: a round blob
        plot.polyline(thinned, kAvoiding, kAvoidingBandPx);
      }
    }
    if (!plan.height_map) {
      plot.dashed_polyline(to.all(run.planned_path), plan.overlay ? own : kPlannedPath, 1, 7.0, 5.0);
    }
    std::vector<cv::Point2d> track;
    for (const auto& p : run.track) track.push_back(to(p.position_m));
    const std::vector<std::size_t> kept = thin_out(track);
    std::vector<cv::Point2d> line;
    for (std::size_t k : kept) line.push_back(track[k]);
    if (plan.overlay || plan.height_map) {
      plot.polyline(line, figure::kWhite, 5);
      plot.polyline(line, plan.height_map ? kTrackHalo : own, plan.height_map ? 2 : 3);
      continue;
    }
    plot.polyline(line, kTrackHalo, 5);
    // Each segment in the colour of its end point; a run of segments of one colour (the colour map has 256)
    // as one polyline, so that a PDF or SVG holds a few hundred paths rather than one per segment.
    std::vector<cv::Point2d> piece;
    cv::Vec3b piece_colour;
    for (std::size_t k = 1; k < kept.size(); ++k) {
      const TrackPoint& p = run.track[kept[k]];
      const double value = plan.coloring == TrackColoring::time ? p.time_s : p.speed_mps;
      const cv::Vec3b colour = sequential_color((value - plan.value_lo) / (plan.value_hi - plan.value_lo));
      if (!piece.empty() && colour != piece_colour) {
        plot.polyline(piece, to_scalar(piece_colour), 3);
        piece.clear();
      }
      if (piece.empty()) piece.push_back(line[k - 1]);
      piece.push_back(line[k]);
      piece_colour = colour;
    }
    plot.polyline(piece, to_scalar(piece_colour), 3);
  }
  if (!plan.overlay && !plan.height_map) {
    // One dot per pixel: thousands of hits along a wall land on the same few pixels, and a PDF or SVG would
    // otherwise hold every one of them.
    std::set<std::pair<long, long>> drawn;
    for (const auto& p : plan.runs.front()->sensor_hits) {
      const cv::Point2d q = to(p);
      if (drawn.emplace(std::lround(q.x), std::lround(q.y)).second) sensor_hit_marker(plot, q);
    }
  }
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const RunView& run = *plan.runs[i];
    if (plan.height_map) break;  // the height map shows what was mapped, not the planner's steps
    for (const auto& p : run.planned) {
      figure::diamond_marker(plot, to(p), plan.overlay ? plan_color(plan, i) : kPlannedWaypoint);
    }
    for (const auto& p : run.discarded) {
      figure::cross_marker(plot, to(p), plan.overlay ? plan_color(plan, i) : kDiscardedWaypoint);
    }
  }
  // Each vehicle of a fleet where its track ends (a video: where it is), over the tracks.
  for (std::size_t i = 0; plan.fleet && i < plan.runs.size(); ++i) {
    const RunView& run = *plan.runs[i];
    if (!run.track.empty() && run.footprint_m.minCoeff() > 0.0) {
      draw_vehicle_footprint(plot, to, run.track.back(), run.footprint_m, plan_color(plan, i));
    }
  }
  // Last, over everything of the runs: where each hit something.
  for (const RunView* run : plan.runs) {
    for (const auto& [t, p] : run->collisions) figure::collision_marker(plot, to(p));
  }
}

namespace {

// Scale bar with its length above, and a north arrow on the right, in `box`.
void draw_scale_bar(Canvas& image, const cv::Rect& box, double px_per_m) {
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
  image.fill_box({x0, y0}, {x0 + bar_px / 2, y0 + 7}, figure::kInk);
  image.polyline({{x0, y0}, {x0 + bar_px, y0}, {x0 + bar_px, y0 + 7}, {x0, y0 + 7}}, figure::kInk, 1, /*closed=*/true);
  figure::put_text(image, "0", {x0, box.y + 16.0}, figure::kTickFont, figure::kInk, Align::centre);
  figure::put_text(image, figure::format_number(length_m, length_m) + " m", {x0 + bar_px, box.y + 16.0},
                   figure::kTickFont, figure::kInk, Align::centre);
  const cv::Point2d tip(box.x + box.width - 24.0, box.y + 18.0), tail(tip.x, box.y + 46.0);
  image.arrow(tail, tip, figure::kInk, 2, 0.35);
  figure::put_text(image, "N", {tip.x, box.y + 6.0}, figure::kLabelFont, figure::kInk, Align::centre);
}

// Numbered operator waypoints, the goal last. Waypoints on the same spot
// (e.g. at two altitudes) share one marker labelled with all their numbers;
// so does one under a start marker, which is drawn over it.
// On fleet maps each vehicle's mission on its own (`from` to `to` of plan.mission), its goal ringed in its colour.
void draw_mission(Canvas& plot, int plot_width_px, const PlotMapper& to, const MapPlan& plan, std::size_t from,
                  std::size_t until) {
  const std::size_t n = until - from;
  const auto mission = [&](std::size_t i) -> const Waypoint& { return plan.mission[from + i]; };
  const auto reached = [&](std::size_t i) { return plan.mission_reached[from + i]; };
  const bool own_marks = !plan.overlay || plan.fleet;  // filled when reached
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < n; ++i) {
    const cv::Point2d p = to(mission(i).position_m);
    const auto same = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return cv::norm(to(mission(g.front()).position_m) - p) < 4.0;
    });
    if (same != groups.end()) same->push_back(i);
    else groups.push_back({i});
  }
  for (const auto& group : groups) {
    const cv::Point2d p = to(mission(group.front()).position_m);
    const bool has_goal = group.back() + 1 == n;
    if (has_goal && plan.fleet) plot.circle(p, 16.0, plan_color(plan, plan.mission_owner[from]), 3.0);
    if (has_goal) figure::goal_marker(plot, p, !own_marks || reached(n - 1));
    else figure::waypoint_marker(plot, p, static_cast<int>(group.front() + 1), own_marks && reached(group.front()));
    const bool under_start = std::any_of(plan.starts.begin(), plan.starts.end(),
                                         [&](const Eigen::Vector3d& s) { return cv::norm(to(s) - p) < 12.0; });
    if (group.size() == 1 && !under_start && (!has_goal || n == 1)) continue;
    std::string numbers;
    for (std::size_t i : group) numbers += (numbers.empty() ? "" : ", ") + std::to_string(i + 1);
    // Right of the marker, or left of it when that would leave the plot.
    const bool fits = p.x + 15.0 + figure::text_size(numbers, figure::kTickFont).width < plot_width_px - 2;
    figure::put_text(plot, numbers, p + cv::Point2d(fits ? 15 : -15, -12), figure::kTickFont, figure::kInk,
                     fits ? Align::left : Align::right, true);
  }
}

// Mapped cells as squares coloured by height; unmapped cells keep the ground. One raster pixel per cell
// (north row first), stretched sharp over the cells' rectangle: a PDF holds the grid, not a rectangle per cell.
void paint_height_map(Canvas& plot, const PlotMapper& to, const HeightMapView& map, double lo, double hi) {
  if (map.rows <= 0 || map.columns <= 0) return;
  cv::Mat cells(map.rows, map.columns, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  for (int row = 0; row < map.rows; ++row) {
    auto* out = cells.ptr<cv::Vec4b>(map.rows - 1 - row);
    for (int col = 0; col < map.columns; ++col) {
      const double top = map.top_m[static_cast<std::size_t>(row) * map.columns + col];
      if (std::isnan(top)) continue;
      const cv::Vec3b c = sequential_color((top - lo) / (hi - lo));
      out[col] = cv::Vec4b(c[0], c[1], c[2], 255);
    }
  }
  // The grid's corners in drawing coordinates; a raster pixel's edges lie half a pixel off its centre, so the
  // rectangle of pixels whose edges are nearest the cells' edges.
  const cv::Point2d nw = to(Eigen::Vector2d(map.origin_m + Eigen::Vector2d(0.0, map.rows * map.cell_size_m)));
  const cv::Point2d se = to(Eigen::Vector2d(map.origin_m + Eigen::Vector2d(map.columns * map.cell_size_m, 0.0)));
  const int x0 = static_cast<int>(std::lround(nw.x + 0.5)), y0 = static_cast<int>(std::lround(nw.y + 0.5));
  const int x1 = static_cast<int>(std::lround(se.x + 0.5)), y1 = static_cast<int>(std::lround(se.y + 0.5));
  plot.image(cells, cv::Rect(x0, y0, std::max(1, x1 - x0), std::max(1, y1 - y0)), /*smooth=*/false);
}

}  // namespace

void draw_map_figure(Canvas& image, const Scene& scene, const MapPlan& plan, const FigureLayout& layout,
                     const std::string& title) {
  const PlotMapper to{layout};
  const double px_per_m = layout.px_per_unit.x();
  {
    auto clip = image.region(layout.plot_px);
    Canvas& plot = image;
    const Eigen::Vector2d top_left = layout.min + Eigen::Vector2d(0.5, layout.plot_px.height - 0.5) / px_per_m;
    plan.ground.paint(plot, layout.plot_px.size(), top_left, px_per_m, plan.contour_interval_m);
    if (plan.height_map) {
      paint_height_map(plot, to, *plan.height_map, plan.value_lo, plan.value_hi);
      for (const auto& f : plan.footprints) plot.polyline(to.all(f.outline_m), figure::kInk, 1, /*closed=*/true);
    } else {
      // Above the flight band first, so that trunks and obstacles at flight height are drawn over pale crowns.
      const auto above = [&](std::size_t i) { return i < plan.above_band.size() && plan.above_band[i]; };
      for (std::size_t i = 0; i < plan.footprints.size(); ++i) {
        const Footprint& f = plan.footprints[i];
        if (above(i)) draw_footprint_above_band(plot, to, f, to_bgr(f.shape->color));
      }
      for (std::size_t i = 0; i < plan.footprints.size(); ++i) {
        const Footprint& f = plan.footprints[i];
        if (!above(i)) draw_footprint(plot, to, f, to_bgr(f.shape->color));
      }
    }
    for (std::size_t k = 0; k < plan.movers.size(); ++k) {
      const Mover& m = scene.movers[plan.movers[k]];
      const cv::Scalar c = to_bgr(m.shape.color);
      if (plan.movers_at_start) draw_footprint(plot, to, plan.mover_footprints[k], figure::lighten(c, 0.3));
      plot.dashed_polyline(to.all(m.path_m), figure::shade(c, 0.7), 2, 10.0, 6.0);
    }

    draw_run_marks(plot, to, plan);
    // Over the track, the hits and the planned waypoints, thin and dashed, so that where the track leaves it both
    // show.
    if (!plan.overlay && !plan.height_map && has_nominal_route(*plan.runs.front())) {
      plot.dashed_polyline(to.all(nominal_route(*plan.runs.front())), kNominalRoute, 2, 9.0, 6.0);
    }
    if (plan.fleet) {
      // Each vehicle's start ringed in its colour, under the goals: vehicles crossing or swapping places have
      // their goals on each other's starts, and a star shows the start between its arms.
      for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        if (!plan.runs[i]->track.empty()) plot.circle(to(plan.runs[i]->track.front().position_m), 12.0, plan_color(plan, i), 3.0);
      }
      for (const auto& s : plan.starts) figure::start_marker(plot, to(s));
      for (std::size_t from = 0, until = 0; from < plan.mission.size(); from = until) {
        while (until < plan.mission.size() && plan.mission_owner[until] == plan.mission_owner[from]) ++until;
        draw_mission(plot, layout.plot_px.width, to, plan, from, until);
      }
      // Each footprint's edge again over the markers, which would hide a small vehicle that ended at its goal.
      for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        const RunView& run = *plan.runs[i];
        if (!run.track.empty() && run.footprint_m.minCoeff() > 0.0) {
          draw_vehicle_footprint(plot, to, run.track.back(), run.footprint_m, plan_color(plan, i), false);
        }
      }
    } else {
      draw_mission(plot, layout.plot_px.width, to, plan, 0, plan.mission.size());
      for (const auto& s : plan.starts) figure::start_marker(plot, to(s));
    }
  }

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
}

Canvas draw_map_figure(const Scene& scene, const MapPlan& plan, const FigureLayout& layout, const std::string& title) {
  Canvas canvas(layout.image_px);
  draw_map_figure(canvas, scene, plan, layout, title);
  return canvas;
}

}  // namespace campo::figure
