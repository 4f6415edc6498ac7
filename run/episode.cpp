#include "campo/episode.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "campo/json_reader.hpp"
#include "campo/planner_record.hpp"
#include "metrics/episode_metrics.hpp"
#include "metrics/mission_metrics.hpp"
#include "metrics/planner_metrics.hpp"
#include "run/event_log.hpp"

namespace campo {

namespace {

using Clock = std::chrono::steady_clock;

// Steps between two events at `rate_hz` with physics step dt. The scene
// loader accepts only rates that divide the physics rate, so every accepted
// rate is the rate that runs; a scene built in code must obey it too.
std::int64_t period_steps(double rate_hz, double dt) {
  const std::int64_t steps = steps_per_period(rate_hz, dt);
  if (steps < 1) {
    throw std::invalid_argument("a rate of " + std::to_string(rate_hz) + " Hz does not divide the physics rate " +
                                std::to_string(1.0 / dt) + " Hz into whole steps");
  }
  return steps;
}

struct MountedSensor {
  std::unique_ptr<RangeSensor> sensor;
  std::shared_ptr<RangeScan> scan;  // shared with the readings (SensorReading::scan)
  std::int64_t period;
};

constexpr double kExact = std::numeric_limits<double>::infinity();

// "collision with forest/tree4/crown at t = 3.120000 s, at (12.411, 4.032, 2.950) m".
std::string collision_reason(const CollisionEvent& e) {
  char point[96];
  std::snprintf(point, sizeof point, "(%.3f, %.3f, %.3f)", e.point_m.x(), e.point_m.y(), e.point_m.z());
  const std::string with = e.ground ? "the ground (" + e.body + ")" : e.body;
  return "collision with " + with + " at t = " + std::to_string(e.time_s) + " s, at " + point + " m";
}

}  // namespace

// Everything one run holds between control ticks; stepped only by Episode::step.
struct Episode::Loop {
  Loop(const Scene& scene_in, VehicleFactory make_vehicle, const EpisodeOptions& options_in)
      : scene(scene_in),
        options(options_in),
        def(scene.vehicles.at(options.vehicle_index)),
        dt(scene.world.physics_step_s),
        wall_start(Clock::now()),
        world(scene),
        vehicle(make_vehicle(world, def)),
        estimator(def.state_noise, Rng::derive_seed(scene.world.seed, 0x5e57'0000ULL + options.vehicle_index)),
        control_period(period_steps(scene.world.control_rate_hz, dt)),
        start(vehicle->state().position_m),
        previous(start),
        reached_at(def.mission.size()),
        reached_sample(def.mission.size()),
        record(planner_record(def.planner.name)) {
    // A planner's own metric that would overwrite another metric of run.json refuses the run before it starts.
    if (record) check_planner_metric_names(def.planner.name, *record, def);
    sensors.reserve(def.sensors.size());
    for (const SensorDef& s : def.sensors) {
      const double rate = s.range.rate_hz > 0.0 ? s.range.rate_hz : scene.world.sensor_rate_hz;
      sensors.push_back(
          {options.make_sensor(scene, s, scene.world.seed), std::make_shared<RangeScan>(), period_steps(rate, dt)});
    }
    readings.resize(sensors.size());
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      readings[i] = {def.sensors[i].alias, &def.sensors[i].range, nullptr, false};
    }
    result.vehicle_parameters = vehicle->parameters();
  }

  // Sense: every sensor due at physics step k scans with every body where the physics has it now.
  void sense() {
    const double t = static_cast<double>(k) * dt;
    bool poses_read = false;
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      MountedSensor& s = sensors[i];
      if (k % s.period != 0) continue;
      if (!poses_read) world.moving_body_poses(body_poses);
      poses_read = true;
      s.sensor->scan(vehicle->state().pose() * to_isometry(def.sensors[i].range.mount), t, body_poses, *s.scan);
      readings[i].scan = s.scan;
      readings[i].fresh = true;
      if (options.on_scan) options.on_scan(i, *s.scan);
    }
  }

  // The observation of a control tick, on the estimated state.
  void observe() {
    const double t = static_cast<double>(k) * dt;
    truth = vehicle->state();
    const StateError& error = estimator.error_at(t);
    vehicle->set_estimation_error(error);
    observation = Observation{t, def.type, estimated(truth, error), vehicle->stable(), readings, def.mission};
  }

