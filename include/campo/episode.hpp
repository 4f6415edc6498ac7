#pragma once
/// The closed loop (SPEC §1): sense -> plan -> control -> actuate -> step,
/// each at its own rate, until the mission ends, the time limit passes or the
/// vehicle collides. Stepped from this one place; deterministic for a given
/// Scene (including its world seed).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode_record.hpp"
#include "campo/planner.hpp"
#include "campo/range_sensor.hpp"
#include "campo/scene.hpp"
#include "campo/vehicle.hpp"
#include "campo/world.hpp"

namespace campo {

/// Builds the vehicle of a definition inside a world (make_vehicle, campo/vehicle_factory.hpp).
using VehicleFactory = std::unique_ptr<Vehicle> (*)(World& world, const VehicleDef& def);
struct EpisodeResult {
  EpisodeMetrics metrics;
  std::vector<TrajectorySample> trajectory;
  std::vector<PlannerEvent> events;
  nlohmann::json vehicle_parameters;
  nlohmann::json planner_parameters;
  std::uint64_t final_state_hash = 0;  ///< World::state_hash at the end (determinism checks)
  /// Where the moving bodies (moving_bodies(scene): dynamic shapes, then
  /// movers) were at the end, so figures show a fallen box where it fell.
  std::vector<Eigen::Isometry3d> final_body_poses;
};

struct EpisodeOptions {
  std::size_t vehicle_index = 0;  ///< which of the scene's vehicles runs the mission
  bool stop_on_collision = true;  ///< end the run at the first collision
  /// Builds the vehicle's sensors (sensor_factory.hpp's range_sensor_factory adds depth cameras).
  SensorFactory make_sensor = &make_lidar_sensor;
  /// Called after every scan with the sensor index and its fresh scan (e.g. to record depth maps).
  std::function<void(std::size_t sensor, const RangeScan& scan)> on_scan;
  /// Called after every planner call with what the planner saw and decided
  /// (e.g. to record the depth map a replanning used).
  std::function<void(const Observation& observation, const PlanResult& plan)> on_plan;
};

/// One run of the closed loop, stepped from outside: at every control tick
/// the caller decides what a planner would (step), the episode senses,
/// controls, actuates and steps the physics up to the next tick. run_episode
/// drives one with a planner, the Python module from Python; both give the
/// same result for the same decisions, bit for bit. `scene` must outlive it.
class Episode {
 public:
  /// Builds the world, the vehicle and its sensors, and advances to the first control tick.
  Episode(const Scene& scene, VehicleFactory make_vehicle, const EpisodeOptions& options = {});
  ~Episode();
  Episode(Episode&&) noexcept;
  Episode& operator=(Episode&&) noexcept;

  /// Whether the run has ended (reached, aborted, collision, timeout, failed).
  bool done() const;
  /// What a planner sees at the current control tick (the estimated state,
  /// the latest readings); valid until the next step. Once done(), the state
  /// the run ended in.
  const Observation& observation() const;
  /// Acts on the decision for the current tick (its status may end the run)
  /// and advances to the next tick or the end; `planner_time_ms` is what
  /// deciding took, for the planner-time metrics. Not when done(). A command
  /// the vehicle cannot follow throws std::invalid_argument and changes nothing.
  void step(PlanResult plan, double planner_time_ms = 0.0);
  /// Ends the run as failed with `reason` (a planner that threw), if it has not ended.
  void fail(std::string reason);

  const Vehicle& vehicle() const;
  const World& world() const;
  /// The counters so far (collisions, planner calls, path length); the rest
  /// of the metrics are computed by finish().
  const EpisodeMetrics& metrics_so_far() const;
  /// The result of an ended run; once. Its planner_parameters are left empty.
  EpisodeResult finish();

 private:
  struct Loop;
  std::unique_ptr<Loop> loop_;
};

/// Runs one episode of `scene` to its end with the planner `make_planner`
/// builds. An exception from the planner (but an InputError, rethrown), or a
/// command the vehicle cannot follow, ends the run as Outcome::failed with
/// its message as the reason.
EpisodeResult run_episode(const Scene& scene, VehicleFactory make_vehicle, const PlannerMaker& make_planner,
                          const EpisodeOptions& options = {});

}  // namespace campo
