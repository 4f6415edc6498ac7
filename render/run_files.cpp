#include "render/run_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <tuple>

#include "campo/json_reader.hpp"
#include "core/image_io.hpp"
#include "campo/scene_loader.hpp"
#include "run/event_log.hpp"
#include "sensors/lidar.hpp"

namespace campo {

namespace {

Eigen::Vector3d vector3(const nlohmann::json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

// trajectory.csv: time, position and velocity columns by name.
std::vector<TrackPoint> read_track(const std::filesystem::path& path) {
  const TrajectoryTable table = read_trajectory_table(path);
  const std::vector<double>& t = table.column("time_s");
  const std::vector<double>&x = table.column("x_m"), &y = table.column("y_m"), &z = table.column("z_m");
  const std::vector<double>&vx = table.column("vx_mps"), &vy = table.column("vy_mps"), &vz = table.column("vz_mps");
  // Optional: older files lack it.
  const auto yaw_at = std::find(table.header.begin(), table.header.end(), "yaw_deg");
  const std::vector<double>* yaw = yaw_at == table.header.end() ? nullptr : &table.columns[yaw_at - table.header.begin()];
  std::vector<TrackPoint> track(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    track[i].time_s = t[i];
    track[i].position_m = {x[i], y[i], z[i]};
    track[i].speed_mps = Eigen::Vector3d(vx[i], vy[i], vz[i]).norm();
    if (yaw) track[i].yaw_deg = (*yaw)[i];
  }
  return track;
}

// The planner's own decisions of every event checked against its declarations: a key it does not
// declare, or a value not of its declared type, is an InputError (the notes of bound_decisions aside).
void check_own_decisions(const PlannerRecord& planner, const std::vector<PlannerEvent>& events,
                         const std::string& record_file) {
  for (std::size_t i = 0; i < events.size(); ++i) {
    const std::string at = "/events/" + std::to_string(i) + "/decisions";
    nlohmann::json own = events[i].decisions.own;
    for (const char* note : {"thinned", "omitted"}) own.erase(note);
    planner.decisions.check(own, record_file, at);
    if (events[i].decisions.replan) planner.replan.check(events[i].decisions.replan->details, record_file, at + "/replan");
  }
}

// The view's planner decisions (docs/running.md) from the events up to `until_s`: reached mission
// waypoints, intermediate waypoints set or dropped, a planned path, obstacle avoidance switched
// on and off, the mapping planners' hits and height map. An avoidance still on at the end lasts
// to the view's last track sample.
void add_decisions(RunView& v, const std::vector<PlannerEvent>& events, const PlannerRecord* planner, double until_s,
                   const std::string& record_file) {
  CellsOverlay cells;
  bool avoiding = false;
  double avoiding_since = 0.0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const PlannerEvent& event = events[i];
    if (event.time_s > until_s) break;  // events are in time order
    const Decisions& typed = event.decisions;
    if (typed.avoiding) {
      if (*typed.avoiding && !avoiding) avoiding_since = event.time_s;
      if (!*typed.avoiding && avoiding) v.avoiding_s.emplace_back(avoiding_since, event.time_s);
      avoiding = *typed.avoiding;
    }
    v.reached.insert(v.reached.end(), typed.reached_waypoints.begin(), typed.reached_waypoints.end());
    if (typed.planned_waypoint) v.planned.push_back(*typed.planned_waypoint);
    if (typed.discarded_waypoint) v.discarded.push_back(*typed.discarded_waypoint);
    if (typed.planned_path) v.planned_path = *typed.planned_path;
    // The mapping planners' own decisions (docs/planners.md, dstar_lite_3d).
    v.sensor_hits.insert(v.sensor_hits.end(), typed.lidar_hits.begin(), typed.lidar_hits.end());
    // The planner's own overlays (docs/planners.md, dstar_lite_3d's height map).
    if (planner && planner->cells) {
      try {
        planner->cells(typed, cells);
      } catch (const InputError& e) {
        throw InputError(record_file, "/events/" + std::to_string(i) + e.pointer(), e.message());
      }
    }
  }
  if (!cells.empty()) {
    v.height_map = {.origin_m = cells.origin_m, .cell_size_m = cells.cell_size_m, .columns = cells.columns,
                    .rows = cells.rows, .top_m = std::move(cells.values)};
  }
  if (avoiding) {  // still on at the end: up to the last sample
    v.avoiding_s.emplace_back(avoiding_since, v.track.empty() ? avoiding_since
                                                              : std::max(avoiding_since, v.track.back().time_s));
  }
}

}  // namespace

const std::vector<double>& TrajectoryTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return columns[i];
  }
  throw InputError(file, "", "missing column \"" + name + "\"");
}

