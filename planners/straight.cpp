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

  nlohmann::json parameters() const override {
    return {{"speed_mps", config_.speed_mps}, {"tolerance_m", config_.tolerance_m}, {"horizontal", config_.horizontal}};
  }

 private:
  double distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return config_.horizontal ? (a - b).head<2>().norm() : (a - b).norm();
  }

  StraightConfig config_;
  std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<Planner> make_straight_planner(const ParamsBlock& params, const PlannerContext& context) {
  StraightConfig config;
  if (context.vehicle == VehicleType::rover) {
    config.speed_mps = 0.5;
    config.tolerance_m = 0.5;
    config.horizontal = true;
  }
  ObjectReader r(JsonNode(params.values, params.file, params.pointer));
  r.read("speed_mps", config.speed_mps, Range::closed(0.01, 20.0));
  r.read("tolerance_m", config.tolerance_m, Range::positive());
  r.read("horizontal", config.horizontal);
  r.finish();
  return std::make_unique<StraightPlanner>(config);
}

}  // namespace campo
