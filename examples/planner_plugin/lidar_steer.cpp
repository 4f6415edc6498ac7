// lidar_steer: a quadrotor planner as a campo plugin. It flies toward each
// mission waypoint in turn and steers around the obstacles its LIDAR has seen:
// the hits at flight height are remembered in a 2D grid of cells, and every
// control step it takes the heading closest to the waypoint's along which a
// corridor of the vehicle's clearance is free of remembered cells for a
// look-ahead distance. A reactive planner with a short memory, not a global
// one: a dead end deeper than the look-ahead can trap it.
//
// Only campo's public headers are used (campo/plugin.hpp includes the planner
// contract, campo/planner.hpp, and the strict JSON reading of campo/json_reader.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>

#include <Eigen/Core>

#include "campo/config_fields.hpp"
#include "campo/plugin.hpp"
#include "campo/record_fields.hpp"

namespace lidar_steer {

struct LidarSteerConfig {
  double speed_mps = 0.6;          ///< cruise speed
  double tolerance_m = 0.3;        ///< a waypoint counts as reached within this distance
  double clearance_m = 0.6;        ///< half-width of the corridor a heading needs free
  double lookahead_m = 2.5;        ///< length of that corridor
  double carrot_m = 1.0;           ///< how far ahead along the chosen heading the GoTo target is
  double height_band_m = 0.5;      ///< hits within this height of the vehicle are obstacles (the ground is not)
  double cell_m = 0.2;             ///< side of the memory's cells
  double memory_radius_m = 20.0;   ///< cells farther from the vehicle are forgotten
  double heading_step_deg = 5.0;   ///< spacing of the candidate headings
  double ground_margin_m = 0.3;    ///< hits less than this above the scene's ground are the ground, not obstacles
  std::string sensor;              ///< alias of the LIDAR; empty: the vehicle's first sensor
};

// Each parameter declared once: its key, member, accepted range, unit and meaning. Reading,
// parameters() and a docs table (lidar_steer_config_fields().markdown()) all come from here.
const campo::ConfigFields<LidarSteerConfig>& lidar_steer_config_fields() {
  using campo::Range;
  using C = LidarSteerConfig;
  static const campo::ConfigFields<C> fields =
      campo::ConfigFields<C>()
          .number("speed_mps", &C::speed_mps, Range::closed(0.05, 5.0), "m/s", "cruise speed")
          .number("tolerance_m", &C::tolerance_m, Range::positive(), "m", "a waypoint counts as reached within this")
          .number("clearance_m", &C::clearance_m, Range::closed(0.05, 10.0), "m",
                  "half-width of the corridor a heading needs free")
          .number("lookahead_m", &C::lookahead_m, Range::closed(0.1, 50.0), "m", "length of that corridor")
          .number("carrot_m", &C::carrot_m, Range::closed(0.05, 10.0), "m",
                  "how far ahead along the chosen heading the GoTo target is")
          .number("height_band_m", &C::height_band_m, Range::positive(), "m",
                  "hits within this height of the vehicle are obstacles")
          .number("cell_m", &C::cell_m, Range::closed(0.02, 5.0), "m", "side of the memory's cells")
          .number("memory_radius_m", &C::memory_radius_m, Range::closed(1.0, 1000.0), "m",
                  "cells farther from the vehicle are forgotten")
          .number("heading_step_deg", &C::heading_step_deg, Range::closed(0.5, 90.0), "deg",
                  "spacing of the candidate headings")
          .number("ground_margin_m", &C::ground_margin_m, Range::closed(0.0, 10.0), "m",
                  "hits less than this above the scene's ground are the ground, not obstacles")
          .text("sensor", &C::sensor, "alias of the LIDAR; empty: the vehicle's first sensor")
          .omitted_when_default();
  return fields;
}

// What the planner records beyond campo's generic decisions, each field declared once (name, type,
// unit, meaning) and written through its typed handle: events.jsonl holds it under its name, and a
// figure or a script reads it back through the same declaration (docs/extending.md, "Declaring a
// planner's record"). Its own metric is declared the same way and measured at the end of a run from
// the decisions recorded: run.json's metrics hold it beside the generic ones. Registered with the
// planner below.
struct LidarSteerRecord {
  campo::PlannerRecord description;
  campo::RecordField<double> steer_deg = description.decisions.declare<double>(
      "steer_deg", "deg", "the heading steered for, relative to the waypoint's, positive left; recorded when it changes");
  campo::RecordField<double> steer_deg_max = description.metrics.declare<double>(
      "steer_deg_max", "deg",
      "the largest steering angle commanded, either side (|steer_deg|); 0 when it never steered");

