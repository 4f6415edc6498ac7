#include "planners/depth_reactive.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <optional>
#include <vector>

#include "core/angles.hpp"
#include "campo/json_reader.hpp"
#include "sensors/lidar.hpp"

namespace campo {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kAltitudeTolerance_m = 0.1;  // an altitude change is done within this

double wrap_angle(double a) { return std::remainder(a, 2.0 * M_PI); }

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json vector_json(const Eigen::Vector2d& v) { return {v.x(), v.y()}; }
nlohmann::json vector_json(const Eigen::Vector2i& v) { return {v.x(), v.y()}; }

// A point far along heading `yaw` at the height of `from`, to face with command::Face.
Eigen::Vector3d point_at_yaw(const Eigen::Vector3d& from, double yaw) {
  return from + 100.0 * Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0);
}

class DepthReactivePlanner final : public Planner {
 public:
  explicit DepthReactivePlanner(const DepthReactiveConfig& config) : config_(config) {}

  PlanResult plan(const Observation& o) override {
    PlanResult result;
    const SensorReading* reading = depth_source(o);
    if (!reading) {
      result.status = PlanStatus::invalid_start;
      result.reason = config_.sensor.empty() ? "the vehicle has no grid range sensor to read depth maps from"
                                             : "the vehicle has no grid range sensor \"" + config_.sensor + "\"";
      result.command = command::Hold{o.state.position_m, std::nullopt};
      return result;
    }
    if (!started_) {
      command_ = command::Hold{o.state.position_m, o.state.yaw_rad()};
      started_ = true;
    }

    // Pop every waypoint already reached.
    for (;;) {
      if (stack_.empty()) {
        if (next_target_ >= o.mission.size()) {
          result.status = PlanStatus::reached;
          result.reason = "all " + std::to_string(o.mission.size()) + " waypoints reached";
          result.command = command::Hold{o.state.position_m, std::nullopt};
          return result;
        }
        stack_.push_back({o.mission[next_target_].position_m, false});
      }
      const StackEntry& top = stack_.back();
      if ((o.state.position_m - top.position_m).norm() > config_.tolerance_m) break;
      discarded_.clear();  // from a new place the same waypoints may be worth proposing again
      if (top.temporary) {
        result.decisions.reached_intermediate = top.position_m;
      } else {
        result.decisions.reached_waypoints.push_back(static_cast<int>(next_target_++));
      }
      // Stop at the waypoint reached (not where the drone is, still moving,
      // which would overshoot it by the braking distance) before turning.
      command_ = command::Hold{top.position_m, o.state.yaw_rad()};
      stack_.pop_back();
      enter(Phase::align, o);
    }

    settle(o);
    switch (phase_) {
      case Phase::fly: monitor(o, *reading, result); break;
      case Phase::align: align(o, *reading, result); break;
      case Phase::wall_look: wall_look(o, *reading, result); break;
    }
    if (result.status == PlanStatus::running) result.command = command_;
    return result;
  }

  nlohmann::json parameters() const override { return depth_reactive_config_fields().write(config_); }

 private:
  enum class Phase {
    align,      ///< ControllaAltitudine, ControllaRotazione, hover still, then decide
    fly,        ///< VaiVerso: fly to the waypoint, watching for occlusion
    wall_look,  ///< wall following: look around for free space
  };
  struct StackEntry {
    Eigen::Vector3d position_m;
    bool temporary = true;  ///< false for the target (a mission waypoint)
  };
  struct WallFollowing {
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  ///< where it started
    double goal_yaw = 0.0;          ///< heading toward the target when it started
    double offset = 0.0;            ///< current look direction relative to goal_yaw, radians
    int side = 0;                   ///< chosen turn direction (+1 left, -1 right), 0 while scanning
    double free_left = 0.0;
    double free_right = 0.0;
  };

  // The reading of the configured sensor, or of the first grid sensor.
  const SensorReading* depth_source(const Observation& o) const {
    for (const SensorReading& r : o.sensors) {
      if (r.config && is_image(*r.config) && (config_.sensor.empty() || r.alias == config_.sensor)) return &r;
    }
    return nullptr;
  }

  void enter(Phase phase, const Observation& o) {
    phase_ = phase;
    settled_since_s_.reset();
    phase_start_s_ = o.time_s;
  }

