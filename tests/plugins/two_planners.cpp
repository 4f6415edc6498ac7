// Fixture plugin: two planners registered from one source file.
//   fixture_goto: flies to each mission waypoint in turn in a straight line.
//   fixture_hold: holds the start position and gives up (aborted) after hold_s.
#include <memory>
#include <optional>

#include "campo/json_reader.hpp"
#include "campo/plugin.hpp"

namespace {

class GotoPlanner final : public campo::Planner {
 public:
  explicit GotoPlanner(double speed_mps) : speed_mps_(speed_mps) {}
  campo::PlanResult plan(const campo::Observation& o) override {
    campo::PlanResult result;
    while (next_ < o.mission.size() && (o.mission[next_].position_m - o.state.position_m).norm() <= 0.3) ++next_;
    if (next_ >= o.mission.size()) {
      result.status = campo::PlanStatus::reached;
      result.reason = "every waypoint reached";
      result.command = campo::command::Hold{o.state.position_m, std::nullopt};
    } else {
      result.command = campo::command::GoTo{o.mission[next_].position_m, speed_mps_, true};
    }
    return result;
  }
  nlohmann::json parameters() const override { return {{"speed_mps", speed_mps_}}; }

 private:
  double speed_mps_;
  std::size_t next_ = 0;
};

class HoldPlanner final : public campo::Planner {
 public:
  explicit HoldPlanner(double hold_s) : hold_s_(hold_s) {}
  campo::PlanResult plan(const campo::Observation& o) override {
    if (!start_) start_ = o.state.position_m;
    campo::PlanResult result;
    result.command = campo::command::Hold{*start_, std::nullopt};
    if (o.time_s >= hold_s_) {
      result.status = campo::PlanStatus::aborted;
      result.reason = "held for " + std::to_string(hold_s_) + " s";
    }
    return result;
  }
  nlohmann::json parameters() const override { return {{"hold_s", hold_s_}}; }

 private:
  double hold_s_;
  std::optional<Eigen::Vector3d> start_;
};

std::unique_ptr<campo::Planner> make_goto(const campo::ParamsBlock& params, const campo::PlannerContext&) {
  double speed_mps = 1.0;
  campo::ObjectReader r(campo::JsonNode(params.values, params.file, params.pointer));
  r.read("speed_mps", speed_mps, campo::Range::closed(0.1, 5.0));
  r.finish();
  return std::make_unique<GotoPlanner>(speed_mps);
}

std::unique_ptr<campo::Planner> make_hold(const campo::ParamsBlock& params, const campo::PlannerContext&) {
  double hold_s = 1.0;
  campo::ObjectReader r(campo::JsonNode(params.values, params.file, params.pointer));
  r.read("hold_s", hold_s, campo::Range::positive());
  r.finish();
  return std::make_unique<HoldPlanner>(hold_s);
}

}  // namespace

CAMPO_REGISTER_PLANNERS(registrar) {
  // Quadrotor only: it measures reaching in 3D, and a rover body never gets within 0.3 m of a waypoint on the ground.
  registrar.add({"fixture_goto", "fixture: straight to each waypoint", &make_goto, {campo::VehicleType::quadrotor}});
  registrar.add({"fixture_hold", "fixture: hold the start, then give up", &make_hold, {campo::VehicleType::quadrotor, campo::VehicleType::rover}});
}