  LidarSteerRecord() {
    description.measure = [this](const campo::PlannerRun& run, nlohmann::json& out) {
      double largest = 0.0;
      for (const campo::PlannerEvent& e : run.events) {
        const std::optional<double> steer = steer_deg.get(e.decisions.own);
        if (steer) largest = std::max(largest, std::abs(*steer));
      }
      steer_deg_max.set(out, largest);
    };
  }
  LidarSteerRecord(const LidarSteerRecord&) = delete;  // `measure` reads this object's handles
  LidarSteerRecord& operator=(const LidarSteerRecord&) = delete;
};

const LidarSteerRecord& lidar_steer_record() {
  static const LidarSteerRecord record;
  return record;
}

class LidarSteerPlanner final : public campo::Planner {
 public:
  /// `scene`: the ground it knows (may be null: then every hit in the height band is an obstacle).
  LidarSteerPlanner(const LidarSteerConfig& config, const campo::Scene* scene) : config_(config), scene_(scene) {}

  campo::PlanResult plan(const campo::Observation& o) override {
    campo::PlanResult result;
    const Eigen::Vector3d position = o.state.position_m;
    while (next_ < o.mission.size() && (o.mission[next_].position_m - position).norm() <= config_.tolerance_m) {
      result.decisions.reached_waypoints.push_back(static_cast<int>(next_));
      ++next_;
    }
    if (next_ >= o.mission.size()) {
      result.status = campo::PlanStatus::reached;
      result.reason = "all " + std::to_string(o.mission.size()) + " waypoints reached";
      result.command = campo::command::Hold{position, std::nullopt};
      return result;
    }
    remember(o);

    const Eigen::Vector3d& goal = o.mission[next_].position_m;
    const Eigen::Vector2d here = position.head<2>();
    const Eigen::Vector2d to_goal = goal.head<2>() - here;
    const double distance = to_goal.norm();
    if (distance < 1e-6) {  // straight above or below the waypoint: only the height is left
      result.command = campo::command::GoTo{goal, config_.speed_mps, false};
      return result;
    }
    const std::optional<int> step = free_heading_step(here, std::atan2(to_goal.y(), to_goal.x()), distance);
    if (!step) {
      result.status = campo::PlanStatus::no_path;
      result.reason = "every heading is blocked within " + std::to_string(config_.lookahead_m) + " m";
      result.command = campo::command::Hold{position, std::nullopt};
      return result;
    }
    const bool avoiding = *step != 0;
    if (avoiding != avoiding_) result.decisions.avoiding = avoiding;
    if (*step != last_step_) lidar_steer_record().steer_deg.set(result.decisions.own, *step * config_.heading_step_deg);
    last_step_ = *step;
    avoiding_ = avoiding;
    if (avoiding) preferred_side_ = *step > 0 ? 1 : -1;
    if (!avoiding && distance <= config_.carrot_m) {
      result.command = campo::command::GoTo{goal, config_.speed_mps, true};
      return result;
    }
    const double heading = std::atan2(to_goal.y(), to_goal.x()) + *step * step_rad();
    const Eigen::Vector2d ahead = here + config_.carrot_m * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    result.command = campo::command::GoTo{Eigen::Vector3d(ahead.x(), ahead.y(), goal.z()), config_.speed_mps, true};
    return result;
  }

  nlohmann::json parameters() const override { return lidar_steer_config_fields().write(config_); }

 private:
  double step_rad() const { return config_.heading_step_deg * std::numbers::pi / 180.0; }