  // Tracks since when the vehicle has been hovering still.
  void settle(const Observation& o) {
    if (!o.stable) {
      settled_since_s_.reset();
    } else if (!settled_since_s_) {
      settled_since_s_ = o.time_s;
    }
  }

  // A scan taken after the vehicle settled: what a decision may read.
  bool settled_scan(const SensorReading& reading) const {
    return settled_since_s_ && reading.scan && reading.scan->time_s >= *settled_since_s_;
  }

  // Turns toward `yaw` while holding position; true once aligned, still and scanned.
  bool look(const Observation& o, const SensorReading& reading, double yaw) {
    if (std::abs(wrap_angle(yaw - o.state.yaw_rad())) > config_.yaw_tolerance_deg * kDegToRad) {
      const command::Face face{point_at_yaw(wall_.origin_m, yaw)};
      const auto* current = std::get_if<command::Face>(&command_);
      if (!current || current->point_m != face.point_m) command_ = face;
      return false;
    }
    return settled_scan(reading);
  }

  void align(const Observation& o, const SensorReading& reading, PlanResult& result) {
    // After a waypoint was reached: come to rest on it before turning in place.
    if (std::holds_alternative<command::Hold>(command_) && !o.stable) return;
    const Eigen::Vector3d w = stack_.back().position_m;
    const Eigen::Vector3d delta = w - o.state.position_m;
    // ControllaAltitudine: the least altitude change that brings W within max_elevation_deg.
    const Eigen::Vector3d level = after_altitude_check(o.state.position_m, w, Eigen::Vector3d::UnitZ(),
                                                       config_.max_elevation_deg, kAltitudeTolerance_m);
    if (level != o.state.position_m) {
      const double z = level.z();
      const auto* current = std::get_if<command::Altitude>(&command_);
      if (!current || std::abs(current->z_m - z) > kAltitudeTolerance_m) command_ = command::Altitude{z};
      return;
    }
    // ControllaRotazione, then hover still until a scan taken at rest arrives.
    const double yaw = delta.head<2>().norm() > 1e-6 ? std::atan2(delta.y(), delta.x()) : o.state.yaw_rad();
    if (std::abs(wrap_angle(yaw - o.state.yaw_rad())) > config_.yaw_tolerance_deg * kDegToRad) {
      const auto* current = std::get_if<command::Face>(&command_);
      if (!current || current->point_m != w) command_ = command::Face{w};
      return;
    }
    if (!settled_scan(reading)) return;
    evaluate(o, reading, result);
  }

