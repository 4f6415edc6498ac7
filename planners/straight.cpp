#include "planners/straight.hpp"

#include "campo/json_reader.hpp"

namespace campo {

namespace {

class StraightPlanner final : public Planner {
 public:
  explicit StraightPlanner(const StraightConfig& config) : config_(config) {}

  PlanResult plan(const Observation& o) override {
    PlanResult result;
    while (next_ < o.mission.size() && distance(o.state.position_m, o.mission[next_].position_m) <= config_.tolerance_m) {
      result.decisions.reached_waypoints.push_back(static_cast<int>(next_));
      ++next_;
    }
    if (next_ >= o.mission.size()) {
      result.status = PlanStatus::reached;
      result.reason = "all " + std::to_string(o.mission.size()) + " waypoints reached";
      result.command = command::Hold{o.state.position_m, std::nullopt};
      return result;
    }
    result.command = command::GoTo{o.mission[next_].position_m, config_.speed_mps, true};
    return result;
  }

  nlohmann::json parameters() const override { return straight_config_fields().write(config_); }

 private:
  double distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return config_.horizontal ? (a - b).head<2>().norm() : (a - b).norm();
  }

  StraightConfig config_;
  std::size_t next_ = 0;
};

}  // namespace

const ConfigFields<StraightConfig>& straight_config_fields() {
  static const ConfigFields<StraightConfig> fields =
      ConfigFields<StraightConfig>()
          .number("speed_mps", &StraightConfig::speed_mps, Range::closed(0.01, 20.0), "m/s",
                  "cruise speed (the rover's default: 0.5)")
          .number("tolerance_m", &StraightConfig::tolerance_m, Range::positive(), "m",
                  "a waypoint counts as reached within this distance (the rover's default: 0.5)")
          .flag("horizontal", &StraightConfig::horizontal,
                "measure distance in x, y only (the rover's default: true)");
  return fields;
}

std::unique_ptr<Planner> make_straight_planner(const ParamsBlock& params, const PlannerContext& context) {
  StraightConfig config;
  if (context.vehicle == VehicleType::rover) {
    config.speed_mps = 0.5;
    config.tolerance_m = 0.5;
    config.horizontal = true;
  }
  straight_config_fields().read(params, config);
  return std::make_unique<StraightPlanner>(config);
}

}  // namespace campo
