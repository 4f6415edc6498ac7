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
#include "run/event_log.hpp"
#include "run/route_metrics.hpp"

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
  std::shared_ptr<LidarScan> scan;  // shared with the readings (SensorReading::scan)
  std::int64_t period;
};

// The per-leg and gate metrics (run/route_metrics.hpp) from the trajectory
// samples; `reached_sample[k]` is the sample at which waypoint k was reported reached.
void route_metrics(const VehicleDef& def, const Eigen::Vector3d& start, const std::vector<TrajectorySample>& trajectory,
                   const std::vector<std::optional<std::size_t>>& reached_sample, EpisodeMetrics& m) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> agl_m;
  for (const TrajectorySample& s : trajectory) {
    points.push_back(s.state.position_m);
    agl_m.push_back(s.height_above_ground_m);
  }
  const std::span<const Eigen::Vector3d> all(points);
  for (std::size_t k = 0; k < def.mission.size(); ++k) {
    LegMetrics& leg = m.legs.emplace_back();
    const std::optional<std::size_t> first = k == 0 ? std::optional<std::size_t>(0) : reached_sample[k - 1];
    const std::optional<std::size_t> last = reached_sample[k];
    if (!first || !last || *last < *first || *last >= points.size()) continue;
    const auto flown = all.subspan(*first, *last - *first + 1);
    leg.path_length_m = polyline_length_m(flown);
    const Eigen::Vector3d from = k == 0 ? start : def.mission[k - 1].position_m;
    leg.lateral_before_climb_m = lateral_before_climb_m(flown, from, def.mission[k].position_m);
  }
  for (const MissionGate& gate : def.gates) {
    GateMetrics& g = m.gates.emplace_back();
    g.name = gate.name;
    if (const auto i = first_inside(points, agl_m, gate.area_m, gate.max_agl_m)) g.time_s = trajectory[*i].time_s;
  }
}

// Counts the planner's decisions into the metrics.
void count_decisions(const std::vector<PlannerEvent>& events, EpisodeMetrics& m) {
  std::vector<double> replan_ms;
  for (const PlannerEvent& e : events) {
    m.waypoints_planned += e.decisions.planned_waypoint.has_value();
    m.waypoints_reached += e.decisions.reached_intermediate.has_value();
    m.waypoints_discarded += e.decisions.discarded_waypoint.has_value();
    if (e.decisions.replan) replan_ms.push_back(e.decisions.replan->time_ms);
  }
  m.replans = static_cast<int>(replan_ms.size());
  if (replan_ms.empty()) return;
  std::sort(replan_ms.begin(), replan_ms.end());
  const std::size_t n = replan_ms.size();
  m.replan_time_ms_median = n % 2 ? replan_ms[n / 2] : 0.5 * (replan_ms[n / 2 - 1] + replan_ms[n / 2]);
  m.replan_time_ms_max = replan_ms.back();
}

// Exact horizontal distance to a polyline, in about log time per query: a
// binary tree of bounding boxes over halves of the segment index range (a
// route is spatially coherent, so consecutive segments make tight boxes),
// searched branch and bound starting from the previous query's nearest
// segment, which successive trajectory samples mostly share.
class RouteDistance {
 public:
  explicit RouteDistance(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
    if (points_.size() == 1) points_.push_back(points_.front());  // one point: a zero-length segment
    nodes_.reserve(2 * (points_.size() - 1) / kLeafSegments + 2);
    build(0, points_.size() - 1);
  }

  double squared_distance(const Eigen::Vector2d& q) {
    double best = segment_squared_distance(q, hint_);
    std::vector<std::size_t>& stack = stack_;
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      if (box_squared_distance(q, node.box) >= best) continue;
      if (node.left == kNone) {
        for (std::size_t s = node.first; s < node.last; ++s) {
          const double d = segment_squared_distance(q, s);
          if (d < best) {
            best = d;
            hint_ = s;
          }
        }
        continue;
      }
      // The nearer child last, so that it is searched first.
      const double l = box_squared_distance(q, nodes_[node.left].box);
      const double r = box_squared_distance(q, nodes_[node.right].box);
      const std::size_t left = node.left, right = node.right;
      if (l < r) {
        stack.push_back(right);
        stack.push_back(left);
      } else {
        stack.push_back(left);
        stack.push_back(right);
      }
    }
    return best;
  }

 private:
  static constexpr std::size_t kLeafSegments = 8;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  struct Node {
    Eigen::AlignedBox2d box;
    std::size_t first = 0, last = 0;  // segments [first, last)
    std::size_t left = kNone, right = kNone;
  };

  // Builds the node of segments [first, last) and returns its index.
  std::size_t build(std::size_t first, std::size_t last) {
    const std::size_t index = nodes_.size();
    nodes_.push_back({Eigen::AlignedBox2d(), first, last, kNone, kNone});
    if (last - first <= kLeafSegments) {
      Eigen::AlignedBox2d box;
      for (std::size_t i = first; i <= last; ++i) box.extend(points_[i]);
      nodes_[index].box = box;
      return index;
    }
    const std::size_t middle = first + (last - first) / 2;
    const std::size_t left = build(first, middle);
    const std::size_t right = build(middle, last);
    nodes_[index].left = left;
    nodes_[index].right = right;
    nodes_[index].box = nodes_[left].box.merged(nodes_[right].box);
    return index;
  }

  double segment_squared_distance(const Eigen::Vector2d& q, std::size_t s) const {
    const Eigen::Vector2d& a = points_[s];
    const Eigen::Vector2d d = points_[s + 1] - a;
    const double length2 = d.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((q - a).dot(d) / length2, 0.0, 1.0) : 0.0;
    return (a + t * d - q).squaredNorm();
  }

  static double box_squared_distance(const Eigen::Vector2d& q, const Eigen::AlignedBox2d& box) {
    const Eigen::Vector2d outside = (box.min() - q).cwiseMax(q - box.max()).cwiseMax(0.0);
    return outside.squaredNorm();
  }

  std::vector<Eigen::Vector2d> points_;
  std::vector<Node> nodes_;
  std::vector<std::size_t> stack_;
  std::size_t hint_ = 0;
};