  // One replanning step: DilataMappa, ControllaVisibilita and what Algorithm 3 does with the result.
  void evaluate(const Observation& o, const SensorReading& reading, PlanResult& result) {
    const auto start = Clock::now();
    const RangeScan& scan = *reading.scan;
    const DepthGrid grid = DepthGrid::of(scan, *reading.config);
    const cv::Mat depth = depth_map(scan, *reading.config);
    const cv::Mat dilated = dilate_depth_map(depth, dilation_params(config_, grid));
    const double dilation_ms = elapsed_ms(start);
    const StackEntry entry = stack_.back();
    const Eigen::Isometry3d to_sensor = scan.sensor_pose.inverse();
    VisibilityCheck check =
        check_visibility(dilated, grid, to_sensor * entry.position_m, config_.safety_radius_m, 0.0, depth_margin(), &depth);
    // Hysteresis against VaiVerso's check: a target visible only just (its
    // neighbourhood widened by visible_margin_px holds an obstacle) counts as
    // invisible, so TrovaWP sets a waypoint clear by the same margin instead
    // of a flight that stops at the first scan taken while pitched forward.
    bool marginal = false;
    if (!entry.temporary && check.visibility == Visibility::visible && config_.visible_margin_px > 0.0 &&
        check.waypoint_range_m > config_.monitor_min_range_m) {
      const VisibilityCheck strict = check_visibility(dilated, grid, to_sensor * entry.position_m,
                                                      config_.safety_radius_m, config_.visible_margin_px, depth_margin(),
                                                      &depth);
      if (strict.visibility != Visibility::visible) {
        check = strict;
        check.visibility = Visibility::invisible;
        marginal = true;
      }
    }

    ReplanDecision replan = replan_record(reading, scan, entry, check);
    const DepthReactiveRecord& rec = depth_reactive_record();
    if (marginal) rec.marginal.set(replan.details, true);
    std::string action;
    if (check.visibility == Visibility::visible) {
      action = "fly";
      command_ = command::GoTo{entry.position_m, config_.speed_mps, true};
      enter(Phase::fly, o);
    } else if (entry.temporary) {
      action = "discard";
      discard(o, result);
    } else if (check.visibility == Visibility::unreachable) {
      action = "abort";
      result.status = PlanStatus::no_path;
      result.reason = "target unreachable: an obstacle " + std::to_string(check.obstacle_range_m) +
                      " m away lies within the safety radius of the target, " +
                      std::to_string(check.waypoint_range_m) + " m away";
    } else {
      const auto search_start = Clock::now();
      std::vector<Eigen::Vector3d> avoid;
      for (const Eigen::Vector3d& d : discarded_) avoid.push_back(to_sensor * d);
      FindWaypointParams search_params = find_waypoint_params(config_);
      if (config_.margin_in_depth) {
        // What the vehicle cannot see once it turns at the new waypoint toward the target.
        const RangeSensorConfig& sensor = *reading.config;
        search_params.next_leg_check_m = blind_leg_m(config_.dilation_margin_m,
                                                     0.5 * std::min(sensor.fov_h_deg, sensor.fov_v_deg),
                                                     sensor.mount.position_m.x());
      }
      const WaypointSearch search =
          find_waypoint(dilated, grid, check.pixel, check.waypoint_range_m / grid.max_range_m,
                        check.obstacle_range_m / grid.max_range_m, search_params, avoid, to_sensor * o.state.position_m,
                        to_sensor.linear() * Eigen::Vector3d::UnitZ(), &depth);
      rec.search_ms.set(replan.details, elapsed_ms(search_start));
      rec.threshold.set(replan.details, search.threshold);
      rec.candidates.set(replan.details, search.candidates);
      if (search.found) {
        const FoundWaypoint& f = *search.found;
        const Eigen::Vector3d waypoint = scan.sensor_pose * (f.direction_sensor * f.range_m);
        rec.chosen_pixel.set(replan.details, vector_json(f.pixel));
        rec.edge_pixel.set(replan.details, vector_json(f.edge_pixel));
        rec.waypoint_pixel.set(replan.details, vector_json(f.waypoint_pixel));
        rec.edge_range_m.set(replan.details, f.edge_range_m);
        rec.new_waypoint_range_m.set(replan.details, f.range_m);
        rec.tried.set(replan.details, f.tried);
        action = "new_waypoint";
        stack_.push_back({waypoint, true});
        result.decisions.planned_waypoint = waypoint;
        enter(Phase::align, o);
      } else {
        action = "wall_following";
        wall_ = WallFollowing{o.state.position_m, o.state.yaw_rad(), config_.wall_scan_deg * kDegToRad, 0, 0.0, 0.0};
        enter(Phase::wall_look, o);
      }
    }
    rec.action.set(replan.details, action);
    rec.dilation_ms.set(replan.details, dilation_ms);
    replan.time_ms = elapsed_ms(start);
    result.decisions.replan = std::move(replan);
    if (result.status == PlanStatus::running && replans_ >= config_.max_replans) {
      result.status = PlanStatus::aborted;
      result.reason = "gave up after " + std::to_string(replans_) + " replanning steps";
    }
  }

  ReplanDecision replan_record(const SensorReading& reading, const RangeScan& scan, const StackEntry& entry,
                               const VisibilityCheck& check) {
    ReplanDecision replan{.index = replans_++, .sensor = std::string(reading.alias)};
    const DepthReactiveRecord& rec = depth_reactive_record();
    rec.scan_time_s.set(replan.details, scan.time_s);
    rec.waypoint.set(replan.details, vector_json(entry.position_m));
    rec.role.set(replan.details, entry.temporary ? "intermediate" : "target");
    rec.visibility.set(replan.details, std::string(to_string(check.visibility)));
    rec.pixel.set(replan.details, vector_json(check.pixel));
    rec.radius_px.set(replan.details, vector_json(Eigen::Vector2d(check.radius_x_px, check.radius_y_px)));
    rec.waypoint_range_m.set(replan.details, check.waypoint_range_m);
    rec.obstacle_range_m.set(replan.details, check.obstacle_range_m);
    return replan;
  }

  void discard(const Observation& o, PlanResult& result) {
    discarded_.push_back(stack_.back().position_m);
    result.decisions.discarded_waypoint = stack_.back().position_m;
    stack_.pop_back();
    enter(Phase::align, o);
  }

