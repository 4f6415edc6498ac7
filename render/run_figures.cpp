#include "render/run_figures.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "campo/json_reader.hpp"
#include "core/output_dir.hpp"
#include "planners/depth_reactive.hpp"
#include "render/snapshot.hpp"
#include "scene/scene_mesh.hpp"

namespace campo {

namespace {

// A rendered raster (the 3D snapshot) as a figure: PDF and SVG embed it.
figure::Canvas raster_figure(const cv::Mat& image) {
  figure::Canvas canvas(image.size());
  canvas.image(image, {0, 0, image.cols, image.rows});
  return canvas;
}

void append(std::vector<std::filesystem::path>& to, std::vector<std::filesystem::path> files) {
  for (auto& f : files) to.push_back(std::move(f));
}

std::string title_of(const RecordedRun& run, const std::string& what) {
  const auto& p = run.record.at("parameters");
  return run.scene.name + " - " + p.at("vehicle").at("type").get<std::string>() + " - " +
         p.at("planner").at("name").get<std::string>() + " - " + run.view.outcome + " - " + what;
}

std::string record_file(const RecordedRun& run) { return (run.dir / "run.json").string(); }

// A depth figure grey and colour-mapped: out_dir/depth_figures/<stem>_grey.png and _colour.png.
std::vector<std::filesystem::path> write_depth_pair(const cv::Mat& depth, const DepthOverlays& overlays,
                                                    const std::string& title, const std::filesystem::path& out_dir,
                                                    const std::string& stem, const FigureFormats& formats) {
  const auto dir = out_dir / "depth_figures";
  const OutputDirectory made(dir);  // removed again if no figure could be written into it
  std::vector<std::filesystem::path> written = draw_depth(depth, overlays, false, title + " (grey)")
                                                   .write(dir / (stem + "_grey.png"), formats);
  append(written, draw_depth(depth, overlays, true, title + " (colour)").write(dir / (stem + "_colour.png"), formats));
  return written;
}

// The angular grid of sensor `alias` as run.json's parameters.sensors recorded it.
DepthGrid recorded_grid(const RecordedRun& run, const std::string& alias) {
  for (const auto& s : run.record.at("parameters").at("sensors")) {
    if (s.value("alias", "") != alias) continue;
    const auto& resolution = s.at("resolution");
    const auto& fov = s.at("fov_deg");
    return {resolution.at(0).get<int>(), resolution.at(1).get<int>(), fov.at(0).get<double>(), fov.at(1).get<double>(),
            s.at("range_m").at(1).get<double>()};
  }
  throw InputError(record_file(run), "/parameters/sensors", "no sensor \"" + alias + "\", which replanning read");
}

cv::Point2d point2d(const nlohmann::json& j) { return {j.at(0).get<double>(), j.at(1).get<double>()}; }
Eigen::Vector2i vector2i(const nlohmann::json& j) { return {j.at(0).get<int>(), j.at(1).get<int>()}; }
cv::Point to_cv(const Eigen::Vector2i& p) { return {p.x(), p.y()}; }

// The overlays of one replanning step, recomputed as depth_reactive.cpp computes
// them. The 16-bit file rounds values by at most 1 / 131070, so the maps match
// the planner's except, rarely, at a pixel that close to a layer boundary or t.
DepthOverlays replan_overlays(const cv::Mat& depth, const nlohmann::json& replan, const DepthReactiveConfig& config,
                              const DepthGrid& grid) {
  DepthOverlays o;
  o.dilated = dilate_depth_map(depth, dilation_params(config, grid));
  const cv::Point2d projection = point2d(replan.at("pixel"));
  const cv::Point2d radius = point2d(replan.at("radius_px"));
  o.waypoint_projection = projection;
  o.safety_ellipse_px = {radius.x, radius.y};
  if (replan.contains("threshold")) {
    o.threshold = replan["threshold"].get<double>();
    o.thresholded = threshold_free(o.dilated, *o.threshold);
  }
  if (replan.contains("chosen_pixel")) {
    const Eigen::Vector2i chosen = vector2i(replan["chosen_pixel"]);
    const Eigen::Vector2i edge = vector2i(replan.at("edge_pixel"));
    o.chosen_pixel = to_cv(chosen);
    // TrovaWP's scan from the chosen pixel toward W', up to the obstacle edge;
    // an edge at the chosen pixel itself means the scan met none and ran on.
    for (const Eigen::Vector2i& q : pixel_segment(depth.size(), chosen, {projection.x, projection.y})) {
      o.scan_line.push_back(to_cv(q));
      if (q == edge && edge != chosen) break;
    }
    o.new_waypoint_pixel = to_cv(vector2i(replan.at("waypoint_pixel")));
  }
  return o;
}

// "two_barriers - replan 3 at 12.4 s - target invisible -> new waypoint".
std::string replan_title(const RecordedRun& run, const ReplanStep& step) {
  const nlohmann::json& details = step.decision.details;
  std::string action = details.value("action", "");
  std::replace(action.begin(), action.end(), '_', ' ');
  std::ostringstream title;
  title << run.scene.name << " - replan " << step.decision.index << " at " << std::fixed << std::setprecision(1) << step.time_s
        << " s - " << details.value("role", "") << " " << details.value("visibility", "") << " -> " << action;
  return title.str();
}

}  // namespace

namespace {

constexpr std::array<std::pair<FigureKind, std::string_view>, kFigureKinds.size()> kFigureKindNames{{
    {FigureKind::map, "map"},
    {FigureKind::side, "side"},
    {FigureKind::heightmap, "heightmap"},
    {FigureKind::depth, "depth"},
    {FigureKind::snapshot, "snapshot"},
    {FigureKind::overlay, "overlay"},
    {FigureKind::sequence, "sequence"},
    {FigureKind::video, "video"},
    {FigureKind::replay, "replay"},
}};

// The file of a figure of one run: named after its kind (map.png; figure::Canvas::write names the other formats).
std::filesystem::path figure_file(const std::filesystem::path& out_dir, FigureKind kind) {
  return out_dir / (std::string(to_string(kind)) + ".png");
}

}  // namespace

std::string_view to_string(FigureKind kind) {
  for (const auto& [value, name] : kFigureKindNames) {
    if (value == kind) return name;
  }
  return "?";
}

std::optional<FigureKind> figure_kind_from_string(std::string_view name) {
  for (const auto& [value, n] : kFigureKindNames) {
    if (n == name) return value;
  }
  return std::nullopt;
}

std::vector<std::string> figure_kind_names() {
  std::vector<std::string> names;
  for (const FigureKind kind : kFigureKinds) names.emplace_back(to_string(kind));
  return names;
}

std::vector<FigureKind> run_directory_figures(const RecordedRun& run) {
  std::vector<FigureKind> kinds{FigureKind::map, FigureKind::side};
  if (!run.view.height_map.empty()) kinds.push_back(FigureKind::heightmap);
  return kinds;
}

std::vector<std::filesystem::path> write_figure(const RecordedRun& run, FigureKind kind,
                                                const std::filesystem::path& out_dir, const FigureFormats& formats) {
  FigureStyle style;
  switch (kind) {
    case FigureKind::map:
      style.title = title_of(run, "map");
      return draw_map(run.scene, run.view, style).write(figure_file(out_dir, kind), formats);
    case FigureKind::side:
      style.title = title_of(run, "side view");
      return draw_side_view(run.scene, run.view, style).write(figure_file(out_dir, kind), formats);
    case FigureKind::heightmap:
      if (run.view.height_map.empty()) {
        throw InputError(record_file(run), "/events",
                         "no height map: only dstar_lite_3d with column mapping records one (octomap mapping keeps "
                         "what lies under an overhang, which a height map cannot show: see the side view)");
      }
      style.title = title_of(run, "reconstructed height map");
      return draw_height_map(run.scene, run.view, style).write(figure_file(out_dir, kind), formats);
    case FigureKind::snapshot: {
      std::vector<Eigen::Vector3d> path;
      for (const TrackPoint& p : run.view.track) path.push_back(p.position_m);
      const SceneMesh mesh = build_scene_mesh(run.scene);
      const SnapshotCamera camera = default_snapshot_camera(run.scene, path);
      std::optional<Eigen::Isometry3d> pose;
      if (!path.empty()) pose = Eigen::Isometry3d(Eigen::Translation3d(path.back()));
      const auto type =
          vehicle_type_from_string(run.record.at("parameters").at("vehicle").at("type").get<std::string>());
      return raster_figure(render_snapshot(run.scene, mesh, camera, path, pose, type.value_or(VehicleType::quadrotor)))
          .write(figure_file(out_dir, kind), formats);
    }
    case FigureKind::depth: {
      // Every recorded depth map (campo run --record-depth), grey and colour-mapped.
      std::vector<std::filesystem::path> frames, written;
      const auto depth_dir = run.dir / "depth";
      if (std::filesystem::is_directory(depth_dir)) {
        for (const auto& e : std::filesystem::directory_iterator(depth_dir)) {
          if (e.path().extension() == ".png") frames.push_back(e.path());
        }
      }
      std::sort(frames.begin(), frames.end());
      if (frames.empty()) {
        throw InputError(depth_dir.string(), "", "no recorded depth maps; run with --record-depth N");
      }
      for (const auto& frame : frames) {
        const std::string stem = frame.stem().string();
        append(written, write_depth_pair(read_depth_map(frame), {}, stem, out_dir, stem, formats));
      }
      return written;
    }
    case FigureKind::overlay:
    case FigureKind::sequence:
    case FigureKind::video:
    case FigureKind::replay:
      break;  // several runs, or a run over time: write_overlay, write_sequence, write_video, replay_html
  }
  throw std::invalid_argument("write_figure: " + std::string(to_string(kind)) + " is not a figure of one run");
}

std::vector<ReplanStep> find_replan_steps(const RecordedRun& run, const std::optional<std::vector<int>>& indices) {
  const std::string file = record_file(run);
  const std::string planner = run.record.value("/parameters/planner/name"_json_pointer, std::string());
  if (planner != "depth_reactive") {
    throw InputError(file, "/parameters/planner/name",
                     "expected \"depth_reactive\", whose replanning steps --step draws, got \"" + planner + "\"");
  }
  std::vector<ReplanStep> recorded;
  for (const PlannerEvent& event : run.events) {
    if (!event.decisions.replan) continue;
    const ReplanDecision& replan = *event.decisions.replan;
    recorded.push_back({event.time_s, replan, run.dir / "replans" / replan_depth_file(replan.index)});
  }
  std::vector<ReplanStep> steps;
  if (!indices) {
    if (recorded.empty()) throw InputError(file, "/events", "no replanning steps recorded");
    steps = recorded;
  }
  for (const int k : indices.value_or(std::vector<int>{})) {
    const auto it = std::find_if(recorded.begin(), recorded.end(), [k](const ReplanStep& s) { return s.decision.index == k; });
    if (it == recorded.end()) {
      const std::string held = recorded.empty() ? "none"
                                                : "steps " + std::to_string(recorded.front().decision.index) + " to " +
                                                      std::to_string(recorded.back().decision.index);
      throw InputError(file, "/events", "no replanning step " + std::to_string(k) + " (the run recorded " + held + ")");
    }
    steps.push_back(*it);
  }
  for (const ReplanStep& step : steps) {
    if (!std::filesystem::is_regular_file(step.depth_file)) {
      throw InputError(step.depth_file.string(), "",
                       "missing: expected the depth map replanning step " + std::to_string(step.decision.index) +
                           " read (was the run made with --no-replan-depth?)");
    }
  }
  return steps;
}

namespace {

// The planner parameters of a depth_reactive run, as recorded.
DepthReactiveConfig recorded_depth_reactive_config(const RecordedRun& run) {
  const std::string file = record_file(run);
  const auto params = "/parameters/planner/parameters"_json_pointer;
  if (!run.record.contains(params)) throw InputError(file, params.to_string(), "missing; expected the planner's parameters");
  return parse_depth_reactive_config({run.record.at(params), file, params.to_string()});
}

// The depth map replanning `step` read and the planner's overlays on it.
std::pair<cv::Mat, DepthOverlays> replan_depth(const RecordedRun& run, const DepthReactiveConfig& config,
                                               const ReplanStep& step) {
  const std::string file = record_file(run);
  try {
    if (!step.decision.sensor) {
      throw InputError(file, "/events", "replanning step " + std::to_string(step.decision.index) +
                                            " names no sensor; expected the one whose depth map it read");
    }
    const std::string& sensor = *step.decision.sensor;
    const DepthGrid grid = recorded_grid(run, sensor);
    cv::Mat depth = read_depth_map(step.depth_file);
    if (depth.cols != grid.cols || depth.rows != grid.rows) {
      throw InputError(step.depth_file.string(), "",
                       "expected a " + std::to_string(grid.cols) + " x " + std::to_string(grid.rows) +
                           " depth map, the resolution of sensor \"" + sensor + "\"");
    }
    DepthOverlays overlays = replan_overlays(depth, step.decision.details, config, grid);
    return {std::move(depth), std::move(overlays)};
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "/events", "malformed replanning step " + std::to_string(step.decision.index) + ": " + e.what());
  }
}

}  // namespace

