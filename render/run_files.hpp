#pragma once
/// Reading a recorded run directory (run.json, events.jsonl, trajectory.csv, scene.json)
/// back for figures, so every figure is reproducible from the files alone.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/planner_record.hpp"
#include "campo/scene.hpp"
#include "render/figures.hpp"

namespace campo {

/// One vehicle of a recorded run: its own record, track and planner decisions.
struct RecordedVehicle {
  std::string alias;
  /// Its parameters {vehicle, planner, sensors, mission}: run.json's "parameters" for a run of one vehicle, its
  /// entry's under "vehicles" for a run of several.
  nlohmann::json parameters;
  nlohmann::json metrics;        ///< its metrics (a run of one vehicle: run.json's "metrics")
  std::string trajectory_file;   ///< file name in the run directory: trajectory.csv, trajectory_<alias>.csv
  std::vector<PlannerEvent> events;  ///< its planner's decisions in time order
  RunView view;                  ///< track, mission and planner decisions; label: the alias
  const PlannerRecord* planner = nullptr;  ///< its planner's description of its record; null when none
};

struct RecordedRun {
  std::filesystem::path dir;
  nlohmann::json record;  ///< run.json
  Scene scene;            ///< from scene.json, the effective scene of the run
  /// Every vehicle of the run, in scene order (one for a run of one vehicle).
  std::vector<RecordedVehicle> vehicles;
  /// The chosen vehicle (load_run_dir's `vehicle`, the first by default): index into `vehicles`. The fields below
  /// are its, so that what draws one vehicle (sensor panels, depth figures, sequences) reads them as before.
  std::size_t chosen = 0;
  /// The chosen vehicle's planner decisions in time order: events.jsonl (run.json's
  /// event_log), or the "events" array of run.json in runs recorded before it.
  std::vector<PlannerEvent> events;
  /// The chosen vehicle's track, mission and planner decisions; label: the run directory's name.
  RunView view;
  /// The recorded planner's description of its record (planner_record), found
  /// by the planner name run.json records; null when it has none or is not loaded.
  const PlannerRecord* planner = nullptr;
  /// The chosen vehicle's parameters {vehicle, planner, sensors, mission} (RecordedVehicle::parameters).
  const nlohmann::json& parameters() const { return vehicles.at(chosen).parameters; }
  /// The chosen vehicle's metrics.
  const nlohmann::json& metrics() const { return vehicles.at(chosen).metrics; }
  /// Whether the run held several vehicles (run.json's "vehicles").
  bool several() const { return vehicles.size() > 1; }
};

/// trajectory.csv read back as numbers, column by column (docs/running.md);
/// fields that are not numbers (the command's name) read as 0.
struct TrajectoryTable {
  std::string file;
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;  ///< [column][row]
  /// The column named `name`; InputError naming the file when there is none.
  const std::vector<double>& column(const std::string& name) const;
};

/// Reads a trajectory.csv; InputError naming the file and line when a line is
/// short or its time_s is not a finite number >= 0 and >= the previous line's.
TrajectoryTable read_trajectory_table(const std::filesystem::path& path);

/// Loads a run directory written by `campo run`, every vehicle of it (a run of
/// several: run.json's "vehicles", trajectory_<alias>.csv, events_<alias>.jsonl);
/// `vehicle` names the chosen one (RecordedRun::chosen; empty: the first).
/// InputError naming the file when something is missing or malformed, or when
/// a planner's own decisions (or its replanning steps' details) hold a key its
/// description does not declare or a value not of its declared type;
/// InputError naming --vehicle when the run has no vehicle `vehicle`.
RecordedRun load_run_dir(const std::filesystem::path& dir, const std::string& vehicle = "");

/// The run as it was at `time_s`: its track samples up to then (at least the
/// first) and the planner decisions made by then (RunView's fields); label,
/// outcome and mission as recorded. What a video's frame shows. The chosen
/// vehicle's; the second form vehicle `index`'s (RecordedRun::vehicles).
RunView run_view_at(const RecordedRun& run, double time_s);
RunView run_view_at(const RecordedRun& run, std::size_t index, double time_s);

/// The vehicle's size (length, width, height), m, from the recorded vehicle
/// parameters: a rover's chassis_size_m, a quadrotor's collision box; the
/// presets' sizes (rover 1.5 x 1.0 x 0.35, quadrotor 0.6 x 0.6 x 0.12) when absent.
/// The chosen vehicle's; the second form that of `vehicle`.
Eigen::Vector3d vehicle_size_m(const RecordedRun& run);
Eigen::Vector3d vehicle_size_m(const RecordedVehicle& vehicle);

/// The alias of the vehicle whose depth maps (depth/) and replanning depth maps
/// (replans/) the run recorded (`campo run --vehicle`): run.json's
/// "recorded_vehicle" when it names one, else the first vehicle.
std::string sensor_records_vehicle(const RecordedRun& run);

/// A depth map `campo run --record-depth N` saved: depth/<sensor>_<time>.png.
struct RecordedDepthMap {
  std::string sensor;  ///< the sensor's alias
  double time_s = 0.0; ///< when it scanned, simulated seconds
  std::filesystem::path file;
};
/// The run's recorded depth maps in time order (none when it recorded none).
std::vector<RecordedDepthMap> recorded_depth_maps(const RecordedRun& run);
/// The colour images `campo run --record-images N` saved, images/<camera>_<time>.png
/// (8-bit RGB), in time order; `sensor` is the camera's alias.
std::vector<RecordedDepthMap> recorded_images(const RecordedRun& run);
/// The name of a recorded depth map or image: <alias>_<time, %08.3f s>.png.
std::string recorded_file_name(const std::string& alias, double time_s);
/// A recorded depth map (16-bit PNG, sensors/depth_image.hpp) back as CV_32F
/// in [0, 1]; InputError naming the file when it is not one.
cv::Mat read_depth_map(const std::filesystem::path& file);
/// The returns of a recorded depth map of `sensor` (one value per beam, SPEC §6:
/// neither 0, below min range, nor 1, no return) as points in the frame of which
/// `vehicle_pose` is the vehicle's pose (identity: the vehicle's own frame), through
/// the sensor's mount and beam directions; InputError naming `file` when the map
/// has not one value per beam.
std::vector<Eigen::Vector3d> depth_map_returns(const cv::Mat& depth, const SensorDef& sensor,
                                               const Eigen::Isometry3d& vehicle_pose, const std::filesystem::path& file);

/// The run's chosen vehicle in its scene.json (its parameters' /vehicle/alias);
/// InputError when the scene has no such vehicle.
const VehicleDef& recorded_vehicle(const RecordedRun& run);

/// File name, under the run's replans/ directory, of the depth map that
/// replanning `index` used (16-bit PNG, depth_image.hpp).
std::string replan_depth_file(int index);

}  // namespace campo