  // VaiVerso: keep flying; at every fresh scan check that the waypoint is still visible.
  void monitor(const Observation& o, const SensorReading& reading, PlanResult& result) {
    const StackEntry& entry = stack_.back();
    if (!reading.fresh || !reading.scan || reading.scan->time_s <= phase_start_s_) return;
    if ((entry.position_m - o.state.position_m).norm() < config_.monitor_min_range_m) return;
    const auto start = Clock::now();
    const DepthGrid grid = DepthGrid::of(*reading.scan, *reading.config);
    const cv::Mat depth = depth_map(*reading.scan, *reading.config);
    const cv::Mat dilated = dilate_depth_map(depth, dilation_params(config_, grid));
    // The other side of the hysteresis of evaluate(): on the way the
    // neighbourhood is visible_margin_px narrower than when deciding, so the
    // image shifting by a pixel or two as the drone pitches does not stop it;
    // the dilation still keeps the margin around the line of flight.
    const VisibilityCheck check = check_visibility(dilated, grid, reading.scan->sensor_pose.inverse() * entry.position_m,
                                                   config_.safety_radius_m, -config_.visible_margin_px, depth_margin(),
                                                   &depth);
    if (check.visibility == Visibility::visible) return;
    // Occluded on the way: stop here and decide again once still.
    ReplanDecision replan = replan_record(reading, *reading.scan, entry, check);
    depth_reactive_record().action.set(replan.details, "stop");
    replan.time_ms = elapsed_ms(start);
    result.decisions.replan = std::move(replan);
    command_ = command::Hold{o.state.position_m, o.state.yaw_rad()};
    enter(Phase::align, o);
  }

  // Wall following (000 §4.4.3): look wall_scan_deg either side of the goal,
  // turn toward the freer side until the navigable sector is free enough,
  // then set a waypoint wall_step_m ahead.
  void wall_look(const Observation& o, const SensorReading& reading, PlanResult& result) {
    if (!look(o, reading, wall_.goal_yaw + wall_.offset)) return;
    const DepthGrid grid = DepthGrid::of(*reading.scan, *reading.config);
    const cv::Mat dilated = dilate_depth_map(depth_map(*reading.scan, *reading.config), dilation_params(config_, grid));
    const double free_value = (config_.wall_step_m + config_.safety_radius_m) / grid.max_range_m;
    const double fraction = free_fraction(dilated, navigable_region(grid, config_.wall_sector_deg, config_.wall_band_deg),
                                          free_value);
    nlohmann::json record = {{"offset_deg", wall_.offset / kDegToRad}, {"free_fraction", fraction}};
    const double scan_offset = config_.wall_scan_deg * kDegToRad;
    if (wall_.side == 0 && wall_.offset > 0.0) {
      wall_.free_left = fraction;  // looked left; now look right
      wall_.offset = -scan_offset;
    } else if (wall_.side == 0) {
      wall_.free_right = fraction;  // looked both ways: turn toward the freer side
      wall_.side = wall_.free_left > wall_.free_right ? 1 : -1;
      wall_.offset = wall_.side * scan_offset;
      record["side"] = wall_.side > 0 ? "left" : "right";
    } else if (fraction >= config_.wall_free_fraction) {
      place_wall_waypoint(o, dilated, grid, result, record);
      return;
    } else {
      wall_.offset += wall_.side * config_.wall_turn_step_deg * kDegToRad;
      if (std::abs(wall_.offset) > M_PI) {
        result.status = PlanStatus::aborted;
        result.reason = "cannot get around the obstacle: no free sector within 180 deg of the goal";
      }
    }
    depth_reactive_record().wall_following.set(result.decisions.own, record);
  }

