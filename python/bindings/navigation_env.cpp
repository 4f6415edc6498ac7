#include "python/bindings/navigation_env.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "campo/planner_registry.hpp"
#include "campo/vehicle_factory.hpp"
#include "sweep/bundled.hpp"
#include "vehicles/quadrotor.hpp"
#include "vehicles/rover.hpp"

namespace campo::gym {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
// What the driven vehicle records as its planner.
constexpr const char* kDriver = "gym";

struct ModeName {
  ActionMode mode;
  std::string_view name;
};
constexpr std::array<ModeName, 6> kModeNames{{{ActionMode::waypoint, "waypoint"},
                                              {ActionMode::velocity, "velocity"},
                                              {ActionMode::attitude_thrust, "attitude_thrust"},
                                              {ActionMode::rotors, "rotors"},
                                              {ActionMode::twist, "twist"},
                                              {ActionMode::wheels, "wheels"}}};

// An action component clipped to [-1, 1] (a NaN, which no clip makes meaningful, is refused by the vehicle).
double unit(float a) { return std::isnan(a) ? std::numeric_limits<double>::quiet_NaN() : std::clamp<double>(a, -1.0, 1.0); }

// [-1, 1] onto [lo, hi].
double span(float a, double lo, double hi) { return lo + 0.5 * (unit(a) + 1.0) * (hi - lo); }

// The heading frame's rotation (yaw about world z) of `state`.
Eigen::Matrix3d heading_frame(const VehicleState& state) {
  return Eigen::AngleAxisd(state.yaw_rad(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

void put(float* out, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(v[i]);
}

}  // namespace

std::string_view to_string(ActionMode mode) {
  for (const ModeName& m : kModeNames) {
    if (m.mode == mode) return m.name;
  }
  return "?";
}

ActionMode action_mode(std::string_view name) {
  std::string names;
  for (const ModeName& m : kModeNames) {
    if (m.name == name) return m.mode;
    names += (names.empty() ? "" : ", ") + std::string(m.name);
  }
  throw std::invalid_argument("unknown action mode \"" + std::string(name) + "\": expected one of " + names);
}

std::vector<ActionMode> action_modes(VehicleType type) {
  if (type == VehicleType::rover) return {ActionMode::waypoint, ActionMode::twist, ActionMode::wheels};
  return {ActionMode::waypoint, ActionMode::velocity, ActionMode::attitude_thrust, ActionMode::rotors};
}

bool is_low_level(ActionMode mode) {
  return mode == ActionMode::attitude_thrust || mode == ActionMode::rotors || mode == ActionMode::wheels;
}

double reward(const RewardWeights& w, const RewardTerms& t) {
  return w.progress_weight * t.progress_m + (t.reached ? w.goal_reward : 0.0) -
         (t.collided ? w.collision_penalty : 0.0) - w.time_penalty_per_s * t.dt_s;
}

NavigationEnv::NavigationEnv(const std::string& scene, const std::vector<SceneOverride>& overrides,
                             const NavigationOptions& options)
    : options_(options) {
  request_.scene = file_or_bundled(scene, &bundled_scene);
  request_.overrides = overrides;
  request_.vehicle = options.vehicle;
  prepared_ = prepare_run(request_, false);
  vehicle_index_ = prepared_.vehicle_index;
  const Scene& s = prepared_.scene;
  const VehicleDef& def = s.vehicles.at(vehicle_index_);
  const std::vector<ActionMode> modes = action_modes(def.type);
  if (std::find(modes.begin(), modes.end(), options.action_mode) == modes.end()) {
    std::string names;
    for (const ActionMode m : modes) names += (names.empty() ? "" : ", ") + std::string(to_string(m));
    throw InputError("action_mode", "", "a mode of the " + std::string(to_string(def.type)) + " \"" + def.alias +
                                            "\" (" + names + "), got \"" + std::string(to_string(options.action_mode)) +
                                            "\"");
  }
  auto positive = [](double value, const char* name) {
    if (!(value > 0.0) || !std::isfinite(value)) throw InputError(name, "", "a finite number > 0");
  };
  positive(options.goal_radius_m, "goal_radius_m");
  positive(options.waypoint_range_m, "waypoint_range_m");
  positive(options.waypoint_speed_mps, "waypoint_speed_mps");
  positive(options.max_speed_mps, "max_speed_mps");
  positive(options.max_yaw_rate_radps, "max_yaw_rate_radps");
  if (options.ticks_per_step < 0) throw InputError("ticks_per_step", "", "a whole number >= 0 (0: by the action mode)");
  if (def.mission.empty()) throw InputError(s.source_path, def.params.pointer, "a mission: the environment's goal");
  // The others fly their scene's planners, in the worker threads of a vector environment: not Python ones.
  for (std::size_t v = 0; v < s.vehicles.size(); ++v) {
    if (v == vehicle_index_) continue;
    const VehicleDef& other = s.vehicles[v];
    if (other.planner.name.starts_with("python")) {
      throw InputError(s.source_path, other.planner.name_pointer,
                       "a C++ planner for vehicle \"" + other.alias + "\": the environment steps it without the "
                       "Python interpreter");
    }
    create_planner(other.planner, {other.type, &s, &other});  // checks its parameters now
  }
  for (const SensorDef& sensor : def.sensors) {
    sensors_.push_back({sensor.alias + "_ranges_m", sensor.range.scan_rows(), sensor.range.scan_cols(),
                        sensor.range.max_range_m});
  }
  for (const RgbCameraDef& camera : def.rgb_cameras) {
    cameras_.push_back({camera.alias + "_rgb", camera.camera.rows, camera.camera.cols});
  }
  for (const ImuDef& imu : def.imus) imus_.push_back({imu.alias + "_imu"});
  const std::int64_t control = steps_per_period(s.world.control_rate_hz, s.world.physics_step_s);
  const std::int64_t sensing = steps_per_period(s.world.sensor_rate_hz, s.world.physics_step_s);
  ticks_per_step_ = options.ticks_per_step > 0 ? options.ticks_per_step
                    : is_low_level(options.action_mode) ? 1
                                                        : static_cast<int>(std::max<std::int64_t>(1, sensing / control));
  // The ranges the actions scale to, from the vehicle's effective parameters.
  if (def.type == VehicleType::quadrotor) {
    const QuadrotorConfig q = parse_quadrotor_config(def.params);
    rotor_range_radps_ = {q.min_rotor_speed_radps, q.max_rotor_speed_radps};
    max_thrust_n_ = 4.0 * q.thrust_coefficient * q.max_rotor_speed_radps * q.max_rotor_speed_radps;
    max_tilt_rad_ = q.controller.max_tilt_deg * kDegToRad;
  } else {
    max_wheel_speed_radps_ = parse_rover_config(def.params).max_wheel_speed_radps;
  }
}

NavigationEnv::~NavigationEnv() = default;
NavigationEnv::NavigationEnv(NavigationEnv&&) noexcept = default;
NavigationEnv& NavigationEnv::operator=(NavigationEnv&&) noexcept = default;

VehicleType NavigationEnv::vehicle_type() const { return prepared_.scene.vehicles.at(vehicle_index_).type; }
const std::string& NavigationEnv::vehicle_alias() const { return prepared_.scene.vehicles.at(vehicle_index_).alias; }

int NavigationEnv::action_size() const {
  switch (options_.action_mode) {
    case ActionMode::waypoint: return vehicle_type() == VehicleType::rover ? 2 : 3;
    case ActionMode::velocity:
    case ActionMode::attitude_thrust:
    case ActionMode::rotors:
    case ActionMode::wheels: return 4;
    case ActionMode::twist: return 2;
  }
  return 0;
}

std::vector<std::string> NavigationEnv::action_names() const {
  switch (options_.action_mode) {
    case ActionMode::waypoint:
      if (vehicle_type() == VehicleType::rover) return {"forward_m", "left_m"};
      return {"forward_m", "left_m", "up_m"};
    case ActionMode::velocity: return {"forward_mps", "left_mps", "up_mps", "yaw_rate_radps"};
    case ActionMode::attitude_thrust: return {"roll_rad", "pitch_rad", "yaw_rate_radps", "thrust_n"};
    case ActionMode::rotors: return {"rotor0_radps", "rotor1_radps", "rotor2_radps", "rotor3_radps"};
    case ActionMode::twist: return {"v_mps", "w_radps"};
    case ActionMode::wheels:
      return {"front_left_radps", "front_right_radps", "rear_left_radps", "rear_right_radps"};
  }
  return {};
}

double NavigationEnv::step_s() const { return ticks_per_step_ / prepared_.scene.world.control_rate_hz; }

const Scene& NavigationEnv::scene() const { return episode_scene_ ? episode_scene_->scene : prepared_.scene; }

const Episode& NavigationEnv::episode() const {
  if (!episode_) throw std::logic_error("call reset() first");
  return *episode_;
}

bool NavigationEnv::done() const { return episode().done(vehicle_index_); }

Eigen::Isometry3d NavigationEnv::vehicle_pose() const { return episode().vehicle(vehicle_index_).state().pose(); }

void NavigationEnv::reset(std::optional<std::uint64_t> seed, const std::vector<SceneOverride>& overrides) {
  if (seed) rng_ = Rng(*seed);
  const std::uint64_t world_seed = static_cast<std::uint64_t>(rng_.uniform_int(0, std::numeric_limits<std::int64_t>::max()));
  episode_.reset();  // before the scene it refers to changes
  if (overrides.empty()) {
    episode_scene_.reset();
  } else {
    RunRequest request = request_;
    request.overrides.insert(request.overrides.end(), overrides.begin(), overrides.end());
    episode_scene_ = prepare_run(request, false);
  }
  PreparedRun& run = episode_scene_ ? *episode_scene_ : prepared_;
  run.scene.world.seed = world_seed;
  VehicleDef& driven = run.scene.vehicles.at(vehicle_index_);
  driven.planner.name = kDriver;
  driven.planner.params.values = nlohmann::json::object();
  episode_.emplace(run.scene, &make_vehicle, run.options);
  // The others' planners, made as run_episode makes them (after the world).
  planners_.clear();
  for (std::size_t v = 0; v < run.scene.vehicles.size(); ++v) {
    const VehicleDef& def = run.scene.vehicles[v];
    planners_.push_back(v == vehicle_index_ ? nullptr : create_planner(def.planner, {def.type, &run.scene, &def}));
  }
  waypoint_ = 0;
  trajectory_m_.assign(1, episode_->vehicle(vehicle_index_).state().position_m);
}

Command NavigationEnv::command_of(const float* a) const {
  const VehicleState state = episode_->observation(vehicle_index_).state;
  const Eigen::Matrix3d heading = heading_frame(state);
  const NavigationOptions& o = options_;
  switch (o.action_mode) {
    case ActionMode::waypoint: {
      const bool rover = vehicle_type() == VehicleType::rover;
      const Eigen::Vector3d offset(unit(a[0]), unit(a[1]), rover ? 0.0 : unit(a[2]));
      return command::GoTo{state.position_m + heading * (o.waypoint_range_m * offset), o.waypoint_speed_mps, true};
    }
    case ActionMode::velocity:
      return command::Velocity{o.max_speed_mps * Eigen::Vector3d(unit(a[0]), unit(a[1]), unit(a[2])),
                               o.max_yaw_rate_radps * unit(a[3])};
    case ActionMode::attitude_thrust:
      return command::AttitudeThrust{max_tilt_rad_ * unit(a[0]), max_tilt_rad_ * unit(a[1]),
                                     o.max_yaw_rate_radps * unit(a[2]), span(a[3], 0.0, max_thrust_n_)};
    case ActionMode::rotors: {
      command::Rotors rotors;
      for (std::size_t i = 0; i < 4; ++i) rotors.speeds_radps[i] = span(a[i], rotor_range_radps_[0], rotor_range_radps_[1]);
      return rotors;
    }
    case ActionMode::twist: return command::Twist{o.max_speed_mps * unit(a[0]), o.max_yaw_rate_radps * unit(a[1])};
    case ActionMode::wheels: {
      command::Wheels wheels;
      for (std::size_t i = 0; i < 4; ++i) wheels.speeds_radps[i] = max_wheel_speed_radps_ * unit(a[i]);
      return wheels;
    }
  }
  throw std::logic_error("unknown action mode");
}

double NavigationEnv::distance_to_waypoint() const {
  const std::vector<Waypoint>& mission = scene().vehicles.at(vehicle_index_).mission;
  const Eigen::Vector3d position = episode_->vehicle(vehicle_index_).state().position_m;
  if (waypoint_ >= mission.size()) return std::numeric_limits<double>::infinity();
  Eigen::Vector3d d = mission[waypoint_].position_m - position;
  if (vehicle_type() == VehicleType::rover) d.z() = 0.0;  // a rover's waypoints are on the ground plane
  return d.norm();
}

void NavigationEnv::advance(PlanResult driven) {
  Episode& e = *episode_;
  const std::size_t n = e.vehicle_count();
  std::vector<PlanResult> plans(n);
  for (std::size_t v = 0; v < n; ++v) {
    if (v == vehicle_index_ || e.done(v)) continue;
    try {
      plans[v] = planners_[v]->plan(e.observation(v));
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& error) {
      e.fail(v, std::string("the planner raised an error: ") + error.what());
    }
  }
  plans[vehicle_index_] = std::move(driven);
  while (!e.done()) {
    try {
      e.step(std::vector<PlanResult>(plans));
      return;
    } catch (const VehicleCommandError& error) {
      if (error.vehicle() == vehicle_index_) throw std::invalid_argument(std::string("action: ") + error.what());
      e.fail(error.vehicle(), std::string("the planner gave a command the vehicle cannot follow: ") + error.what());
    }
  }
}

StepOutcome NavigationEnv::step(const float* action) {
  if (done()) throw std::logic_error("the episode has ended: call reset() for a new one");
  Episode& e = *episode_;
  const std::vector<Waypoint>& mission = scene().vehicles.at(vehicle_index_).mission;
  PlanResult decision;
  decision.command = command_of(action);
  StepOutcome out;
  const double start_s = e.world().time_s();
  const int start_collisions = e.metrics_so_far(vehicle_index_).collisions;
  double reference_m = distance_to_waypoint();  // to the current waypoint, where the progress counts from
  for (int tick = 0; tick < ticks_per_step_ && !done(); ++tick) {
    advance(decision);
    trajectory_m_.push_back(e.vehicle(vehicle_index_).state().position_m);
    if (done()) break;
    // Waypoints reached on the way; the last one ends the mission, recorded as reached at this tick.
    while (distance_to_waypoint() <= options_.goal_radius_m) {
      out.terms.progress_m += reference_m - distance_to_waypoint();
      ++waypoint_;
      if (waypoint_ == mission.size()) {
        PlanResult reached;
        reached.status = PlanStatus::reached;
        reached.reason = "within goal_radius_m of the last waypoint";
        reached.decisions.reached_waypoints = {static_cast<int>(waypoint_ - 1)};
        reached.command = command::Hold{e.vehicle(vehicle_index_).state().position_m, std::nullopt};
        advance(std::move(reached));
        out.terms.reached = true;
        break;
      }
      reference_m = distance_to_waypoint();
    }
  }
  if (!out.terms.reached) out.terms.progress_m += reference_m - distance_to_waypoint();
  out.terms.collided = e.metrics_so_far(vehicle_index_).collisions > start_collisions;
  out.time_s = e.done(vehicle_index_) && e.end_time_s(vehicle_index_) > 0.0 ? e.end_time_s(vehicle_index_)
                                                                             : e.world().time_s();
  out.terms.dt_s = out.time_s - start_s;
  out.reward = reward(options_.reward, out.terms);
  out.waypoint = static_cast<int>(waypoint_);
  out.outcome = e.outcome(vehicle_index_);
  if (out.outcome) {
    // The time limit, or another vehicle's failure ending the run, cut the episode short: truncated.
    out.truncated = *out.outcome == Outcome::timeout || *out.outcome == Outcome::stopped;
    out.terminated = !out.truncated;
  }
  return out;
}

void NavigationEnv::write_observation(const ObservationBuffers& out) const {
  const Observation& o = episode().observation(vehicle_index_);
  const VehicleState& s = o.state;
  const Eigen::Matrix3d to_body = s.orientation.conjugate().toRotationMatrix();
  put(out.state[0], s.position_m);
  out.state[1][0] = static_cast<float>(s.orientation.w());
  out.state[1][1] = static_cast<float>(s.orientation.x());
  out.state[1][2] = static_cast<float>(s.orientation.y());
  out.state[1][3] = static_cast<float>(s.orientation.z());
  put(out.state[2], to_body * s.linear_velocity_mps);
  put(out.state[3], to_body * s.angular_velocity_radps);
  const std::vector<Waypoint>& mission = scene().vehicles.at(vehicle_index_).mission;
  const Eigen::Vector3d goal = mission.at(std::min(waypoint_, mission.size() - 1)).position_m;
  put(out.state[4], to_body * (goal - s.position_m));
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    float* image = out.sensors.at(i);
    const std::size_t n = static_cast<std::size_t>(sensors_[i].rows) * static_cast<std::size_t>(sensors_[i].cols);
    const RangeScan* scan = i < o.sensors.size() ? o.sensors[i].scan.get() : nullptr;
    if (scan && scan->ranges_m.size() == n) {
      // Within the space's bounds: range noise may carry a reading past max_range_m or below 0.
      const auto max_range = static_cast<float>(sensors_[i].max_range_m);
      std::transform(scan->ranges_m.begin(), scan->ranges_m.end(), image,
                     [max_range](float r) { return std::clamp(r, 0.0f, max_range); });
    } else {
      std::fill(image, image + n, static_cast<float>(sensors_[i].max_range_m));  // nothing seen yet
    }
  }
  for (std::size_t i = 0; i < cameras_.size(); ++i) {
    std::uint8_t* pixels = out.cameras.at(i);
    const std::size_t n = static_cast<std::size_t>(cameras_[i].rows) * static_cast<std::size_t>(cameras_[i].cols) * 3;
    const RgbImage* image = i < o.images.size() ? o.images[i].image.get() : nullptr;
    if (image && image->rgb.size() == n) {
      std::copy(image->rgb.begin(), image->rgb.end(), pixels);
    } else {
      std::fill(pixels, pixels + n, std::uint8_t{0});  // nothing seen yet: black
    }
  }
  for (std::size_t i = 0; i < imus_.size(); ++i) {
    float* sample = out.imus.at(i);
    const ImuReading* reading = i < o.imus.size() && o.imus[i].valid ? &o.imus[i] : nullptr;
    for (int axis = 0; axis < 3; ++axis) {
      sample[axis] = reading ? static_cast<float>(reading->specific_force_mps2[axis]) : 0.0f;
      sample[3 + axis] = reading ? static_cast<float>(reading->angular_rate_radps[axis]) : 0.0f;
    }
  }
}

}  // namespace campo::gym