std::vector<std::filesystem::path> write_replan_figures(const RecordedRun& run, const std::vector<ReplanStep>& steps,
                                                        const std::filesystem::path& out_dir,
                                                        const FigureFormats& formats) {
  const DepthReactiveConfig config = recorded_depth_reactive_config(run);
  std::vector<std::filesystem::path> written;
  for (const ReplanStep& step : steps) {
    const auto [depth, overlays] = replan_depth(run, config, step);
    const std::string stem = std::filesystem::path(replan_depth_file(step.decision.index)).stem().string();
    append(written, write_depth_pair(depth, overlays, replan_title(run, step), out_dir, stem, formats));
  }
  return written;
}

cv::Mat draw_replan_figure(const RecordedRun& run, const ReplanStep& step, bool colour) {
  const auto [depth, overlays] = replan_depth(run, recorded_depth_reactive_config(run), step);
  return draw_depth(depth, overlays, colour, replan_title(run, step)).raster();
}

namespace {

// A follow-the-gap decision of a rover_route run ("gap" event) and when it was taken.
struct TimedGap {
  double time_s = 0.0;
  GapDecision gap;
};

std::vector<TimedGap> gap_decisions(const RecordedRun& run) {
  std::vector<TimedGap> out;
  for (const PlannerEvent& event : run.events) {
    if (event.decisions.gap) out.push_back({event.time_s, *event.decisions.gap});
  }
  return out;
}

}  // namespace