  void place_wall_waypoint(const Observation& o, const cv::Mat& dilated,
                           const DepthGrid& grid, PlanResult& result, nlohmann::json& record) {
    const Eigen::Vector2d ahead = grid.project(Eigen::Vector3d::UnitX());
    const double range =
        clear_range(dilated, grid, ahead, config_.wall_step_m, config_.safety_radius_m, 0.0, 1.5, depth_margin()).value_or(0.0);
    const double yaw = o.state.yaw_rad();
    const Eigen::Vector3d waypoint = o.state.position_m + range * Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0);
    record["waypoint"] = vector_json(waypoint);
    depth_reactive_record().wall_following.set(result.decisions.own, record);
    result.decisions.planned_waypoint = waypoint;
    stack_.push_back({waypoint, true});
    enter(Phase::align, o);
  }

  // Kept toward the sensor as well as across (margin_in_depth).
  double depth_margin() const { return config_.margin_in_depth ? config_.dilation_margin_m : 0.0; }

  DepthReactiveConfig config_;
  std::vector<StackEntry> stack_;     // NavigazioneLocale's stack: the target, then at most one temporary waypoint
  std::size_t next_target_ = 0;       // mission waypoint the target is
  std::vector<Eigen::Vector3d> discarded_;  // since the last waypoint reached: not proposed again
  Phase phase_ = Phase::align;
  double phase_start_s_ = 0.0;
  std::optional<double> settled_since_s_;
  Command command_;       // the behaviour the vehicle follows until a decision changes it
  bool started_ = false;
  WallFollowing wall_;
  int replans_ = 0;
};

}  // namespace

const ConfigFields<DepthReactiveConfig>& depth_reactive_config_fields() {
  using C = DepthReactiveConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .text("sensor", &C::sensor, "alias of the depth source; none: the vehicle's first grid sensor")
          .omitted_when_default()
          .number("speed_mps", &C::speed_mps, Range::closed(0.01, 20.0), "m/s", "cruise speed (seed 000 flew at 0.6 m/s)")
          .number("tolerance_m", &C::tolerance_m, Range::positive(), "m", "a waypoint is reached within this distance")
          .number("safety_radius_m", &C::safety_radius_m, Range::positive(), "m",
                  "r of ControllaVisibilita, on top of the dilation margin")
          .number("vehicle_radius_m", &C::vehicle_radius_m, Range::non_negative(), "m",
                  "added to the obstacle-edge distance in TrovaWP")
          .integer("layers", &C::layers, {1, 64}, "",
                   "n of DilataMappa for `as_printed` (`margin` makes one layer per distinct radius)")
          .choice("structuring_element", &C::structuring_element,
                  {{"square", StructuringShape::square}, {"disc", StructuringShape::disc}},
                  "shape of DilataMappa's structuring element")
          .choice("layer_radii", &C::layer_radii, {{"margin", LayerRadii::margin}, {"as_printed", LayerRadii::as_printed}},
                  "how the structuring element shrinks over the layers: keeping a metric margin, or Algorithm 1 as "
                  "printed (r s / n)")
          .number("dilation_margin_m", &C::dilation_margin_m, Range::non_negative(), "m",
                  "margin kept around obstacles (`margin`): the drone's bounding radius 0.43 m + 0.07 m")
          .flag("margin_in_depth", &C::margin_in_depth,
                "keep the margin toward the sensor too: beyond waypoints, along TrovaWP's corridor and the blind start "
                "of the next leg (false: Algorithm 2 and TrovaWP as printed)")
          .number("dilation_radius_deg", &C::dilation_radius_deg, Range::closed(0.0, 90.0), "deg",
                  "r of `as_printed` (seed 000: 49 px at 256 px over 90 deg)")
          .number("altitude_penalty", &C::altitude_penalty, Range::non_negative(), "1/px",
                  "k of TrovaWP's cost, per pixel of altitude change")
          .number("threshold_cap", &C::threshold_cap, Range::closed(0.05, 1.0), "", "cap of TrovaWP's threshold t")
          .number("min_waypoint_distance_m", &C::min_waypoint_distance_m, Range::non_negative(), "m",
                  "TrovaWP skips nearer waypoints")
          .integer("max_candidates", &C::max_candidates, {1, 1'000'000}, "",
                   "TrovaWP candidates tried before wall following")
          .number("yaw_tolerance_deg", &C::yaw_tolerance_deg, Range::closed(0.1, 45.0), "deg",
                  "ControllaRotazione: aligned within this")
          .number("max_elevation_deg", &C::max_elevation_deg, Range::closed(1.0, 80.0), "deg",
                  "ControllaAltitudine: change altitude until the waypoint is within this elevation")
          .number("monitor_min_range_m", &C::monitor_min_range_m, Range::non_negative(), "m",
                  "VaiVerso stops checking occlusion this close to the waypoint")
          .number("visible_margin_px", &C::visible_margin_px, Range::closed(0.0, 100.0), "px",
                  "hysteresis: the target's neighbourhood this much wider to decide, VaiVerso's this much narrower "
                  "on the way")
          .number("wall_scan_deg", &C::wall_scan_deg, Range::closed(1.0, 180.0), "deg",
                  "wall following: look this far either side of the goal (000 §4.4.3)")
          .number("wall_turn_step_deg", &C::wall_turn_step_deg, Range::closed(1.0, 180.0), "deg",
                  "wall following: then turn toward the freer side in these steps")
          .number("wall_sector_deg", &C::wall_sector_deg, Range::closed(1.0, 360.0), "deg",
                  "wall following: width of the navigable sector that must be free")
          .number("wall_band_deg", &C::wall_band_deg, Range::closed(0.0, 90.0), "deg",
                  "wall following: rows within this elevation of the horizon are looked at")
          .number("wall_free_fraction", &C::wall_free_fraction, Range::closed(0.0, 1.0), "",
                  "wall following: fraction of the sector that must be free")
          .number("wall_step_m", &C::wall_step_m, Range::positive(), "m",
                  "wall following: distance of a wall-following waypoint")
          .integer("max_replans", &C::max_replans, {1, 1'000'000}, "", "give up after this many replanning steps");
  return fields;
}