TrajectoryTable read_trajectory_table(const std::filesystem::path& path) {
  const std::string text = read_text_file(path, {256u << 20, 32});
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw InputError(path.string(), "", "empty file; expected a CSV header");
  TrajectoryTable table;
  table.file = path.string();
  for (std::stringstream s(line); std::getline(s, line, ',');) table.header.push_back(line);
  table.columns.resize(table.header.size());
  // The recorded times: finite, from 0, in order (what readers of the track search by).
  const auto time_at = std::find(table.header.begin(), table.header.end(), "time_s");
  const std::size_t time_field = static_cast<std::size_t>(time_at - table.header.begin());
  double previous_s = 0.0;
  for (int row = 2; std::getline(in, line); ++row) {
    std::size_t start = 0, field = 0;
    while (start <= line.size() && field < table.header.size()) {
      const std::size_t end = std::min(line.find(',', start), line.size());
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(line.data() + start, line.data() + end, v);
      if (field == time_field) {
        const bool number = ec == std::errc() && ptr == line.data() + end && std::isfinite(v);
        if (!number || v < previous_s) {
          const std::string text = line.substr(start, std::min<std::size_t>(end - start, 40));
          throw InputError(path.string(), "", "line " + std::to_string(row) + ": expected a time_s in seconds, " +
                                                  (row == 2 ? std::string("a finite number >= 0")
                                                            : "a finite number >= the previous line's " +
                                                                  std::to_string(previous_s)) +
                                                  ", got \"" + text + (end - start > 40 ? "...\"" : "\""));
        }
        previous_s = v;
      }
      table.columns[field++].push_back(ec == std::errc() ? v : 0.0);
      start = end + 1;
    }
    if (field < table.header.size()) {
      throw InputError(path.string(), "", "line " + std::to_string(row) + ": expected " +
                                              std::to_string(table.header.size()) + " fields");
    }
  }
  return table;
}

