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
#include "sensors/imu.hpp"

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

// An IMU: its error model, its period and the carrier's state at its previous sample.
struct MountedImu {
  ImuErrorModel errors;
  std::int64_t period;
  CarrierMotion before;
  bool sampled = false;
};

struct MountedCamera {
  std::unique_ptr<RgbCamera> camera;
  std::shared_ptr<RgbImage> image;  // shared with the readings (ImageReading::image)
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

// Where a vehicle's own bodies are put for its own scans: far below
// anything a sensor reaches, so a sensor never sees the body it is mounted on.
const Eigen::Isometry3d kParked = Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, -1.0e7));

// A copy of `scene` whose movers end with every vehicle's collision shapes
// (where they start), for the sensors of a run of several vehicles: each
// sees the others as moving bodies. `first` gets the index of each vehicle's
// first shape among the scene's moving bodies; `counts` their number.
Scene sensor_scene(const Scene& scene, const World& world, std::vector<std::size_t>& first,
                   std::vector<std::size_t>& counts) {
  Scene seen = scene;
  std::size_t next = moving_bodies(scene).size();
  for (std::size_t v = 0; v < scene.vehicles.size(); ++v) {
    const std::vector<Shape> shapes = world.vehicle_shapes(v, scene.vehicles[v].alias);
    first.push_back(next);
    counts.push_back(shapes.size());
    next += shapes.size();
    for (const Shape& shape : shapes) {
      Mover proxy;
      proxy.shape = shape;
      proxy.path_m = {shape.pose.translation(), shape.pose.translation()};
      seen.movers.push_back(std::move(proxy));
    }
  }
  return seen;
}

}  // namespace