DepthReactiveConfig parse_depth_reactive_config(const ParamsBlock& params) {
  return depth_reactive_config_fields().read(params);
}

DilationParams dilation_params(const DepthReactiveConfig& c, const DepthGrid& grid) {
  if (c.layer_radii == LayerRadii::margin) return margin_layers(c.dilation_margin_m, grid, c.structuring_element);
  return {c.structuring_element,
          printed_layer_radii(c.layers, c.dilation_radius_deg / grid.deg_per_col(), c.dilation_radius_deg / grid.deg_per_row()),
          {}};
}

FindWaypointParams find_waypoint_params(const DepthReactiveConfig& c) {
  return {c.altitude_penalty, c.threshold_cap, c.vehicle_radius_m, c.safety_radius_m, c.min_waypoint_distance_m,
          c.max_candidates, c.margin_in_depth ? c.dilation_margin_m : 0.0, 0.0,
          c.margin_in_depth ? c.max_elevation_deg : 0.0, kAltitudeTolerance_m};
}

namespace {

Eigen::Vector2d vector2d(const nlohmann::json& j) { return {j.at(0).get<double>(), j.at(1).get<double>()}; }
Eigen::Vector2i vector2i(const nlohmann::json& j) { return {j.at(0).get<int>(), j.at(1).get<int>()}; }

// "new_waypoint" -> "new waypoint".
std::string spaced(std::string text) {
  std::replace(text.begin(), text.end(), '_', ' ');
  return text;
}

std::string replan_action(const ReplanDecision& step) {
  return spaced(depth_reactive_record().action.get(step.details).value_or(""));
}

// "target invisible -> new waypoint".
std::string replan_caption(const ReplanDecision& step) {
  const DepthReactiveRecord& r = depth_reactive_record();
  return r.role.get(step.details).value_or("") + " " + r.visibility.get(step.details).value_or("") + " -> " +
         replan_action(step);
}

// The overlays of one replanning step, recomputed as evaluate() computes them.
// The 16-bit file rounds values by at most 1 / 131070, so the maps match the
// planner's except, rarely, at a pixel that close to a layer boundary or t.
ImageOverlays replan_overlays(const ReplanDecision& step, const RecordedImage& image, const nlohmann::json& parameters,
                              const std::string& file, const std::string& pointer) {
  const DepthReactiveConfig config = parse_depth_reactive_config({parameters, file, pointer});
  const DepthGrid grid{image.cols, image.rows, image.fov_h_deg, image.fov_v_deg, image.max_range_m};
  const cv::Mat depth(image.rows, image.cols, CV_32F, const_cast<float*>(image.values.data()));
  const DepthReactiveRecord& r = depth_reactive_record();
  const nlohmann::json& d = step.details;
  const auto required = [&](const RecordField<nlohmann::json>& field) {
    const std::optional<nlohmann::json> value = field.get(d);
    if (!value) throw InputError(file, "/events", "replanning step " + std::to_string(step.index) + " has no " + field.name());
    return *value;
  };
  ImageOverlays o;
  const cv::Mat dilated = dilate_depth_map(depth, dilation_params(config, grid));
  o.processed.assign(dilated.ptr<float>(), dilated.ptr<float>() + dilated.total());
  const Eigen::Vector2d projection = vector2d(required(r.pixel));
  o.target_px = projection;
  o.ellipse_px = vector2d(required(r.radius_px));
  if (const auto t = r.threshold.get(d)) {
    o.mask_threshold = *t;
    const cv::Mat thresholded = threshold_free(dilated, *t);
    o.mask.assign(thresholded.ptr<std::uint8_t>(), thresholded.ptr<std::uint8_t>() + thresholded.total());
  }
  if (const auto chosen_json = r.chosen_pixel.get(d)) {
    const Eigen::Vector2i chosen = vector2i(*chosen_json);
    const Eigen::Vector2i edge = vector2i(required(r.edge_pixel));
    o.chosen_px = chosen;
    // TrovaWP's scan from the chosen pixel toward W', up to the obstacle edge;
    // an edge at the chosen pixel itself means the scan met none and ran on.
    for (const Eigen::Vector2i& q : pixel_segment(depth.size(), chosen, {projection.x(), projection.y()})) {
      o.polyline_px.push_back(q);
      if (q == edge && edge != chosen) break;
    }
    o.placed_px = vector2i(required(r.waypoint_pixel));
  }
  return o;
}

}  // namespace