namespace {

// A file name run.json gives for a file beside it: only a file there, a record names no other place to read.
std::filesystem::path file_beside(const std::filesystem::path& dir, const std::string& name, const std::string& pointer) {
  const std::filesystem::path file = name;
  if (file.has_parent_path() || file.empty() || file == "." || file == "..") {
    throw InputError((dir / "run.json").string(), pointer, "expected a file name, got " + file.string());
  }
  return dir / file;
}

// The events of the object holding an "event_log" (a vehicle's entry, or run.json itself), or its "events" array
// (runs recorded before events.jsonl); none when it has neither.
std::vector<PlannerEvent> read_events(const std::filesystem::path& dir, const nlohmann::json& holder,
                                      const std::string& pointer) {
  const std::string record_file = (dir / "run.json").string();
  try {
    if (const auto log = holder.find("event_log"); log != holder.end()) {
      return read_events_jsonl(file_beside(dir, log->at("file").get<std::string>(), pointer + "/event_log/file"));
    }
    if (const auto events = holder.find("events"); events != holder.end()) {
      return events_from_json(*events, record_file, pointer + "/events");
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(record_file, pointer + "/event_log", std::string("malformed run record: ") + e.what());
  }
  return {};
}

// A vehicle's view: its track, mission, planner decisions and collisions.
RunView vehicle_view(const std::filesystem::path& dir, const RecordedVehicle& vehicle, const std::string& pointer) {
  const std::string record_file = (dir / "run.json").string();
  RunView v;
  v.label = vehicle.alias;
  v.outcome = vehicle.metrics.value("outcome", std::string());
  v.track = read_track(dir / vehicle.trajectory_file);
  try {
    for (const auto& wp : vehicle.parameters.at("mission")) {
      Waypoint w;
      w.position_m = vector3(wp.at("position_m"));
      if (wp.contains("heading_deg")) w.heading_deg = wp["heading_deg"].get<double>();
      v.mission.push_back(w);
    }
    add_decisions(v, vehicle.events, vehicle.planner, std::numeric_limits<double>::infinity(), record_file);
    // Runs recorded before collisions were listed have none to mark.
    if (const auto events = vehicle.metrics.find("collision_events"); events != vehicle.metrics.end()) {
      for (const auto& e : *events) v.collisions.emplace_back(e.at("time_s").get<double>(), vector3(e.at("point_m")));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(record_file, pointer, std::string("malformed run record: ") + e.what());
  }
  return v;
}

}  // namespace

RecordedRun load_run_dir(const std::filesystem::path& dir, const std::string& vehicle) {
  // An empty path would read run.json from the working directory.
  if (dir.empty()) throw InputError("", "", "expected the path of a run directory, got an empty string");
  RecordedRun run;
  run.dir = dir;
  run.record = read_json_file(dir / "run.json", {64u << 20, 64});
  const std::string record_file = (dir / "run.json").string();
  const auto scene_path = dir / "scene.json";
  const std::filesystem::path data_dir = run.record.value("/provenance/scene/data_dir"_json_pointer, std::string("."));
  run.scene = parse_scene(read_json_file(scene_path), scene_path.string(), data_dir);
  // Dynamic bodies are drawn where the run left them (a fallen box on the ground).
  for (const auto& body : run.record.value("final_body_poses", nlohmann::json::array())) {
    const std::string alias = body.at("alias").get<std::string>();
    for (Shape& shape : run.scene.shapes) {
      if (shape.is_static || shape.alias != alias) continue;
      shape.pose = to_isometry(Pose{vector3(body.at("position_m")), vector3(body.at("rpy_deg"))});
    }
  }
  // Each vehicle's record: run.json's "vehicles" with several, run.json itself with one.
  std::vector<std::string> pointers;
  try {
    if (const auto list = run.record.find("vehicles"); list != run.record.end()) {
      if (!list->is_array() || list->empty()) {
        throw InputError(record_file, "/vehicles", "expected an array of one record per vehicle");
      }
      for (std::size_t i = 0; i < list->size(); ++i) {
        const nlohmann::json& entry = (*list)[i];
        const std::string pointer = "/vehicles/" + std::to_string(i);
        RecordedVehicle v;
        v.alias = entry.at("alias").get<std::string>();
        v.parameters = entry.at("parameters");
        v.metrics = entry.at("metrics");
        v.trajectory_file = file_beside(dir, entry.at("trajectory_file").get<std::string>(), pointer + "/trajectory_file")
                                .filename()
                                .string();
        v.events = read_events(dir, entry, pointer);
        run.vehicles.push_back(std::move(v));
        pointers.push_back(pointer);
      }
    } else {
      RecordedVehicle v;
      v.alias = run.record.value("/parameters/vehicle/alias"_json_pointer, std::string());
      v.parameters = run.record.value("parameters", nlohmann::json::object());
      v.metrics = run.record.at("metrics");
      v.trajectory_file = "trajectory.csv";
      v.events = read_events(dir, run.record, "");
      run.vehicles.push_back(std::move(v));
      pointers.push_back("");
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(record_file, "", std::string("malformed run record: ") + e.what());
  }
  if (!vehicle.empty()) {
    const auto it = std::find_if(run.vehicles.begin(), run.vehicles.end(),
                                 [&](const RecordedVehicle& v) { return v.alias == vehicle; });
    if (it == run.vehicles.end()) {
      std::string known;
      for (const RecordedVehicle& v : run.vehicles) known += (known.empty() ? "\"" : ", \"") + v.alias + "\"";
      throw InputError("command line", "--vehicle",
                       "no vehicle \"" + vehicle + "\" in the run " + dir.string() + " (its vehicles: " + known + ")");
    }
    run.chosen = static_cast<std::size_t>(it - run.vehicles.begin());
  }
  for (std::size_t i = 0; i < run.vehicles.size(); ++i) {
    RecordedVehicle& v = run.vehicles[i];
    v.planner = planner_record(v.parameters.value("/planner/name"_json_pointer, std::string()));
    if (v.planner) check_own_decisions(*v.planner, v.events, record_file);
    v.view = vehicle_view(dir, v, pointers[i]);
  }
  const RecordedVehicle& chosen = run.vehicles[run.chosen];
  run.events = chosen.events;
  run.planner = chosen.planner;
  run.view = chosen.view;
  run.view.label = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
  return run;
}

std::string sensor_records_vehicle(const RecordedRun& run) {
  const auto named = run.record.find("recorded_vehicle");
  if (named != run.record.end() && named->is_string()) return named->get<std::string>();
  return run.vehicles.empty() ? std::string() : run.vehicles.front().alias;
}

namespace {

// `whole` as it was at `time_s`, from its planner's `events`.
RunView view_at(const RunView& whole, const std::vector<PlannerEvent>& events, const PlannerRecord* planner,
                const std::string& record_file, double time_s) {
  RunView v;
  v.label = whole.label;
  v.outcome = whole.outcome;
  v.mission = whole.mission;
  for (const TrackPoint& p : whole.track) {
    if (p.time_s > time_s) break;
    v.track.push_back(p);
  }
  if (v.track.empty() && !whole.track.empty()) v.track.push_back(whole.track.front());
  add_decisions(v, events, planner, time_s, record_file);
  for (const auto& c : whole.collisions) {
    if (c.first <= time_s) v.collisions.push_back(c);
  }
  return v;
}

}  // namespace

RunView run_view_at(const RecordedRun& run, double time_s) {
  return view_at(run.view, run.events, run.planner, (run.dir / "run.json").string(), time_s);
}

RunView run_view_at(const RecordedRun& run, std::size_t index, double time_s) {
  const RecordedVehicle& vehicle = run.vehicles.at(index);
  return view_at(vehicle.view, vehicle.events, vehicle.planner, (run.dir / "run.json").string(), time_s);
}

Eigen::Vector3d vehicle_size_m(const RecordedRun& run) { return vehicle_size_m(run.vehicles.at(run.chosen)); }

Eigen::Vector3d vehicle_size_m(const RecordedVehicle& recorded) {
  const nlohmann::json& vehicle = recorded.parameters.value("vehicle", nlohmann::json::object());
  const nlohmann::json params = vehicle.value("parameters", nlohmann::json::object());
  const auto triple = [](const nlohmann::json& j) {
    return j.is_array() && j.size() == 3 && std::all_of(j.begin(), j.end(), [](const auto& v) { return v.is_number(); });
  };
  if (triple(params.value("chassis_size_m", nlohmann::json()))) return vector3(params["chassis_size_m"]);
  if (triple(params.value("collision_half_extents_m", nlohmann::json()))) {
    return 2.0 * vector3(params["collision_half_extents_m"]);
  }
  return vehicle.value("type", "") == "rover" ? Eigen::Vector3d(1.5, 1.0, 0.35) : Eigen::Vector3d(0.6, 0.6, 0.12);
}

std::string recorded_file_name(const std::string& alias, double time_s) {
  char time[32];
  std::snprintf(time, sizeof time, "%08.3f", time_s);
  return alias + "_" + time + ".png";
}

namespace {

// The files recorded_file_name names in `dir`, in time order.
std::vector<RecordedDepthMap> recorded_files(const std::filesystem::path& dir) {
  std::vector<RecordedDepthMap> maps;
  std::error_code error;  // no such directory: nothing recorded
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    const std::string stem = entry.path().stem().string();
    const std::size_t cut = stem.rfind('_');
    if (entry.path().extension() != ".png" || cut == std::string::npos) continue;
    double t = 0.0;
    const char* end = stem.data() + stem.size();
    const auto [ptr, ec] = std::from_chars(stem.data() + cut + 1, end, t);
    if (ec != std::errc() || ptr != end) continue;
    maps.push_back({stem.substr(0, cut), t, entry.path()});
  }
  // Directory order is the file system's: sort, by time and then name, for the same result everywhere.
  std::sort(maps.begin(), maps.end(), [](const auto& a, const auto& b) {
    return std::tie(a.time_s, a.sensor) < std::tie(b.time_s, b.sensor);
  });
  return maps;
}

}  // namespace

std::vector<RecordedDepthMap> recorded_depth_maps(const RecordedRun& run) { return recorded_files(run.dir / "depth"); }

std::vector<RecordedDepthMap> recorded_images(const RecordedRun& run) { return recorded_files(run.dir / "images"); }

cv::Mat read_depth_map(const std::filesystem::path& file) {
  const cv::Mat gray16 = read_png_file(file);
  if (gray16.type() != CV_16U) throw InputError(file.string(), "", "expected a 16-bit grey depth map");
  cv::Mat depth;
  gray16.convertTo(depth, CV_32F, 1.0 / 65535.0);
  return depth;
}

std::vector<Eigen::Vector3d> depth_map_returns(const cv::Mat& depth, const SensorDef& sensor,
                                               const Eigen::Isometry3d& vehicle_pose, const std::filesystem::path& file) {
  const std::vector<Beam> beams = lidar_beams(sensor.range);
  if (depth.type() != CV_32F || depth.total() != beams.size()) {
    throw InputError(file.string(), "", "expected " + std::to_string(beams.size()) + " ranges, one per beam of sensor \"" +
                                            sensor.alias + "\"");
  }
  const Eigen::Isometry3d sensor_pose = vehicle_pose * to_isometry(sensor.range.mount);
  std::vector<Eigen::Vector3d> points;
  const cv::Mat values = depth.reshape(1, 1);  // beam order: the map row by row
  const float* v = values.ptr<float>(0);
  for (std::size_t b = 0; b < beams.size(); ++b) {
    if (v[b] <= 0.0f || v[b] >= 1.0f) continue;  // below min range, or no return
    points.push_back(sensor_pose * (beam_direction(beams[b]).cast<double>() * (v[b] * sensor.range.max_range_m)));
  }
  return points;
}

const VehicleDef& recorded_vehicle(const RecordedRun& run) {
  const std::string alias = run.parameters().value("/vehicle/alias"_json_pointer, std::string());
  for (const VehicleDef& v : run.scene.vehicles) {
    if (v.alias == alias) return v;
  }
  throw InputError((run.dir / "run.json").string(),
                   (run.several() ? "/vehicles/" + std::to_string(run.chosen) : std::string()) + "/parameters/vehicle/alias",
                   "expected a vehicle of scene.json, got \"" + alias + "\"");
}

std::string replan_depth_file(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "replan_%04d.png", index);
  return name;
}

}  // namespace campo