std::vector<double> gap_switch_instants(const RecordedRun& run) {
  const std::vector<TimedGap> gaps = gap_decisions(run);
  const auto chosen =
      std::find_if(gaps.begin(), gaps.end(), [](const TimedGap& g) { return g.gap.chosen.has_value(); });
  if (chosen == gaps.end()) {
    throw InputError(record_file(run), "/events", "no follow-the-gap decision with a chosen gap (\"gap\" events)");
  }
  // Sides by the gap's centre: the heading is blended toward the goal and may cross the route.
  const bool left_first = chosen->gap.chosen->center_deg > 0.0;
  const auto other = std::find_if(chosen, gaps.end(), [&](const TimedGap& g) {
    return g.gap.chosen && (g.gap.chosen->center_deg > 0.0) != left_first;
  });
  if (other == gaps.end()) {
    throw InputError(record_file(run), "/events", "the chosen gap never changed sides; give the instants with --at");
  }
  // Back on the route: 2 s after the avoidance the switch belongs to ended (else the last gap decision).
  double end = gaps.back().time_s;
  for (const auto& [from, until] : run.view.avoiding_s) {
    if (from <= other->time_s && until >= other->time_s) end = until + 2.0;
  }
  if (!run.view.track.empty()) end = std::min(end, run.view.track.back().time_s);
  return {chosen->time_s, 0.5 * (chosen->time_s + other->time_s), other->time_s, end};
}