// One vehicle's part of a run.
struct VehicleLoop {
  VehicleLoop(const Scene& scene, std::size_t index_in, World& world, VehicleFactory make_vehicle)
      : def(scene.vehicles[index_in]),
        index(index_in),
        vehicle(make_vehicle(world, def)),
        estimator(def.state_noise, Rng::derive_seed(scene.world.seed, 0x5e57'0000ULL + index)),
        start(vehicle->state().position_m),
        previous(start),
        reached_at(def.mission.size()),
        reached_sample(def.mission.size()),
        record(planner_record(def.planner.name)) {
    // A planner's own metric that would overwrite another metric of run.json refuses the run before it starts.
    if (record) check_planner_metric_names(def.planner.name, *record, def);
    result.alias = def.alias;
    result.vehicle_parameters = vehicle->parameters();
  }

  bool running() const { return !outcome.has_value(); }

  const VehicleDef& def;
  const std::size_t index;
  const std::unique_ptr<Vehicle> vehicle;
  StateEstimator estimator;
  std::vector<MountedSensor> sensors;
  std::vector<SensorReading> readings;
  std::vector<MountedImu> imus;
  std::vector<ImuReading> imu_readings;
  std::vector<MountedCamera> cameras;
  std::vector<ImageReading> image_readings;
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
  double end_time_s = 0.0;
  VehicleState truth;  // at the current control tick
  Observation observation;
  VehicleResult result;
};

// Everything one run holds between control ticks; stepped only by Episode::step.
struct Episode::Loop {
  Loop(const Scene& scene_in, VehicleFactory make_vehicle, const EpisodeOptions& options_in)
      : scene(scene_in),
        options(options_in),
        dt(scene.world.physics_step_s),
        wall_start(Clock::now()),
        world(scene),
        control_period(period_steps(scene.world.control_rate_hz, dt)) {
    vehicles.reserve(scene.vehicles.size());
    for (std::size_t v = 0; v < scene.vehicles.size(); ++v) {
      vehicles.push_back(std::make_unique<VehicleLoop>(scene, v, world, make_vehicle));
    }
    // With one vehicle its sensors see the scene itself; with several, each
    // sees the others' bodies (and its own parked out of sight).
    if (vehicles.size() > 1) {
      seen_scene = std::make_unique<Scene>(sensor_scene(scene, world, proxy_first, proxy_count));
      separations.assign(vehicles.size() * vehicles.size(), VehicleSeparation{});
      pair_m.assign(vehicles.size() * vehicles.size(), kExact);
      pair_point.assign(vehicles.size() * vehicles.size(), Eigen::Vector3d::Zero());
    }
    const Scene& sensed = seen_scene ? *seen_scene : scene;
    for (auto& v : vehicles) {
      // Each vehicle's sensors draw their noise from their own streams; the first's are the single-vehicle run's.
      const std::uint64_t seed =
          v->index == 0 ? scene.world.seed : Rng::derive_seed(scene.world.seed, 0x5e45'0000ULL + v->index);
      v->sensors.reserve(v->def.sensors.size());
      for (const SensorDef& s : v->def.sensors) {
        const double rate = s.range.rate_hz > 0.0 ? s.range.rate_hz : scene.world.sensor_rate_hz;
        v->sensors.push_back({options.make_sensor(sensed, s, seed), std::make_shared<RangeScan>(), period_steps(rate, dt)});
      }
      v->readings.resize(v->sensors.size());
      for (std::size_t i = 0; i < v->sensors.size(); ++i) {
        v->readings[i] = {v->def.sensors[i].alias, &v->def.sensors[i].range, nullptr, false};
      }
      for (std::size_t i = 0; i < v->def.imus.size(); ++i) {
        const ImuDef& imu = v->def.imus[i];
        const std::int64_t period = period_steps(imu.imu.rate_hz > 0.0 ? imu.imu.rate_hz : scene.world.control_rate_hz, dt);
        const std::uint64_t stream = Rng::derive_seed(Rng::derive_seed(seed, 0x1a0'0000ULL + i), imu.imu.seed);
        v->imus.push_back({ImuErrorModel(imu.imu, static_cast<double>(period) * dt, stream), period, {}, false});
        v->imu_readings.push_back({imu.alias, &imu.imu});
      }
      if (!v->def.rgb_cameras.empty() && !options.make_camera) {
        throw std::invalid_argument("vehicle '" + v->def.alias + "' has a colour camera ('" +
                                    v->def.rgb_cameras.front().alias +
                                    "') but the episode has no camera factory (EpisodeOptions::make_camera)");
      }
      for (const RgbCameraDef& camera : v->def.rgb_cameras) {
        const double rate = camera.camera.rate_hz > 0.0 ? camera.camera.rate_hz : scene.world.sensor_rate_hz;
        v->cameras.push_back({options.make_camera(sensed, camera, seed), std::make_shared<RgbImage>(), period_steps(rate, dt)});
        v->image_readings.push_back({camera.alias, &camera.camera, nullptr, false});
      }
    }
  }

  bool all_ended() const {
    return std::none_of(vehicles.begin(), vehicles.end(), [](const auto& v) { return v->running(); });
  }

  // Sense: every sensor due at physics step k scans with every body where the physics has it now.
  void sense() {
    const double t = static_cast<double>(k) * dt;
    bool poses_read = false;
    for (auto& vp : vehicles) {
      VehicleLoop& v = *vp;
      if (!v.running()) continue;
      for (std::size_t i = 0; i < v.sensors.size(); ++i) {
        MountedSensor& s = v.sensors[i];
        if (k % s.period != 0) continue;
        if (!poses_read) read_body_poses();
        poses_read = true;
        // A vehicle's own bodies out of its own sight, for its scans only.
        const std::size_t first = seen_scene ? proxy_first[v.index] : 0;
        const std::size_t count = seen_scene ? proxy_count[v.index] : 0;
        for (std::size_t b = 0; b < count; ++b) std::swap(body_poses[first + b], parked[b]);
        s.sensor->scan(v.vehicle->state().pose() * to_isometry(v.def.sensors[i].range.mount), t, body_poses, *s.scan);
        for (std::size_t b = 0; b < count; ++b) std::swap(body_poses[first + b], parked[b]);
        v.readings[i].scan = s.scan;
        v.readings[i].fresh = true;
        if (options.on_scan) options.on_scan(v.index, i, *s.scan);
      }
      for (std::size_t i = 0; i < v.imus.size(); ++i) {
        MountedImu& imu = v.imus[i];
        if (k % imu.period != 0) continue;
        const VehicleState state = v.vehicle->state();
        const CarrierMotion now{state.orientation, state.linear_velocity_mps, state.angular_velocity_radps};
        // The first sample has no previous state: the carrier counts as unaccelerated.
        const CarrierMotion& before = imu.sampled ? imu.before : now;
        const ImuSample sample = imu.errors.corrupt(ideal_imu_sample(
            before, now, v.def.imus[i].imu.mount, static_cast<double>(imu.period) * dt, scene.world.gravity_mps2));
        ImuReading& reading = v.imu_readings[i];
        reading.time_s = t;
        reading.specific_force_mps2 = sample.specific_force_mps2;
        reading.angular_rate_radps = sample.angular_rate_radps;
        reading.valid = true;
        reading.fresh = true;
        imu.before = now;
        imu.sampled = true;
        if (options.on_imu) options.on_imu(v.index, i, reading);
      }
      for (std::size_t i = 0; i < v.cameras.size(); ++i) {
        MountedCamera& c = v.cameras[i];
        if (k % c.period != 0) continue;
        if (!poses_read) read_body_poses();
        poses_read = true;
        const std::size_t first = seen_scene ? proxy_first[v.index] : 0;
        const std::size_t count = seen_scene ? proxy_count[v.index] : 0;
        for (std::size_t b = 0; b < count; ++b) std::swap(body_poses[first + b], parked[b]);
        c.camera->render(v.vehicle->state().pose() * to_isometry(v.def.rgb_cameras[i].camera.mount), t, body_poses,
                         *c.image);
        for (std::size_t b = 0; b < count; ++b) std::swap(body_poses[first + b], parked[b]);
        v.image_readings[i].image = c.image;
        v.image_readings[i].fresh = true;
        if (options.on_image) options.on_image(v.index, i, *c.image);
      }
    }
  }

  void read_body_poses() {
    world.moving_body_poses(body_poses);
    if (!seen_scene) return;
    for (std::size_t v = 0; v < vehicles.size(); ++v) world.append_vehicle_poses(v, body_poses);
    std::size_t most = 0;
    for (const std::size_t c : proxy_count) most = std::max(most, c);
    parked.assign(most, kParked);
  }

  // The observation of a control tick, on the estimated state.
  void observe(VehicleLoop& v) {
    const double t = static_cast<double>(k) * dt;
    v.truth = v.vehicle->state();
    const StateError& error = v.estimator.error_at(t);
    v.vehicle->set_estimation_error(error);
    v.observation = Observation{t,          v.def.type,     estimated(v.truth, error), v.vehicle->stable(), v.readings,
                                v.def.mission, v.imu_readings, v.image_readings};
  }

  // The rest of a control tick, after the decision (the vehicle has taken its command): records it.
  void act(VehicleLoop& v, PlanResult plan, double planner_ms) {
    const double t = v.observation.time_s;
    if (options.on_plan) options.on_plan(v.index, v.observation, plan);
    for (auto& r : v.readings) r.fresh = false;
    for (auto& r : v.imu_readings) r.fresh = false;
    for (auto& r : v.image_readings) r.fresh = false;
    EpisodeMetrics& m = v.result.metrics;
    ++m.planner_calls;
    v.planner_ms_total += planner_ms;
    m.planner_time_ms_max = std::max(m.planner_time_ms_max, planner_ms);
    for (const int i : plan.decisions.reached_waypoints) {
      if (i >= 0 && static_cast<std::size_t>(i) < v.reached_at.size()) {
        v.reached_at[static_cast<std::size_t>(i)] = v.truth.position_m;
        v.reached_sample[static_cast<std::size_t>(i)] = v.result.trajectory.size();
      }
    }
    // Bounded as recorded (run/event_log.hpp): a scan's thousands of hits would otherwise make the record
    // grow with every scan; the metrics below read the same bounded decisions the files keep.
    if (!plan.decisions.empty()) v.result.events.push_back({t, bounded_decisions(std::move(plan.decisions))});
    // Exact obstacle clearance for the record; the ground only as far as
    // it could lower its minimum (far terrain costs many triangles).
    Clearance clearance = world.vehicle_clearance(v.index, kExact, v.minima.ground_cutoff(), !seen_scene);
    if (seen_scene) {
      // The pairs the last physics step measured exactly (the world has not moved since), then the rest
      // only where nearer than those.
      const std::size_t n = vehicles.size();
      if (k > 0) add_vehicle_pairs(v.index, clearance);
      for (std::size_t other = 0; other < n; ++other) {
        if (other == v.index || (k > 0 && pair_m[v.index * n + other] < kExact)) continue;
        const double d = world.vehicle_distance(v.index, other, clearance.obstacle_m);
        if (d < clearance.obstacle_m) {
          clearance.obstacle_m = d;
          clearance.obstacle = vehicle_tag(other, false);
        }
      }
    }
    v.minima.update(clearance, t);
    const std::optional<double> ground = scene.ground_height(v.truth.position_m.x(), v.truth.position_m.y());
    const double above_ground = ground ? v.truth.position_m.z() - *ground : std::numeric_limits<double>::quiet_NaN();
    v.result.trajectory.push_back({t, v.truth, v.observation.state.position_m, plan.command, clearance.obstacle_m,
                                   above_ground, v.vehicle->actuators()});
    if (plan.status == PlanStatus::reached) {
      end(v, Outcome::reached, plan.reason);
    } else if (plan.status != PlanStatus::running) {
      end(v, Outcome::aborted, std::string(to_string(plan.status)) + (plan.reason.empty() ? "" : ": " + plan.reason));
    }
  }

  // Actuate and step the physics once; then sense at the new step.
  void physics_step() {
    // Vehicles whose missions ended still hold where they are.
    for (auto& v : vehicles) v->vehicle->pre_step(dt);
    world.step();
    if (seen_scene) {
      measure_vehicle_pairs();
      keep_separations();
    }
    for (auto& vp : vehicles) {
      VehicleLoop& v = *vp;
      if (!v.running()) continue;
      EpisodeMetrics& m = v.result.metrics;
      const Eigen::Vector3d position = v.vehicle->state().position_m;
      m.path_length_m += (position - v.previous).norm();
      v.previous = position;
      // A collision is the collision shapes touching, from the same query as
      // the clearance metrics, so an overlap is always a collision.
      Clearance clearance =
          world.vehicle_clearance(v.index, v.minima.obstacle_cutoff(), v.minima.ground_cutoff(), !seen_scene);
      if (seen_scene) add_vehicle_pairs(v.index, clearance);
      v.minima.update(clearance, world.time_s());
      const bool colliding = clearance.touching();
      if (colliding && !v.was_colliding) {
        ++m.collisions;
        // Strings only here, when a collision begins: a step that touches nothing allocates nothing.
        CollisionEvent e;
        e.time_s = world.time_s();
        if (clearance.touch) {  // always set when touching (ClearanceQuery::measure)
          e.body = body_name(scene, clearance.touch->body);
          e.ground = clearance.touch->ground;
          e.point_m = clearance.touch->point_m;
        }
        if (options.stop_on_collision) end(v, Outcome::collision, collision_reason(e));
        if (m.collision_events.size() < EpisodeMetrics::kMaxCollisionEvents) m.collision_events.push_back(std::move(e));
      }
      v.was_colliding = colliding;
    }
    if (!all_ended() && world.time_s() >= scene.world.time_limit_s) {
      for (auto& v : vehicles) {
        if (v->running()) {
          end(*v, Outcome::timeout, "time limit of " + std::to_string(scene.world.time_limit_s) + " s reached");
        }
      }
    }
    ++k;
  }

  // The distance between each pair of vehicles, measured once for both
  // vehicles' clearance and least distances: exact below what either still
  // keeps (its least distance to the other, its clearance cutoff), +infinity beyond.
  void measure_vehicle_pairs() {
    const std::size_t n = vehicles.size();
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = a + 1; b < n; ++b) {
        double cutoff = -kExact;
        for (const auto& [self, other] : {std::pair{a, b}, std::pair{b, a}}) {
          const VehicleLoop& v = *vehicles[self];
          if (!v.running()) continue;
          cutoff = std::max({cutoff, separations[self * n + other].min_distance_m, v.minima.obstacle_cutoff()});
        }
        pair_m[a * n + b] = pair_m[b * n + a] =
            cutoff == -kExact ? kExact : world.vehicle_distance(a, b, cutoff, &pair_point[a * n + b]);
      }
    }
  }

  // The least distance to each other vehicle, kept while a vehicle is on its mission.
  void keep_separations() {
    const std::size_t n = vehicles.size();
    for (std::size_t a = 0; a < n; ++a) {
      if (!vehicles[a]->running()) continue;
      for (std::size_t b = 0; b < n; ++b) {
        VehicleSeparation& s = separations[a * n + b];
        if (b != a && pair_m[a * n + b] < s.min_distance_m) {
          s.min_distance_m = pair_m[a * n + b];
          s.min_distance_time_s = world.time_s();
        }
      }
    }
  }

  // The other vehicles into vehicle `self`'s clearance, from this step's pairs.
  void add_vehicle_pairs(std::size_t self, Clearance& c) const {
    const std::size_t n = vehicles.size();
    for (std::size_t other = 0; other < n; ++other) {
      const double d = pair_m[self * n + other];
      if (other == self || !(d < c.obstacle_m)) continue;
      c.obstacle_m = d;
      c.obstacle = vehicle_tag(other, false);
      if (d <= 0.0 && !c.touch) {  // overlapping without a contact Bullet reported: where, on the other
        Touch t;
        t.body = c.obstacle;
        if (self < other) {
          t.point_m = pair_point[self * n + other];
        } else {
          world.vehicle_distance(self, other, kExact, &t.point_m);
        }
        c.touch = t;
      }
    }
  }

  void end(VehicleLoop& v, Outcome o, std::string reason) {
    if (!v.running()) return;
    v.outcome = o;
    v.end_time_s = world.time_s();
    v.result.metrics.reason = std::move(reason);
    if (vehicles.size() > 1) {
      // It holds where it is from now on, a body the others must still avoid.
      try {
        v.vehicle->command(command::Hold{v.vehicle->state().position_m, std::nullopt});
      } catch (const std::invalid_argument&) {  // every vehicle follows Hold; kept as it was if not
      }
    }
    if (o != Outcome::reached && o != Outcome::stopped && scene.end == EndRule::first_failure) {
      for (auto& other : vehicles) {
        if (other->running()) end(*other, Outcome::stopped, "the run ended when " + v.def.alias + " ended (" +
                                                                std::string(to_string(o)) + ")");
      }
    }
  }

  // From physics step k (sensed): steps until the next control tick (observed) or the end.
  void advance_to_control_tick() {
    while (!all_ended()) {
      if (k % control_period == 0) {
        for (auto& v : vehicles) {
          if (v->running()) observe(*v);
        }
        return;
      }
      physics_step();
      if (!all_ended()) sense();
    }
  }

  void finish_vehicle(VehicleLoop& v) {
    EpisodeMetrics& m = v.result.metrics;
    m.outcome = *v.outcome;
    m.sim_time_s = v.end_time_s;
    v.minima.write(scene, m);
    // The nominal route: straight legs from the start through every waypoint
    // (for a single goal, the straight start-goal line), each waypoint taken
    // where the vehicle was when it was reached (within the arrival
    // tolerance), so the path flown, which passes through those points, is
    // never shorter than the route: the ratio of a reached run is at least 1.
    if (m.outcome == Outcome::reached && !v.def.mission.empty()) v.reached_at.back() = v.previous;
    m.path_ratio = path_ratio(m.path_length_m, nominal_route_m(v.def.type, v.start, v.def.mission, v.reached_at));
    count_decisions(v.result.events, m);
    const CrossTrack cross_track = cross_track_error(v.result.trajectory, v.result.events);
    m.cross_track_rms_m = cross_track.rms_m;
    m.cross_track_mean_m = cross_track.mean_m;
    m.cross_track_max_m = cross_track.max_m;
    m.avoiding_time_s = avoiding_time(v.result.events, m.sim_time_s);
    write_mission_metrics(v.def, v.start, v.result.trajectory, v.reached_sample, m.declared);
    if (v.record) write_planner_metrics(v.def.planner.name, *v.record, {v.result.events, m.sim_time_s}, m.declared);
    m.planner_time_ms_mean = m.planner_calls > 0 ? v.planner_ms_total / m.planner_calls : 0.0;
    m.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
    if (seen_scene) {
      const std::size_t n = vehicles.size();
      for (std::size_t other = 0; other < n; ++other) {
        if (other == v.index) continue;
        VehicleSeparation s = separations[v.index * n + other];
        s.other = vehicles[other]->def.alias;
        m.separations.push_back(std::move(s));
      }
    }
  }

  FleetMetrics fleet_metrics(const EpisodeResult& result) const {
    FleetMetrics r;
    r.vehicles = static_cast<int>(vehicles.size());
    r.sim_time_s = world.time_s();
    r.outcome = Outcome::reached;
    double decided_at = kExact;
    double last_reached = 0.0;
    for (std::size_t i = 0; i < vehicles.size(); ++i) {
      const EpisodeMetrics& m = result.vehicles[i].metrics;
      r.collisions += m.collisions;
      if (m.outcome == Outcome::reached) {
        ++r.vehicles_reached;
        last_reached = std::max(last_reached, m.sim_time_s);
      } else if (m.outcome != Outcome::stopped && m.sim_time_s < decided_at) {
        decided_at = m.sim_time_s;
        r.outcome = m.outcome;
        r.reason = vehicles[i]->def.alias + ": " + m.reason;
      }
      for (const VehicleSeparation& s : m.separations) {
        if (s.min_distance_m < r.min_vehicle_distance_m) {
          r.min_vehicle_distance_m = s.min_distance_m;
          r.min_vehicle_distance_pair = vehicles[i]->def.alias + "|" + s.other;
          r.min_vehicle_distance_time_s = s.min_distance_time_s;
        }
      }
    }
    r.all_reached = r.vehicles_reached == r.vehicles;
    r.any_collision = r.collisions > 0;
    if (r.all_reached) {
      r.makespan_s = last_reached;
      r.reason = "all " + std::to_string(r.vehicles) + " vehicles reached their goals";
    }
    r.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
    return r;
  }

  EpisodeResult finish() {
    EpisodeResult result;
    for (auto& v : vehicles) {
      finish_vehicle(*v);
      result.vehicles.push_back(std::move(v->result));
    }
    result.fleet = fleet_metrics(result);
    result.final_state_hash = world.state_hash();
    world.moving_body_poses(result.final_body_poses);
    return result;
  }

  const Scene& scene;
  const EpisodeOptions options;
  const double dt;
  const Clock::time_point wall_start;
  World world;
  std::vector<std::unique_ptr<VehicleLoop>> vehicles;  // scene order; destroyed before the world
  // With several vehicles: the scene the sensors see (the vehicles' bodies
  // added as movers), where each vehicle's bodies start among its moving
  // bodies and how many; the least distance of each ordered pair (a * n +
  // b); this step's distance of each pair and the point of b nearest a (a < b).
  std::unique_ptr<Scene> seen_scene;
  std::vector<std::size_t> proxy_first;
  std::vector<std::size_t> proxy_count;
  std::vector<VehicleSeparation> separations;
  std::vector<double> pair_m;
  std::vector<Eigen::Vector3d> pair_point;
  std::vector<Eigen::Isometry3d> body_poses;  // of the moving bodies, refreshed before each scan
  std::vector<Eigen::Isometry3d> parked;      // kParked, swapped in for a vehicle's own bodies
  const std::int64_t control_period;
  std::int64_t k = 0;  // physics steps taken
  bool finished = false;
};

VehicleResult& EpisodeResult::only() {
  if (vehicles.size() != 1) {
    throw std::logic_error("EpisodeResult::only: the run has " + std::to_string(vehicles.size()) + " vehicles");
  }
  return vehicles.front();
}

const VehicleResult& EpisodeResult::only() const { return const_cast<EpisodeResult&>(*this).only(); }

Episode::Episode(const Scene& scene, VehicleFactory make_vehicle, const EpisodeOptions& options) {
  if (scene.vehicles.empty()) throw std::invalid_argument("scene " + scene.name + " has no vehicle");
  loop_ = std::make_unique<Loop>(scene, make_vehicle, options);
  loop_->sense();
  loop_->advance_to_control_tick();
}

Episode::~Episode() = default;
Episode::Episode(Episode&&) noexcept = default;
Episode& Episode::operator=(Episode&&) noexcept = default;

std::size_t Episode::vehicle_count() const { return loop_->vehicles.size(); }

bool Episode::done() const { return loop_->all_ended(); }

bool Episode::done(std::size_t vehicle) const { return !loop_->vehicles.at(vehicle)->running(); }

std::optional<Outcome> Episode::outcome(std::size_t vehicle) const { return loop_->vehicles.at(vehicle)->outcome; }

double Episode::end_time_s(std::size_t vehicle) const { return loop_->vehicles.at(vehicle)->end_time_s; }

const Observation& Episode::observation(std::size_t vehicle) const { return loop_->vehicles.at(vehicle)->observation; }

void Episode::step(std::vector<PlanResult>&& plans, const std::vector<double>& planner_time_ms) {
  if (done()) throw std::logic_error("Episode::step: the episode has ended");
  const std::size_t n = loop_->vehicles.size();
  if (plans.size() != n || (!planner_time_ms.empty() && planner_time_ms.size() != n)) {
    throw std::invalid_argument("Episode::step: expected one decision (and time) per vehicle, " + std::to_string(n));
  }
  // Every command first, so one a vehicle cannot follow leaves nothing recorded or stepped.
  std::vector<bool> taken(n, false);
  for (std::size_t v = 0; v < n; ++v) {
    VehicleLoop& loop = *loop_->vehicles[v];
    if (!loop.running()) continue;
    try {
      loop.vehicle->command(plans[v].command);
      taken[v] = true;
    } catch (const std::invalid_argument& e) {
      // The vehicles that took theirs go back to the one they had.
      for (std::size_t u = 0; u < v; ++u) {
        if (taken[u] && !loop_->vehicles[u]->result.trajectory.empty()) {
          loop_->vehicles[u]->vehicle->command(loop_->vehicles[u]->result.trajectory.back().command);
        }
      }
      throw VehicleCommandError(v, n > 1 ? loop.def.alias + ": " + e.what() : std::string(e.what()));
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (taken[v]) loop_->act(*loop_->vehicles[v], std::move(plans[v]), planner_time_ms.empty() ? 0.0 : planner_time_ms[v]);
  }
  if (!done()) {
    loop_->physics_step();
    if (!done()) loop_->sense();
    loop_->advance_to_control_tick();
  }
  // A mission's end as a caller stepping from outside sees it: the state it ended in.
  for (std::size_t v = 0; v < n; ++v) {
    if (taken[v] && !loop_->vehicles[v]->running()) loop_->observe(*loop_->vehicles[v]);
  }
}

void Episode::step(PlanResult plan, double planner_time_ms) {
  if (loop_->vehicles.size() != 1) {
    throw std::logic_error("Episode::step: the scene has " + std::to_string(loop_->vehicles.size()) +
                           " vehicles; give one decision per vehicle");
  }
  std::vector<PlanResult> plans;
  plans.push_back(std::move(plan));
  step(std::move(plans), std::vector<double>{planner_time_ms});
}

void Episode::fail(std::size_t vehicle, std::string reason) {
  loop_->end(*loop_->vehicles.at(vehicle), Outcome::failed, std::move(reason));
}

void Episode::fail(std::string reason) {
  for (auto& v : loop_->vehicles) loop_->end(*v, Outcome::failed, reason);
}

const Vehicle& Episode::vehicle(std::size_t vehicle) const { return *loop_->vehicles.at(vehicle)->vehicle; }

const World& Episode::world() const { return loop_->world; }

const EpisodeMetrics& Episode::metrics_so_far(std::size_t vehicle) const {
  return loop_->vehicles.at(vehicle)->result.metrics;
}

EpisodeResult Episode::finish() {
  if (!done()) throw std::logic_error("Episode::finish: the episode has not ended");
  if (loop_->finished) throw std::logic_error("Episode::finish: called twice");
  loop_->finished = true;
  return loop_->finish();
}

EpisodeResult run_episode(const Scene& scene, VehicleFactory make_vehicle, const PlannerMaker& make_planner,
                          const EpisodeOptions& options) {
  Episode episode(scene, make_vehicle, options);
  const std::size_t n = scene.vehicles.size();
  std::vector<std::unique_ptr<Planner>> planners;
  std::vector<nlohmann::json> planner_parameters;
  for (const VehicleDef& def : scene.vehicles) {
    planners.push_back(make_planner(def.planner, {def.type, &scene, &def}));
    planner_parameters.push_back(planners.back()->parameters());
  }
  std::vector<PlanResult> plans(n);
  std::vector<double> ms(n, 0.0);
  while (!episode.done()) {
    for (std::size_t v = 0; v < n; ++v) {
      plans[v] = PlanResult{};
      ms[v] = 0.0;
      if (episode.done(v)) continue;
      const auto plan_start = Clock::now();
      try {
        plans[v] = planners[v]->plan(episode.observation(v));
      } catch (const InputError&) {
        throw;  // bad input stays bad input (exit 2), whoever finds it
      } catch (const std::exception& e) {
        // A planner that fails ends its vehicle's mission, recorded as failed with what it said; nothing is lost.
        episode.fail(v, std::string("the planner raised an error: ") + e.what());
        continue;
      }
      ms[v] = std::chrono::duration<double, std::milli>(Clock::now() - plan_start).count();
    }
    if (episode.done()) break;
    for (;;) {
      try {
        episode.step(std::move(plans), ms);  // left as given when it throws
        break;
      } catch (const VehicleCommandError& e) {
        episode.fail(e.vehicle(), std::string("the planner gave a command the vehicle cannot follow: ") + e.what());
        if (episode.done()) break;
      }
    }
  }
  EpisodeResult result = episode.finish();
  for (std::size_t v = 0; v < n; ++v) result.vehicles[v].planner_parameters = planner_parameters[v];
  return result;
}

}  // namespace campo