  // The rest of a control tick, after the decision: records it and commands the vehicle.
  void act(PlanResult plan, double planner_ms) {
    // First, so a command the vehicle cannot follow (std::invalid_argument) leaves the run untouched.
    vehicle->command(plan.command);
    const double t = observation.time_s;
    if (options.on_plan) options.on_plan(observation, plan);
    for (auto& r : readings) r.fresh = false;
    EpisodeMetrics& m = result.metrics;
    ++m.planner_calls;
    planner_ms_total += planner_ms;
    m.planner_time_ms_max = std::max(m.planner_time_ms_max, planner_ms);
    for (const int i : plan.decisions.reached_waypoints) {
      if (i >= 0 && static_cast<std::size_t>(i) < reached_at.size()) {
        reached_at[static_cast<std::size_t>(i)] = truth.position_m;
        reached_sample[static_cast<std::size_t>(i)] = result.trajectory.size();
      }
    }
    // Bounded as recorded (run/event_log.hpp): a scan's thousands of hits would otherwise make the record
    // grow with every scan; the metrics below read the same bounded decisions the files keep.
    if (!plan.decisions.empty()) result.events.push_back({t, bounded_decisions(std::move(plan.decisions))});
    // Exact obstacle clearance for the record; the ground only as far as
    // it could lower its minimum (far terrain costs many triangles).
    const Clearance clearance = world.vehicle_clearance(kExact, minima.ground_cutoff());
    minima.update(clearance, t);
    const std::optional<double> ground = scene.ground_height(truth.position_m.x(), truth.position_m.y());
    const double above_ground = ground ? truth.position_m.z() - *ground : std::numeric_limits<double>::quiet_NaN();
    result.trajectory.push_back({t, truth, observation.state.position_m, plan.command, clearance.obstacle_m,
                                 above_ground, vehicle->actuators()});
    if (plan.status == PlanStatus::reached) {
      end(Outcome::reached, plan.reason);
    } else if (plan.status != PlanStatus::running) {
      end(Outcome::aborted, std::string(to_string(plan.status)) + (plan.reason.empty() ? "" : ": " + plan.reason));
    }
  }

  // Actuate and step the physics once; then sense at the new step.
  void physics_step() {
    EpisodeMetrics& m = result.metrics;
    vehicle->pre_step(dt);
    world.step();
    const Eigen::Vector3d position = vehicle->state().position_m;
    m.path_length_m += (position - previous).norm();
    previous = position;
    // A collision is the collision shapes touching, from the same query as
    // the clearance metrics, so an overlap is always a collision.
    const Clearance clearance = world.vehicle_clearance(minima.obstacle_cutoff(), minima.ground_cutoff());
    minima.update(clearance, world.time_s());
    const bool colliding = clearance.touching();
    if (colliding && !was_colliding) {
      ++m.collisions;
      // Strings only here, when a collision begins: a step that touches nothing allocates nothing.
      CollisionEvent e;
      e.time_s = world.time_s();
      if (clearance.touch) {  // always set when touching (ClearanceQuery::measure)
        e.body = body_name(scene, clearance.touch->body);
        e.ground = clearance.touch->ground;
        e.point_m = clearance.touch->point_m;
      }
      if (options.stop_on_collision) end(Outcome::collision, collision_reason(e));
      if (m.collision_events.size() < EpisodeMetrics::kMaxCollisionEvents) m.collision_events.push_back(std::move(e));
    }
    was_colliding = colliding;
    if (!outcome && world.time_s() >= scene.world.time_limit_s) {
      end(Outcome::timeout, "time limit of " + std::to_string(scene.world.time_limit_s) + " s reached");
    }
    ++k;
  }

  void end(Outcome o, std::string reason) {
    outcome = o;
    result.metrics.reason = std::move(reason);
  }

  // From physics step k (sensed): steps until the next control tick (observed) or the end.
  void advance_to_control_tick() {
    while (!outcome) {
      if (k % control_period == 0) {
        observe();
        return;
      }
      physics_step();
      if (!outcome) sense();
    }
  }

  EpisodeResult finish() {
    EpisodeMetrics& m = result.metrics;
    m.outcome = *outcome;
    m.sim_time_s = world.time_s();
    minima.write(scene, m);
    // The nominal route: straight legs from the start through every waypoint
    // (for a single goal, the straight start-goal line), each waypoint taken
    // where the vehicle was when it was reached (within the arrival
    // tolerance), so the path flown, which passes through those points, is
    // never shorter than the route: the ratio of a reached run is at least 1.
    if (m.outcome == Outcome::reached && !def.mission.empty()) reached_at.back() = vehicle->state().position_m;
    m.path_ratio = path_ratio(m.path_length_m, nominal_route_m(def.type, start, def.mission, reached_at));
    count_decisions(result.events, m);
    const CrossTrack cross_track = cross_track_error(result.trajectory, result.events);
    m.cross_track_rms_m = cross_track.rms_m;
    m.cross_track_mean_m = cross_track.mean_m;
    m.cross_track_max_m = cross_track.max_m;
    m.avoiding_time_s = avoiding_time(result.events, m.sim_time_s);
    write_mission_metrics(def, start, result.trajectory, reached_sample, m.declared);
    if (record) write_planner_metrics(def.planner.name, *record, {result.events, m.sim_time_s}, m.declared);
    m.planner_time_ms_mean = m.planner_calls > 0 ? planner_ms_total / m.planner_calls : 0.0;
    m.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
    result.final_state_hash = world.state_hash();
    world.moving_body_poses(result.final_body_poses);
    return std::move(result);
  }