std::vector<std::filesystem::path> write_sequence(const RecordedRun& run, std::vector<double> times_s,
                                                  const std::filesystem::path& out_dir, const FigureFormats& formats) {
  if (times_s.empty()) times_s = gap_switch_instants(run);
  const std::vector<TimedGap> gaps = gap_decisions(run);
  std::vector<SequencePanel> panels;
  for (std::size_t i = 0; i < times_s.size(); ++i) {
    SequencePanel panel;
    panel.time_s = times_s[i];
    std::ostringstream caption;
    caption << "(" << static_cast<char>('a' + i % 26) << ") " << std::fixed << std::setprecision(1) << panel.time_s
            << " s";
    // The latest gap decision at or before the instant, if avoidance was on then.
    const GapDecision* latest = nullptr;
    for (const TimedGap& g : gaps) {
      if (g.time_s <= panel.time_s + 1e-9) latest = &g.gap;
    }
    const bool avoiding = std::any_of(run.view.avoiding_s.begin(), run.view.avoiding_s.end(), [&](const auto& a) {
      return a.first <= panel.time_s && panel.time_s < a.second;
    });
    if (latest && latest->chosen && avoiding) {
      const double rel = latest->chosen->heading_deg;
      caption << " - gap on the " << (latest->chosen->center_deg > 0.0 ? "left" : "right") << ", heading "
              << std::showpos << std::setprecision(0) << rel << std::noshowpos << " deg (arrow)";
      panel.heading_deg = latest->route_heading_deg + rel;
    } else {
      caption << " - following the route";
    }
    panel.caption = caption.str();
    panels.push_back(std::move(panel));
  }
  const Eigen::Vector2d footprint = vehicle_size_m(run).head<2>();
  FigureStyle style;
  style.max_size_px = 700;
  style.margin_m = 1.5;
  return draw_sequence(run.scene, run.view, panels, footprint, style).write(out_dir / "sequence.png", formats);
}

std::vector<std::filesystem::path> write_overlay(const std::vector<RecordedRun>& runs,
                                                 const std::filesystem::path& out_dir, const FigureFormats& formats) {
  std::vector<RunView> views;
  for (const auto& r : runs) views.push_back(r.view);
  FigureStyle style;
  style.title = runs.front().scene.name + " - " + std::to_string(runs.size()) + " runs";
  return draw_overlay(runs.front().scene, views, style).write(out_dir / "overlay.png", formats);
}

}  // namespace campo