// The (x, y) of a planned path's points.
std::vector<Eigen::Vector2d> route_points(const std::vector<Eigen::Vector3d>& path) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(path.size());
  for (const Eigen::Vector3d& p : path) points.push_back(p.head<2>());
  return points;
}

}  // namespace

CrossTrack cross_track_error(std::span<const TrajectorySample> trajectory, std::span<const PlannerEvent> events) {
  CrossTrack result;
  std::optional<RouteDistance> route;
  const std::vector<Eigen::Vector3d>* pending = nullptr;  // the latest planned path, built when a sample needs it
  std::size_t e = 0;
  double sum = 0.0, sum_squares = 0.0, max_squared = 0.0;
  for (const TrajectorySample& s : trajectory) {
    for (; e < events.size() && events[e].time_s <= s.time_s; ++e) {
      if (const auto& path = events[e].decisions.planned_path) pending = &*path;
    }
    if (pending) {
      std::vector<Eigen::Vector2d> points = route_points(*pending);
      if (points.empty()) route.reset();
      else route.emplace(std::move(points));
      pending = nullptr;
    }
    if (!route) continue;
    const double d2 = route->squared_distance(s.state.position_m.head<2>());
    sum += std::sqrt(d2);
    sum_squares += d2;
    max_squared = std::max(max_squared, d2);
    ++result.samples;
  }
  if (result.samples > 0) {
    result.rms_m = std::sqrt(sum_squares / static_cast<double>(result.samples));
    result.mean_m = sum / static_cast<double>(result.samples);
    result.max_m = std::sqrt(max_squared);
  }
  return result;
}

double avoiding_time(std::span<const PlannerEvent> events, double end_time_s) {
  double total = 0.0;
  bool on = false;
  double since = 0.0;
  for (const PlannerEvent& e : events) {
    if (!e.decisions.avoiding) continue;
    const bool now = *e.decisions.avoiding;
    if (now && !on) since = e.time_s;
    if (!now && on) total += e.time_s - since;
    on = now;
  }
  if (on) total += std::max(0.0, end_time_s - since);
  return total;
}

namespace {

nlohmann::json collision_events_json(const std::vector<CollisionEvent>& events) {
  nlohmann::json list = nlohmann::json::array();
  for (const CollisionEvent& e : events) {
    list.push_back({{"time_s", e.time_s},
                    {"body", e.body},
                    {"ground", e.ground},
                    {"point_m", {e.point_m.x(), e.point_m.y(), e.point_m.z()}}});
  }
  return list;
}

}  // namespace

std::string_view to_string(Outcome outcome) {
  static constexpr std::string_view kNames[] = {"reached", "collision", "timeout", "aborted", "failed"};
  return kNames[static_cast<int>(outcome)];
}