DepthReactiveRecord::DepthReactiveRecord()
    : wall_following(description.decisions.declare_json(
          {"wall_following", RecordType::object, "",
           "a wall-following step: offset_deg (where it looked, deg from the goal), free_fraction (of the navigable "
           "sector), side (left or right, once chosen), waypoint (the one placed, [x, y, z] m)"})),
      scan_time_s(description.replan.declare<double>("scan_time_s", "s", "when the depth map read was taken")),
      waypoint(description.replan.declare_json(
          {"waypoint", RecordType::array, "m", "the waypoint checked, [x, y, z]"})),
      role(description.replan.declare<std::string>("role", "", "target (a mission waypoint) or intermediate")),
      visibility(description.replan.declare<std::string>("visibility", "", "visible, invisible or unreachable")),
      pixel(description.replan.declare_json(
          {"pixel", RecordType::array, "px", "W', the waypoint's projection [column, row] (continuous)"})),
      radius_px(description.replan.declare_json(
          {"radius_px", RecordType::array, "px", "half-axes of the safety sphere's projection [across, down]"})),
      waypoint_range_m(description.replan.declare<double>("waypoint_range_m", "m", "range of the waypoint")),
      obstacle_range_m(description.replan.declare<double>("obstacle_range_m", "m",
                                                          "range of the nearest obstacle around W'")),
      marginal(description.replan.declare<bool>("marginal", "", "visible only just: taken as invisible")),
      search_ms(description.replan.declare<double>("search_ms", "ms", "measured time of TrovaWP's search")),
      threshold(description.replan.declare<double>("threshold", "", "TrovaWP's threshold t on the dilated map")),
      candidates(description.replan.declare<std::int64_t>("candidates", "", "pixels at distance 1 from the obstacle")),
      chosen_pixel(description.replan.declare_json(
          {"chosen_pixel", RecordType::array, "px", "P-bar, the chosen pixel [column, row]"})),
      edge_pixel(description.replan.declare_json(
          {"edge_pixel", RecordType::array, "px", "where the scan toward W' met the obstacle's edge [column, row]"})),
      waypoint_pixel(description.replan.declare_json(
          {"waypoint_pixel", RecordType::array, "px", "the new waypoint's pixel [column, row]"})),
      edge_range_m(description.replan.declare<double>("edge_range_m", "m", "range at the obstacle's edge")),
      new_waypoint_range_m(description.replan.declare<double>("new_waypoint_range_m", "m",
                                                              "range of the new waypoint")),
      tried(description.replan.declare<std::int64_t>("tried", "", "candidates examined before this one succeeded")),
      action(description.replan.declare<std::string>(
          "action", "", "fly, discard, abort, new_waypoint, wall_following or stop")),
      dilation_ms(description.replan.declare<double>("dilation_ms", "ms", "measured time of the dilation")) {
  description.replan_action = replan_action;
  description.replan_caption = replan_caption;
  description.replan_overlays = replan_overlays;
}

const DepthReactiveRecord& depth_reactive_record() {
  static const DepthReactiveRecord record;
  return record;
}

std::unique_ptr<Planner> make_depth_reactive_planner(const ParamsBlock& params, const PlannerContext& context) {
  return std::make_unique<DepthReactivePlanner>(parse_depth_reactive_config(params));
}

}  // namespace campo
