#include "render/run_figures.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "campo/json_reader.hpp"
#include "core/output_dir.hpp"
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
  if (run.several()) {  // the run as a whole: its vehicles and the fleet's outcome
    return run.scene.name + " - " + std::to_string(run.vehicles.size()) + " vehicles - " +
           run.record.value("/metrics/outcome"_json_pointer, std::string()) + " - " + what;
  }
  const auto& p = run.parameters();
  return run.scene.name + " - " + p.at("vehicle").at("type").get<std::string>() + " - " +
         p.at("planner").at("name").get<std::string>() + " - " + run.view.outcome + " - " + what;
}

// Where the chosen vehicle's parameters are in run.json, for messages.
std::string parameters_pointer(const RecordedRun& run) {
  return run.several() ? "/vehicles/" + std::to_string(run.chosen) + "/parameters" : "/parameters";
}

// Every vehicle's view, in scene order, each with its footprint (length and width) for the map.
std::vector<RunView> fleet_views(const RecordedRun& run) {
  std::vector<RunView> views;
  for (const RecordedVehicle& v : run.vehicles) {
    views.push_back(v.view);
    views.back().footprint_m = vehicle_size_m(v).head<2>();
  }
  return views;
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
RecordedImage recorded_grid(const RecordedRun& run, const std::string& alias) {
  for (const auto& s : run.parameters().at("sensors")) {
    if (s.value("alias", "") != alias) continue;
    const auto& resolution = s.at("resolution");
    const auto& fov = s.at("fov_deg");
    return {resolution.at(0).get<int>(), resolution.at(1).get<int>(), fov.at(0).get<double>(), fov.at(1).get<double>(),
            s.at("range_m").at(1).get<double>()};
  }
  throw InputError(record_file(run), parameters_pointer(run) + "/sensors", "no sensor \"" + alias + "\", which replanning read");
}

// The planner's overlays of one replanning step as the depth figure draws them.
DepthOverlays depth_overlays(const ImageOverlays& o, const cv::Size& size) {
  DepthOverlays d;
  if (!o.processed.empty()) d.dilated = cv::Mat(size, CV_32F, const_cast<float*>(o.processed.data())).clone();
  if (!o.mask.empty()) d.thresholded = cv::Mat(size, CV_8U, const_cast<std::uint8_t*>(o.mask.data())).clone();
  d.threshold = o.mask_threshold;
  if (o.chosen_px) d.chosen_pixel = cv::Point(o.chosen_px->x(), o.chosen_px->y());
  for (const Eigen::Vector2i& p : o.polyline_px) d.scan_line.emplace_back(p.x(), p.y());
  if (o.target_px) d.waypoint_projection = cv::Point2d(o.target_px->x(), o.target_px->y());
  d.safety_ellipse_px = {o.ellipse_px.x(), o.ellipse_px.y()};
  if (o.placed_px) d.new_waypoint_pixel = cv::Point(o.placed_px->x(), o.placed_px->y());
  return d;
}

// "two_barriers - replan 3 at 12.4 s - target invisible -> new waypoint".
std::string replan_title(const RecordedRun& run, const ReplanStep& step) {
  std::ostringstream title;
  title << run.scene.name << " - replan " << step.decision.index << " at " << std::fixed << std::setprecision(1) << step.time_s
        << " s - " << (run.planner && run.planner->replan_caption ? run.planner->replan_caption(step.decision) : "");
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
      if (run.several()) return draw_fleet_map(run.scene, fleet_views(run), style).write(figure_file(out_dir, kind), formats);
      return draw_map(run.scene, run.view, style).write(figure_file(out_dir, kind), formats);
    case FigureKind::side:
      style.title = title_of(run, "side view");
      if (run.several()) {
        return draw_fleet_side_view(run.scene, fleet_views(run), style).write(figure_file(out_dir, kind), formats);
      }
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
      if (run.several()) {  // every vehicle in its map colour, framed all together
        std::vector<SnapshotVehicle> vehicles;
        std::vector<Eigen::Vector3d> all;
        for (std::size_t i = 0; i < run.vehicles.size(); ++i) {
          const RecordedVehicle& v = run.vehicles[i];
          SnapshotVehicle s;
          for (const TrackPoint& p : v.view.track) s.trajectory_m.push_back(p.position_m);
          if (!s.trajectory_m.empty()) s.pose = Eigen::Isometry3d(Eigen::Translation3d(s.trajectory_m.back()));
          s.type = vehicle_type_from_string(v.parameters.value("/vehicle/type"_json_pointer, std::string()))
                       .value_or(VehicleType::quadrotor);
          const cv::Scalar c = vehicle_color(i);
          s.color = Color{c[2] / 255.0, c[1] / 255.0, c[0] / 255.0};
          all.insert(all.end(), s.trajectory_m.begin(), s.trajectory_m.end());
          vehicles.push_back(std::move(s));
        }
        // Framed around every track, seen from behind the chosen vehicle's way.
        SnapshotCamera camera = default_snapshot_camera(run.scene, vehicles[run.chosen].trajectory_m);
        const SnapshotCamera around = default_snapshot_camera(run.scene, all);
        const Eigen::Vector3d back = (camera.eye_m - camera.target_m).normalized();
        camera.target_m = around.target_m;
        camera.eye_m = around.target_m + (around.eye_m - around.target_m).norm() * back;
        return raster_figure(render_snapshot(run.scene, build_scene_mesh(run.scene), camera, vehicles))
            .write(figure_file(out_dir, kind), formats);
      }
      std::vector<Eigen::Vector3d> path;
      for (const TrackPoint& p : run.view.track) path.push_back(p.position_m);
      const SceneMesh mesh = build_scene_mesh(run.scene);
      const SnapshotCamera camera = default_snapshot_camera(run.scene, path);
      std::optional<Eigen::Isometry3d> pose;
      if (!path.empty()) pose = Eigen::Isometry3d(Eigen::Translation3d(path.back()));
      const auto type = vehicle_type_from_string(run.parameters().at("vehicle").at("type").get<std::string>());
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
  const std::string planner = run.parameters().value("/planner/name"_json_pointer, std::string());
  if (!run.planner || !run.planner->replan_overlays) {
    throw InputError(file, parameters_pointer(run) + "/planner/name",
                     "expected \"depth_reactive\", whose replanning steps --step draws, got \"" + planner + "\"");
  }
  // replans/ holds the depth maps of one vehicle's replanning steps: those of another are not there.
  const std::string recorded_alias = sensor_records_vehicle(run);
  if (run.several() && run.vehicles[run.chosen].alias != recorded_alias) {
    throw InputError("command line", "--vehicle",
                     "the run recorded the replanning depth maps of vehicle \"" + recorded_alias + "\", not of \"" +
                         run.vehicles[run.chosen].alias + "\" (campo run --vehicle chooses whose)");
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

// The depth map replanning `step` read and the planner's overlays on it.
std::pair<cv::Mat, DepthOverlays> replan_depth(const RecordedRun& run, const ReplanStep& step) {
  const std::string file = record_file(run);
  try {
    if (!step.decision.sensor) {
      throw InputError(file, "/events", "replanning step " + std::to_string(step.decision.index) +
                                            " names no sensor; expected the one whose depth map it read");
    }
    const std::string& sensor = *step.decision.sensor;
    const RecordedImage grid = recorded_grid(run, sensor);
    cv::Mat depth = read_depth_map(step.depth_file);
    if (depth.cols != grid.cols || depth.rows != grid.rows) {
      throw InputError(step.depth_file.string(), "",
                       "expected a " + std::to_string(grid.cols) + " x " + std::to_string(grid.rows) +
                           " depth map, the resolution of sensor \"" + sensor + "\"");
    }
    RecordedImage image = grid;
    image.values.assign(depth.ptr<float>(), depth.ptr<float>() + depth.total());
    const auto params = "/planner/parameters"_json_pointer;
    const std::string params_at = parameters_pointer(run) + params.to_string();
    if (!run.parameters().contains(params)) throw InputError(file, params_at, "missing; expected the planner's parameters");
    DepthOverlays overlays = depth_overlays(
        run.planner->replan_overlays(step.decision, image, run.parameters().at(params), file, params_at), depth.size());
    return {std::move(depth), std::move(overlays)};
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "/events", "malformed replanning step " + std::to_string(step.decision.index) + ": " + e.what());
  }
}

}  // namespace

std::vector<std::filesystem::path> write_replan_figures(const RecordedRun& run, const std::vector<ReplanStep>& steps,
                                                        const std::filesystem::path& out_dir,
                                                        const FigureFormats& formats) {
  std::vector<std::filesystem::path> written;
  for (const ReplanStep& step : steps) {
    const auto [depth, overlays] = replan_depth(run, step);
    const std::string stem = std::filesystem::path(replan_depth_file(step.decision.index)).stem().string();
    append(written, write_depth_pair(depth, overlays, replan_title(run, step), out_dir, stem, formats));
  }
  return written;
}

cv::Mat draw_replan_figure(const RecordedRun& run, const ReplanStep& step, bool colour) {
  const auto [depth, overlays] = replan_depth(run, step);
  return draw_depth(depth, overlays, colour, replan_title(run, step)).raster();
}

namespace {

// A heading mark the planner left (a rover_route run's follow-the-gap choices) and when.
struct TimedHeadingMark {
  double time_s = 0.0;
  HeadingMark mark;
};

std::vector<TimedHeadingMark> heading_marks(const RecordedRun& run) {
  std::vector<TimedHeadingMark> out;
  if (!run.planner || !run.planner->heading) return out;
  for (const PlannerEvent& event : run.events) {
    if (auto mark = run.planner->heading(event.decisions)) out.push_back({event.time_s, std::move(*mark)});
  }
  return out;
}

}  // namespace

std::vector<double> gap_switch_instants(const RecordedRun& run) {
  const std::vector<TimedHeadingMark> marks = heading_marks(run);
  const auto chosen =
      std::find_if(marks.begin(), marks.end(), [](const TimedHeadingMark& m) { return !m.mark.side.empty(); });
  if (chosen == marks.end()) {
    throw InputError(record_file(run), "/events", "no decision on a side (e.g. a follow-the-gap decision with a chosen gap)");
  }
  const auto other = std::find_if(chosen, marks.end(), [&](const TimedHeadingMark& m) {
    return !m.mark.side.empty() && m.mark.side != chosen->mark.side;
  });
  if (other == marks.end()) {
    throw InputError(record_file(run), "/events", "the chosen gap never changed sides; give the instants with --at");
  }
  // Back on the route: 2 s after the avoidance the switch belongs to ended (else the last mark).
  double end = marks.back().time_s;
  for (const auto& [from, until] : run.view.avoiding_s) {
    if (from <= other->time_s && until >= other->time_s) end = until + 2.0;
  }
  if (!run.view.track.empty()) end = std::min(end, run.view.track.back().time_s);
  return {chosen->time_s, 0.5 * (chosen->time_s + other->time_s), other->time_s, end};
}

std::vector<std::filesystem::path> write_sequence(const RecordedRun& run, std::vector<double> times_s,
                                                  const std::filesystem::path& out_dir, const FigureFormats& formats) {
  if (times_s.empty()) times_s = gap_switch_instants(run);
  const std::vector<TimedHeadingMark> marks = heading_marks(run);
  std::vector<SequencePanel> panels;
  for (std::size_t i = 0; i < times_s.size(); ++i) {
    SequencePanel panel;
    panel.time_s = times_s[i];
    std::ostringstream caption;
    caption << "(" << static_cast<char>('a' + i % 26) << ") " << std::fixed << std::setprecision(1) << panel.time_s
            << " s";
    // The latest mark at or before the instant, if avoidance was on then.
    const HeadingMark* latest = nullptr;
    for (const TimedHeadingMark& m : marks) {
      if (m.time_s <= panel.time_s + 1e-9) latest = &m.mark;
    }
    const bool avoiding = std::any_of(run.view.avoiding_s.begin(), run.view.avoiding_s.end(), [&](const auto& a) {
      return a.first <= panel.time_s && panel.time_s < a.second;
    });
    if (latest && latest->heading_deg && avoiding) {
      caption << " - " << latest->caption;
      panel.heading_deg = latest->reference_deg + *latest->heading_deg;
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