  std::int64_t cell_key(const Eigen::Vector2d& p) const {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() / config_.cell_m));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() / config_.cell_m));
    return (ix << 32) ^ (iy & 0xffffffff);
  }

  // Adds the fresh scan's hits at flight height to the memory and forgets far cells.
  void remember(const campo::Observation& o) {
    const campo::SensorReading* reading = o.sensor(config_.sensor);
    if (reading == nullptr || !reading->fresh || reading->scan == nullptr) return;
    const Eigen::Vector3d& position = o.state.position_m;
    for (const Eigen::Vector3f& hit : reading->scan->points) {
      const Eigen::Vector3d p = hit.cast<double>();
      if (std::abs(p.z() - position.z()) > config_.height_band_m) continue;
      // Returns from the ground are no obstacles, however low the vehicle flies (taking off, it
      // scans the ground around it within the height band).
      if (scene_ != nullptr) {
        const std::optional<double> ground = scene_->ground_height(p.x(), p.y());
        if (ground && p.z() - *ground < config_.ground_margin_m) continue;
      }
      const Eigen::Vector2d xy = p.head<2>();
      const Eigen::Vector2d centre = ((xy / config_.cell_m).array().floor() + 0.5).matrix() * config_.cell_m;
      cells_.emplace(cell_key(xy), centre);
    }
    for (auto it = cells_.begin(); it != cells_.end();) {
      it = (it->second - position.head<2>()).norm() > config_.memory_radius_m ? cells_.erase(it) : std::next(it);
    }
  }

  // Whether the corridor from `here` along `direction` for `length` keeps clear of every remembered cell.
  // Cells behind the vehicle do not block it, so it can always move away from a wall it is close to.
  bool corridor_free(const Eigen::Vector2d& here, const Eigen::Vector2d& direction, double length) const {
    for (const auto& [key, centre] : cells_) {
      const Eigen::Vector2d offset = centre - here;
      const double along = offset.dot(direction);
      if (along < 0.0 || along > length + config_.clearance_m) continue;
      const double across = (offset - std::min(along, length) * direction).norm();
      if (across < config_.clearance_m) return false;
    }
    return true;
  }

  // The candidate heading closest to the goal's (in steps of heading_step_deg, positive to the left) whose
  // corridor is free; ties go to the side chosen last, so the vehicle does not dither in front of an obstacle.
  std::optional<int> free_heading_step(const Eigen::Vector2d& here, double goal_heading, double goal_distance) const {
    const double length = std::min(config_.lookahead_m, goal_distance);
    const auto free = [&](int step) {
      const double heading = goal_heading + step * step_rad();
      return corridor_free(here, Eigen::Vector2d(std::cos(heading), std::sin(heading)), length);
    };
    const int steps = static_cast<int>(std::floor(180.0 / config_.heading_step_deg));
    for (int k = 0; k <= steps; ++k) {
      if (free(preferred_side_ * k)) return preferred_side_ * k;
      if (k > 0 && free(-preferred_side_ * k)) return -preferred_side_ * k;
    }
    return std::nullopt;
  }

  LidarSteerConfig config_;
  const campo::Scene* scene_;
  std::size_t next_ = 0;
  bool avoiding_ = false;
  int preferred_side_ = 1;
  int last_step_ = 0;         ///< the heading step recorded last (steer_deg), 0 before any
  std::unordered_map<std::int64_t, Eigen::Vector2d> cells_;
};

// Reads the scene's "planner": {"params": {...}} strictly, as campo's own planners do: a bad or unknown key is an
// InputError naming the scene file and the key's JSON pointer (exit 2 from campo run and campo validate).
std::unique_ptr<campo::Planner> make_lidar_steer_planner(const campo::ParamsBlock& params,
                                                         const campo::PlannerContext& context) {
  const LidarSteerConfig config = lidar_steer_config_fields().read(params);
  // Without its sensor it would fly blind: refuse at creation (campo validate reports it too).
  if (context.vehicle_def != nullptr) {
    const auto& sensors = context.vehicle_def->sensors;
    const auto named = [&](const campo::SensorDef& s) { return s.alias == config.sensor; };
    const bool found = config.sensor.empty() ? !sensors.empty() : std::any_of(sensors.begin(), sensors.end(), named);
    if (!found) {
      const std::string got = config.sensor.empty() ? "a vehicle without sensors" : "\"" + config.sensor + "\"";
      throw campo::InputError(params.file, params.pointer + "/sensor",
                              "expected a sensor of vehicle " + context.vehicle_def->alias +
                                  " for planner lidar_steer, got " + got);
    }
  }
  return std::make_unique<LidarSteerPlanner>(config, context.scene);
}

}  // namespace lidar_steer

// The plugin's one entry point: campo calls it once when it loads the library.
CAMPO_REGISTER_PLANNERS(registrar) {
  registrar.add({"lidar_steer", "example plugin: fly to each waypoint, steering around obstacles seen by LIDAR",
                 &lidar_steer::make_lidar_steer_planner, {campo::VehicleType::quadrotor},
                 &lidar_steer::lidar_steer_record().description});
}