  const Scene& scene;
  const EpisodeOptions options;
  const VehicleDef& def;
  const double dt;
  const Clock::time_point wall_start;
  World world;
  const std::unique_ptr<Vehicle> vehicle;
  StateEstimator estimator;
  std::vector<MountedSensor> sensors;
  std::vector<SensorReading> readings;
  std::vector<Eigen::Isometry3d> body_poses;  // of the moving bodies, refreshed before each scan
  const std::int64_t control_period;
  const Eigen::Vector3d start;
  Eigen::Vector3d previous;
  // Where the vehicle was when the planner reported each mission waypoint reached,
  // and the index of the trajectory sample of that planner call.
  std::vector<std::optional<Eigen::Vector3d>> reached_at;
  std::vector<std::optional<std::size_t>> reached_sample;
  // The description of the vehicle's planner's record, for its own metrics; null: none.
  const PlannerRecord* const record;
  ClearanceMinima minima;
  double planner_ms_total = 0.0;
  bool was_colliding = false;
  std::optional<Outcome> outcome;
  std::int64_t k = 0;  // physics steps taken
  VehicleState truth;  // at the current control tick
  Observation observation;
  EpisodeResult result;
  bool finished = false;
};

Episode::Episode(const Scene& scene, VehicleFactory make_vehicle, const EpisodeOptions& options) {
  if (options.vehicle_index >= scene.vehicles.size()) {
    throw std::invalid_argument("scene " + scene.name + " has no vehicle " + std::to_string(options.vehicle_index));
  }
  loop_ = std::make_unique<Loop>(scene, make_vehicle, options);
  loop_->sense();
  loop_->advance_to_control_tick();
}

Episode::~Episode() = default;
Episode::Episode(Episode&&) noexcept = default;
Episode& Episode::operator=(Episode&&) noexcept = default;

bool Episode::done() const { return loop_->outcome.has_value(); }

const Observation& Episode::observation() const { return loop_->observation; }

void Episode::step(PlanResult plan, double planner_time_ms) {
  if (done()) throw std::logic_error("Episode::step: the episode has ended");
  loop_->act(std::move(plan), planner_time_ms);
  if (!done()) {
    loop_->physics_step();
    if (!done()) loop_->sense();
    loop_->advance_to_control_tick();
  }
  // The end as a caller stepping from outside sees it.
  if (done()) loop_->observe();
}

void Episode::fail(std::string reason) {
  if (!done()) loop_->end(Outcome::failed, std::move(reason));
}

const Vehicle& Episode::vehicle() const { return *loop_->vehicle; }

const World& Episode::world() const { return loop_->world; }

const EpisodeMetrics& Episode::metrics_so_far() const { return loop_->result.metrics; }

EpisodeResult Episode::finish() {
  if (!done()) throw std::logic_error("Episode::finish: the episode has not ended");
  if (loop_->finished) throw std::logic_error("Episode::finish: called twice");
  loop_->finished = true;
  return loop_->finish();
}

EpisodeResult run_episode(const Scene& scene, VehicleFactory make_vehicle, const PlannerMaker& make_planner,
                          const EpisodeOptions& options) {
  Episode episode(scene, make_vehicle, options);  // checks the vehicle index
  const VehicleDef& def = scene.vehicles[options.vehicle_index];
  const std::unique_ptr<Planner> planner = make_planner(def.planner, {def.type, &scene, &def});
  const nlohmann::json planner_parameters = planner->parameters();
  while (!episode.done()) {
    const auto plan_start = Clock::now();
    PlanResult plan;
    try {
      plan = planner->plan(episode.observation());
    } catch (const InputError&) {
      throw;  // bad input stays bad input (exit 2), whoever finds it
    } catch (const std::exception& e) {
      // A planner that fails ends its run, recorded as failed with what it said; nothing is lost.
      episode.fail(std::string("the planner raised an error: ") + e.what());
      break;
    }
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - plan_start).count();
    try {
      episode.step(std::move(plan), ms);
    } catch (const std::invalid_argument& e) {
      episode.fail(std::string("the planner gave a command the vehicle cannot follow: ") + e.what());
    }
  }
  EpisodeResult result = episode.finish();
  result.planner_parameters = planner_parameters;
  return result;
}

}  // namespace campo
