#include "render/run_video.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "campo/json_reader.hpp"
#include "core/image_io.hpp"
#include "render/scan_view.hpp"
#include "render/video_encoder.hpp"
#include "render/video_frame.hpp"
#include "render/depth_figure.hpp"
#include "render/run_figures.hpp"

namespace campo {

namespace {

std::string fixed(double value, int decimals, const char* unit) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f %s", decimals, value, unit);
  return text;
}

// The last of `items` (in time order) at or before t; nullptr when none is.
template <class T>
const T* latest(const std::vector<T>& items, double t) {
  const auto it = std::upper_bound(items.begin(), items.end(), t, [](double v, const T& x) { return v < x.time_s; });
  return it == items.begin() ? nullptr : &*std::prev(it);
}

// A heading mark the planner left and when.
struct TimedMark {
  double time_s;
  HeadingMark mark;
};

// The recorded depth maps of the vehicle's first sensor that has any, in time order.
std::pair<const SensorDef*, std::vector<RecordedDepthMap>> recorded_depths(const RecordedRun& run,
                                                                           const VehicleDef& vehicle) {
  const std::vector<RecordedDepthMap> all = recorded_depth_maps(run);
  for (const SensorDef& sensor : vehicle.sensors) {
    std::vector<RecordedDepthMap> own;
    std::copy_if(all.begin(), all.end(), std::back_inserter(own), [&](const auto& m) { return m.sensor == sensor.alias; });
    if (!own.empty()) return {&sensor, std::move(own)};
  }
  return {nullptr, {}};
}

// The recorded colour images of the vehicle's first camera that has any, in time order.
std::vector<RecordedDepthMap> recorded_camera_images(const RecordedRun& run, const VehicleDef& vehicle) {
  const std::vector<RecordedDepthMap> all = recorded_images(run);
  for (const RgbCameraDef& camera : vehicle.rgb_cameras) {
    std::vector<RecordedDepthMap> own;
    std::copy_if(all.begin(), all.end(), std::back_inserter(own), [&](const auto& m) { return m.sensor == camera.alias; });
    if (!own.empty()) return own;
  }
  return {};
}

// What the sensor panel shows at each instant, drawn once per recorded map or scan.
class SensorPanel {
 public:
  SensorPanel(const RecordedRun& run, const VehicleDef& vehicle, const Eigen::Vector3d& size_m)
      : run_(run), footprint_m_(size_m.head<2>()) {
    // The recorded depth maps are one vehicle's (campo run --vehicle): another's panel shows its decisions alone.
    const bool recorded = !run.several() || run.vehicles[run.chosen].alias == sensor_records_vehicle(run);
    if (!recorded) {
      none_ = "No sensor data of " + run.vehicles[run.chosen].alias + " recorded: the run recorded " +
              sensor_records_vehicle(run) + "'s (campo run --vehicle)";
    }
    if (recorded && run.planner && run.planner->replan_overlays && std::filesystem::is_directory(run.dir / "replans")) {
      replans_ = find_replan_steps(run, std::nullopt);
      std::sort(replans_.begin(), replans_.end(), [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
    }
    if (recorded) std::tie(sensor_, depths_) = recorded_depths(run, vehicle);
    if (recorded) images_ = recorded_camera_images(run, vehicle);
    if (run.planner && run.planner->heading) {
      for (const PlannerEvent& e : run.events) {
        if (auto mark = run.planner->heading(e.decisions)) marks_.push_back({e.time_s, std::move(*mark)});
      }
    }
  }

  // The panel at `time_s` and its caption; `at` is the vehicle's sample then.
  std::pair<cv::Mat, std::string> at(double time_s, const TrackPoint& at, bool avoiding) {
    if (const ReplanStep* step = latest(replans_, time_s)) {
      if (shown_ != step) {
        image_ = draw_replan_figure(run_, *step, true);
        shown_ = step;
      }
      return {image_, "What the planner saw: replanning " + std::to_string(step->decision.index) + " at " +
                          fixed(step->time_s, 1, "s")};
    }
    // A recorded colour image (campo run --record-images) before the depth maps: what a person would see.
    if (const RecordedDepthMap* image = latest(images_, time_s)) {
      if (shown_ != image) {
        image_ = read_png_file(image->file);
        shown_ = image;
      }
      return {image_, "Camera " + image->sensor + " at " + fixed(image->time_s, 1, "s")};
    }
    const bool planar = sensor_ && sensor_->range.rows <= 1;
    const RecordedDepthMap* scan = latest(depths_, time_s);
    if (scan && !planar) {
      if (shown_ != scan) {
        image_ = draw_depth(read_depth_map(scan->file), {}, true, sensor_->alias + " depth map").raster();
        shown_ = scan;
      }
      return {image_, "Depth map of " + sensor_->alias + " at " + fixed(scan->time_s, 1, "s")};
    }
    if (!planar && marks_.empty()) {
      return {cv::Mat(), none_};
    }
    // A planar scan around the vehicle, redrawn each frame (the vehicle turns under it), read once.
    ScanView view;
    view.footprint_m = footprint_m_;
    view.range_m = sensor_ ? std::min(sensor_->range.max_range_m, 8.0) : 5.0;
    std::string caption = "Planar scan, vehicle frame, forward up";
    if (scan) {
      if (shown_ != scan) {
        points_.clear();
        for (const Eigen::Vector3d& p : depth_map_returns(read_depth_map(scan->file), *sensor_,
                                                          Eigen::Isometry3d::Identity(), scan->file)) {
          points_.push_back(p.head<2>());
        }
        shown_ = scan;
      }
      view.points_m = points_;
      caption = sensor_->alias + " scan at " + fixed(scan->time_s, 1, "s") + ", vehicle frame, forward up";
    }
    const TimedMark* timed = latest(marks_, time_s);
    const HeadingMark* mark = timed ? &timed->mark : nullptr;
    if (mark) {
      view.route_deg = mark->reference_deg - at.yaw_deg;
      if (mark->nearest_m) view.nearest_m = *mark->nearest_m;
      if (mark->heading_deg && avoiding) view.gap_heading_deg = mark->reference_deg + *mark->heading_deg - at.yaw_deg;
    }
    view.status = avoiding ? (mark && !mark->status.empty() ? "avoiding: " + mark->status : std::string("avoiding"))
                           : "following the route";
    return {draw_scan_view(view).raster(), caption};
  }

 private:
  const RecordedRun& run_;
  std::string none_ = "No sensor data recorded: campo run --record-depth 1 saves every scan";  // the caption then
  Eigen::Vector2d footprint_m_;
  std::vector<ReplanStep> replans_;
  const SensorDef* sensor_ = nullptr;
  std::vector<RecordedDepthMap> depths_;
  std::vector<RecordedDepthMap> images_;  // the first camera's colour images
  std::vector<TimedMark> marks_;
  const void* shown_ = nullptr;          // the replanning or recorded map image_ or points_ hold
  cv::Mat image_;
  std::vector<Eigen::Vector2d> points_;  // a planar scan's returns, vehicle frame
};

// The measured values of the strip, from trajectory.csv's row at a time.
class StripValues {
 public:
  explicit StripValues(const RecordedRun& run)
      : table_(read_trajectory_table(run.dir / run.vehicles.at(run.chosen).trajectory_file)) {
    time_ = &table_.column("time_s");
    const auto optional = [&](const char* name) -> const std::vector<double>* {
      const auto& h = table_.header;
      return std::find(h.begin(), h.end(), name) != h.end() ? &table_.column(name) : nullptr;
    };
    vx_ = &table_.column("vx_mps");
    vy_ = &table_.column("vy_mps");
    vz_ = &table_.column("vz_mps");
    z_ = &table_.column("z_m");
    agl_ = optional("height_above_ground_m");
    clearance_ = optional("clearance_m");
    const auto& x = table_.column("x_m");
    const auto& y = table_.column("y_m");
    distance_.assign(time_->size(), 0.0);
    for (std::size_t i = 1; i < time_->size(); ++i) {
      distance_[i] = distance_[i - 1] + std::hypot(x[i] - x[i - 1], y[i] - y[i - 1], (*z_)[i] - (*z_)[i - 1]);
    }
  }

  std::vector<std::pair<std::string, std::string>> at(double time_s) const {
    const auto it = std::upper_bound(time_->begin(), time_->end(), time_s);
    const std::size_t i = it == time_->begin() ? 0 : static_cast<std::size_t>(it - time_->begin() - 1);
    std::vector<std::pair<std::string, std::string>> values{
        {"speed", fixed(std::hypot((*vx_)[i], (*vy_)[i], (*vz_)[i]), 2, "m/s")},
        {"altitude", fixed((*z_)[i], 2, "m")}};
    if (agl_) values.emplace_back("above ground", fixed((*agl_)[i], 2, "m"));
    if (clearance_ && std::isfinite((*clearance_)[i])) values.emplace_back("clearance", fixed((*clearance_)[i], 2, "m"));
    values.emplace_back("distance", fixed(distance_[i], 1, "m"));
    return values;
  }

 private:
  TrajectoryTable table_;
  const std::vector<double>* time_ = nullptr;
  const std::vector<double>* vx_ = nullptr;
  const std::vector<double>* vy_ = nullptr;
  const std::vector<double>* vz_ = nullptr;
  const std::vector<double>* z_ = nullptr;
  const std::vector<double>* agl_ = nullptr;
  const std::vector<double>* clearance_ = nullptr;
  std::vector<double> distance_;
};

// The planner's state at the end of `so_far`, one line.
std::string planner_state(const RecordedRun& run, const RunView& so_far, double time_s, double duration_s,
                          bool avoiding) {
  if (time_s >= duration_s) {  // the run's end: with several vehicles, the fleet's outcome
    const std::string reason = run.record.value("/metrics/reason"_json_pointer, std::string());
    const std::string outcome =
        run.several() ? run.record.value("/metrics/outcome"_json_pointer, std::string()) : run.view.outcome;
    return "end: " + outcome + (reason.empty() ? "" : " (" + reason + ")");
  }
  std::string state = avoiding ? "avoiding an obstacle" : "";
  for (const PlannerEvent& e : run.events) {
    if (e.time_s > time_s) break;
    if (e.decisions.replan) {
      const std::string action =
          run.planner && run.planner->replan_action ? run.planner->replan_action(*e.decisions.replan) : "";
      if (!avoiding) state = "replanning " + std::to_string(e.decisions.replan->index) + (action.empty() ? "" : ": " + action);
    }
  }
  const std::size_t reached = so_far.reached.size();
  if (!so_far.mission.empty()) {
    state += (state.empty() ? "" : "  |  ") + std::string("waypoints reached ") + std::to_string(reached) + "/" +
             std::to_string(so_far.mission.size());
  }
  return state;
}

}  // namespace

void check_video_runs(std::size_t runs, const VideoOptions& options) {
  if (runs > options.max_runs) {
    throw InputError("command line", "runs",
                     "at most " + std::to_string(options.max_runs) + " run directories for --kind video, got " +
                         std::to_string(runs) + " (each run's files are held while the videos are made)");
  }
}

void write_video(const RecordedRun& recorded, const VideoOptions& options, const std::filesystem::path& out,
                 const std::function<void(std::size_t, std::size_t)>& progress) {
  // Every frame draws the track so far: a longer track is thinned evenly (the last sample kept),
  // so the work is frames x max_track_samples at most.
  std::optional<RecordedRun> thinned;
  const auto thin = [&](std::vector<TrackPoint>& track) {
    const std::size_t n = track.size(), keep = options.max_track_samples;
    std::vector<TrackPoint> kept;
    for (std::size_t k = 0; k < keep; ++k) kept.push_back(track[k * (n - 1) / (keep - 1)]);
    track = std::move(kept);
  };
  const auto too_long = [&](const RunView& view) { return view.track.size() > options.max_track_samples; };
  if (options.max_track_samples >= 2 &&
      (too_long(recorded.view) ||
       std::any_of(recorded.vehicles.begin(), recorded.vehicles.end(), [&](const auto& v) { return too_long(v.view); }))) {
    thinned = recorded;
    if (too_long(thinned->view)) thin(thinned->view.track);
    for (RecordedVehicle& v : thinned->vehicles) {
      if (too_long(v.view)) thin(v.view.track);
    }
  }
  const RecordedRun& run = thinned ? *thinned : recorded;
  const std::string trajectory = (run.dir / run.vehicles.at(run.chosen).trajectory_file).string();
  const std::optional<VideoFormat> format = video_format_of(out);
  if (!format) throw InputError("command line", "--out", "expected a video file ending in .mp4 or .gif, got " + out.string());
  for (const RecordedVehicle& v : run.vehicles) {
    if (v.view.track.empty()) throw InputError((run.dir / v.trajectory_file).string(), "", "no samples; expected a track");
  }
  if (run.view.track.empty()) throw InputError(trajectory, "", "no samples; expected a track");
  const VehicleDef& vehicle = recorded_vehicle(run);
  // Until the last vehicle's end.
  double duration_s = run.view.track.back().time_s;
  for (const RecordedVehicle& v : run.vehicles) duration_s = std::max(duration_s, v.view.track.back().time_s);
  if (!std::isfinite(duration_s) || duration_s < 0.0) {
    throw InputError(trajectory, "",
                     "expected a last time_s >= 0, got " + std::to_string(duration_s));
  }
  const double step_s = options.speed / options.fps;
  // Frames up to the end, the last one at the end itself; counted as doubles,
  // which neither wrap nor overflow, and checked before they become counts.
  double moving_frames = std::floor(duration_s / step_s + 1e-9) + 1.0;
  if ((moving_frames - 1.0) * step_s < duration_s) moving_frames += 1.0;
  const double held_frames = std::round(options.fps);  // the end, held a second
  if (moving_frames + held_frames > static_cast<double>(options.max_frames)) {
    char duration[32], frames[32];
    std::snprintf(duration, sizeof duration, "%.6g s", duration_s);
    std::snprintf(frames, sizeof frames, "%.15g", moving_frames + held_frames);
    throw InputError("command line", "--speed",
                     std::string("a ") + duration + " run at this speed and frame rate takes " + frames +
                         " frames, more than " + std::to_string(options.max_frames) + "; raise --speed or lower --fps");
  }
  const std::size_t moving = static_cast<std::size_t>(moving_frames);
  const std::size_t total = moving + static_cast<std::size_t>(held_frames);
  if (*format == VideoFormat::gif && total > options.max_gif_frames) {
    throw InputError("command line", "--out",
                     "a GIF of at most " + std::to_string(options.max_gif_frames) + " frames, got " +
                         std::to_string(total) + "; raise --speed, lower --fps or write an .mp4");
  }
  const Eigen::Vector3d size_m = vehicle_size_m(run);
  // With several vehicles, every one on the map in its colour; the sensor panel and the strip the chosen one's.
  std::vector<RunView> whole;
  for (const RecordedVehicle& v : run.vehicles) {
    whole.push_back(v.view);
    whole.back().footprint_m = vehicle_size_m(v).head<2>();
  }
  std::optional<VideoFrames> single, fleet;
  if (run.several()) {
    const std::string outcome = run.record.value("/metrics/outcome"_json_pointer, std::string());
    fleet.emplace(run.scene, whole, options.frame_px,
                  run.view.label + " - " + std::to_string(whole.size()) + " vehicles" + (outcome.empty() ? "" : " - " + outcome));
  }
  else single.emplace(run.scene, run.view, size_m, options.frame_px);
  SensorPanel sensor(run, vehicle, size_m);
  const StripValues values(run);
  VideoEncoder encoder(out, *format, options.frame_px, options.fps);
  cv::Mat frame;
  for (std::size_t k = 0; k < total; ++k) {
    if (k >= moving) {  // the end, held: the same frame again
      encoder.add(frame);
      if (progress) progress(k + 1, total);
      continue;
    }
    const double t = std::min(static_cast<double>(k) * step_s, duration_s);
    const RunView so_far = run_view_at(run, t);
    const double last_s = so_far.track.back().time_s;
    const bool avoiding = !so_far.avoiding_s.empty() && so_far.avoiding_s.back().second >= last_s &&
                          so_far.avoiding_s.back().first <= last_s;
    auto [panel, caption] = sensor.at(t, so_far.track.back(), avoiding);
    VideoStrip strip;
    strip.time_s = t;
    strip.duration_s = duration_s;
    strip.values = values.at(t);
    strip.state = planner_state(run, so_far, t, duration_s, avoiding);
    if (fleet) {
      const std::string& alias = run.vehicles[run.chosen].alias;
      caption = alias + ": " + caption;
      if (t < duration_s) strip.state = alias + ": " + strip.state;
      std::vector<RunView> now;
      for (std::size_t i = 0; i < run.vehicles.size(); ++i) {
        now.push_back(run_view_at(run, i, t));
        now.back().footprint_m = whole[i].footprint_m;
      }
      frame = fleet->draw(now, t, panel, caption, strip);
    } else {
      frame = single->draw(so_far, t, panel, caption, strip);
    }
    encoder.add(frame);
    if (progress) progress(k + 1, total);
  }
  encoder.finish();
}

}  // namespace campo