nlohmann::json to_json(const EpisodeMetrics& m) {
  nlohmann::json j = {
      {"outcome", to_string(m.outcome)},
      {"reason", m.reason},
      {"sim_time_s", m.sim_time_s},
      {"wall_time_s", m.wall_time_s},
      {"path_length_m", m.path_length_m},  // the distance travelled
      {"path_ratio", m.path_ratio},
      // null when the scene has no obstacles at all
      {"min_clearance_m", std::isfinite(m.min_clearance_m) ? nlohmann::json(m.min_clearance_m) : nlohmann::json()},
      {"nearest_obstacle", m.nearest_obstacle.empty() ? nlohmann::json() : nlohmann::json(m.nearest_obstacle)},
      {"min_clearance_time_s", m.nearest_obstacle.empty() ? nlohmann::json() : nlohmann::json(m.min_clearance_time_s)},
      {"min_ground_clearance_m",
       std::isfinite(m.min_ground_clearance_m) ? nlohmann::json(m.min_ground_clearance_m) : nlohmann::json()},
      {"collisions", m.collisions},
      {"collision_events", collision_events_json(m.collision_events)},
      {"planner_calls", m.planner_calls},
      {"planner_time_ms_mean", m.planner_time_ms_mean},
      {"planner_time_ms_max", m.planner_time_ms_max},
      {"waypoints_planned", m.waypoints_planned},
      {"waypoints_reached", m.waypoints_reached},
      {"waypoints_discarded", m.waypoints_discarded},
      {"replans", m.replans},
      {"replan_time_ms_median", m.replan_time_ms_median},
      {"replan_time_ms_max", m.replan_time_ms_max},
      {"cross_track_rms_m", m.cross_track_rms_m},
      {"cross_track_mean_m", m.cross_track_mean_m},
      {"cross_track_max_m", m.cross_track_max_m},
      {"avoiding_time_s", m.avoiding_time_s},
  };
  const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
  for (std::size_t k = 0; k < m.legs.size(); ++k) {
    const std::string leg = "leg" + std::to_string(k);
    j[leg + "_path_length_m"] = optional(m.legs[k].path_length_m);
    j[leg + "_lateral_before_climb_m"] = optional(m.legs[k].lateral_before_climb_m);
  }
  for (const GateMetrics& gate : m.gates) {
    j["gate_" + gate.name + "_passed"] = gate.time_s.has_value();
    j["gate_" + gate.name + "_time_s"] = optional(gate.time_s);
  }
  return j;
}

namespace {

// The running minima of the clearance metrics.
struct ClearanceMinima {
  double obstacle_m = std::numeric_limits<double>::infinity();
  int obstacle = -1;
  double obstacle_time_s = 0.0;
  double ground_m = std::numeric_limits<double>::infinity();

  void update(const Clearance& c, double t_s) {
    if (c.obstacle_m < obstacle_m) {
      obstacle_m = c.obstacle_m;
      obstacle = c.obstacle;
      obstacle_time_s = t_s;
    }
    ground_m = std::min(ground_m, c.ground_m);
  }
  // Cutoffs for a query that only needs to find a new minimum or a touch:
  // anything farther than the minima so far cannot change them.
  double obstacle_cutoff() const { return std::max(obstacle_m, kTouchSearch_m); }
  double ground_cutoff() const { return std::max(ground_m, kTouchSearch_m); }
  static constexpr double kTouchSearch_m = 1e-6;  // finds every overlap
};

constexpr double kExact = std::numeric_limits<double>::infinity();

std::string body_name(const Scene& scene, int id) {
  if (id >= 0) return scene.shapes.at(static_cast<std::size_t>(id)).alias;
  return scene.movers.at(static_cast<std::size_t>(-1 - id)).shape.alias;
}

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
        reached_sample(def.mission.size()) {
    sensors.reserve(def.sensors.size());
    for (const SensorDef& s : def.sensors) {
      const double rate = s.lidar.rate_hz > 0.0 ? s.lidar.rate_hz : scene.world.sensor_rate_hz;
      sensors.push_back(
          {options.make_sensor(scene, s, scene.world.seed), std::make_shared<LidarScan>(), period_steps(rate, dt)});
    }
    readings.resize(sensors.size());
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      readings[i] = {def.sensors[i].alias, &def.sensors[i].lidar, nullptr, false};
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
      s.sensor->scan(vehicle->state().pose() * to_isometry(def.sensors[i].lidar.mount), t, body_poses, *s.scan);
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
    m.min_clearance_m = minima.obstacle_m;
    m.min_ground_clearance_m = minima.ground_m;
    if (std::isfinite(minima.obstacle_m)) {
      m.nearest_obstacle = body_name(scene, minima.obstacle);
      m.min_clearance_time_s = minima.obstacle_time_s;
    }
    // The nominal route: straight legs from the start through every waypoint
    // (for a single goal, the straight start-goal line), each waypoint taken
    // where the vehicle was when it was reached (within the arrival
    // tolerance), so the path flown, which passes through those points, is
    // never shorter than the route: the ratio of a reached run is at least 1.
    if (m.outcome == Outcome::reached && !def.mission.empty()) reached_at.back() = vehicle->state().position_m;
    double nominal = 0.0;
    Eigen::Vector3d from = start;
    for (std::size_t i = 0; i < def.mission.size(); ++i) {
      const Eigen::Vector3d to = reached_at[i].value_or(def.mission[i].position_m);
      const Eigen::Vector3d leg = to - from;
      nominal += def.type == VehicleType::rover ? leg.head<2>().norm() : leg.norm();
      from = to;
    }
    m.path_ratio = nominal > 1e-9 ? m.path_length_m / nominal : 0.0;
    count_decisions(result.events, m);
    const CrossTrack cross_track = cross_track_error(result.trajectory, result.events);
    m.cross_track_rms_m = cross_track.rms_m;
    m.cross_track_mean_m = cross_track.mean_m;
    m.cross_track_max_m = cross_track.max_m;
    m.avoiding_time_s = avoiding_time(result.events, m.sim_time_s);
    route_metrics(def, start, result.trajectory, reached_sample, m);
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
