#pragma once
/// The closed loop (SPEC §1): sense -> plan -> control -> actuate -> step,
/// each at its own rate, for every vehicle of a scene, until their missions
/// end, the time limit passes or they collide. Stepped from this one place; deterministic for a given
/// Scene (including its world seed).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode_record.hpp"
#include "campo/planner.hpp"
#include "campo/range_sensor.hpp"
#include "campo/rgb_camera.hpp"
#include "campo/scene.hpp"
#include "campo/vehicle.hpp"
#include "campo/world.hpp"

namespace campo {

/// Builds the vehicle of a definition inside a world (make_vehicle, campo/vehicle_factory.hpp).
using VehicleFactory = std::unique_ptr<Vehicle> (*)(World& world, const VehicleDef& def);

/// One vehicle's record of a run.
struct VehicleResult {
  std::string alias;
  EpisodeMetrics metrics;
  std::vector<TrajectorySample> trajectory;
  std::vector<PlannerEvent> events;
  nlohmann::json vehicle_parameters;
  nlohmann::json planner_parameters;
};

/// The record of a run: one VehicleResult per vehicle of the scene, in scene
/// order, and the run as a whole.
struct EpisodeResult {
  std::vector<VehicleResult> vehicles;
  FleetMetrics fleet;
  std::uint64_t final_state_hash = 0;  ///< World::state_hash at the end (determinism checks)
  /// Where the moving bodies (moving_bodies(scene): dynamic shapes, then
  /// movers) were at the end, so figures show a fallen box where it fell.
  std::vector<Eigen::Isometry3d> final_body_poses;

  /// The record of the scene's only vehicle; std::logic_error when it has several.
  VehicleResult& only();
  const VehicleResult& only() const;
};

struct EpisodeOptions {
  bool stop_on_collision = true;  ///< end a vehicle's mission at its first collision
  /// Builds the vehicles' sensors (sensor_factory.hpp's range_sensor_factory adds depth cameras).
  SensorFactory make_sensor = &make_lidar_sensor;
  /// Called after every scan with the vehicle's and the sensor's index and the fresh scan
  /// (e.g. to record depth maps).
  std::function<void(std::size_t vehicle, std::size_t sensor, const RangeScan& scan)> on_scan;
  /// Builds the vehicles' colour cameras (sensor_factory.hpp's rgb_camera_factory); a scene
  /// with an "rgb_camera" and no factory is refused with std::invalid_argument.
  RgbCameraFactory make_camera;
  /// Called after every image with the vehicle's and the camera's index (in VehicleDef::rgb_cameras).
  std::function<void(std::size_t vehicle, std::size_t camera, const RgbImage& image)> on_image;
  /// Called after every IMU sample with the vehicle's and the IMU's index (in VehicleDef::imus), at the
  /// IMU's own rate (imu.csv keeps every sample, however fast).
  std::function<void(std::size_t vehicle, std::size_t imu, const ImuReading& reading)> on_imu;
  /// Called after every planner call with the vehicle's index and what its
  /// planner saw and decided (e.g. to record the depth map a replanning used).
  std::function<void(std::size_t vehicle, const Observation& observation, const PlanResult& plan)> on_plan;
};

/// A command a vehicle cannot follow, given to Episode::step.
class VehicleCommandError : public std::invalid_argument {
 public:
  VehicleCommandError(std::size_t vehicle, const std::string& message)
      : std::invalid_argument(message), vehicle_(vehicle) {}
  std::size_t vehicle() const { return vehicle_; }

 private:
  std::size_t vehicle_;
};

/// One run of the closed loop over every vehicle of a scene, stepped from
/// outside: at every control tick the caller decides what each vehicle's
/// planner would (step), the episode senses, controls, actuates and steps
/// the physics up to the next tick. Each vehicle's mission ends on its own
/// (reached, aborted, collision, failed; all at the time limit); an ended
/// vehicle holds where it is, still a body in the world, and the run ends by
/// the scene's EndRule. Each vehicle's sensors see the others where the
/// physics has them. run_episode drives one with planners, the Python module
/// from Python; both give the same result for the same decisions, bit for
/// bit. `scene` must outlive it.
class Episode {
 public:
  /// Builds the world, the vehicles (in scene order) and their sensors, and
  /// advances to the first control tick.
  Episode(const Scene& scene, VehicleFactory make_vehicle, const EpisodeOptions& options = {});
  ~Episode();
  Episode(Episode&&) noexcept;
  Episode& operator=(Episode&&) noexcept;

  std::size_t vehicle_count() const;
  /// Whether the run has ended.
  bool done() const;
  /// Whether vehicle `vehicle`'s mission has ended.
  bool done(std::size_t vehicle) const;
  /// How vehicle `vehicle`'s mission ended, once it has, and when (simulated
  /// seconds; its metrics' outcome and sim_time_s once finished).
  std::optional<Outcome> outcome(std::size_t vehicle) const;
  double end_time_s(std::size_t vehicle) const;
  /// What vehicle `vehicle`'s planner sees at the current control tick (the
  /// estimated state, the latest readings); valid until the next step. Once
  /// its mission has ended, the state it ended in.
  const Observation& observation(std::size_t vehicle = 0) const;
  /// Acts on each vehicle's decision for the current tick (one per vehicle
  /// in scene order; those of vehicles whose missions have ended are
  /// ignored; a status may end a mission) and advances to the next tick or
  /// the end; `planner_time_ms` (empty, or one per vehicle) is what deciding
  /// took, for the planner-time metrics. Not when done(). A command a vehicle
  /// cannot follow throws VehicleCommandError naming it before anything is
  /// recorded or stepped (`plans` left as given); the vehicles before it in
  /// scene order, which took theirs, are given back the command they had
  /// (at the first tick there is none: they keep the new one until the next step).
  void step(std::vector<PlanResult>&& plans, const std::vector<double>& planner_time_ms = {});
  /// The same for a scene of one vehicle.
  void step(PlanResult plan, double planner_time_ms = 0.0);
  /// Ends vehicle `vehicle`'s mission as failed with `reason` (a planner that threw), if it has not ended.
  void fail(std::size_t vehicle, std::string reason);
  /// Ends every mission that has not ended as failed with `reason`.
  void fail(std::string reason);

  const Vehicle& vehicle(std::size_t vehicle = 0) const;
  const World& world() const;
  /// Vehicle `vehicle`'s counters so far (collisions, planner calls, path
  /// length); the rest of the metrics are computed by finish().
  const EpisodeMetrics& metrics_so_far(std::size_t vehicle = 0) const;
  /// The result of an ended run; once. Its planner_parameters are left empty.
  EpisodeResult finish();

 private:
  struct Loop;
  std::unique_ptr<Loop> loop_;
};

/// Runs one episode of `scene` to its end, each vehicle with the planner
/// `make_planner` builds for it. An exception from a planner (but an
/// InputError, rethrown), or a command its vehicle cannot follow, ends that
/// vehicle's mission as Outcome::failed with its message as the reason.
EpisodeResult run_episode(const Scene& scene, VehicleFactory make_vehicle, const PlannerMaker& make_planner,
                          const EpisodeOptions& options = {});

}  // namespace campo
