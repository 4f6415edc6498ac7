// A planner's own metrics (PlannerRecord::metrics and measure, campo/planner_record.hpp): measured at the
// end of a run from its recorded events and written into run.json's metrics beside the generic ones; a
// name that clashes with a generic or a mission metric refuses the run before it starts.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/planner_record.hpp"
#include "campo/planner_registry.hpp"
#include "campo/run_record.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"
#include "metrics/mission_metrics.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

// What the test planner records: its call number at every call (1, 2, ...), and as its metrics the sum of
// the recorded call numbers and the end time it was given.
struct CountingRecord {
  PlannerRecord description;
  RecordField<std::int64_t> call = description.decisions.declare<std::int64_t>("call", "", "the call's number, from 1");
  RecordField<std::int64_t> call_sum =
      description.metrics.declare<std::int64_t>("call_sum", "", "sum of the recorded call numbers");
  RecordField<double> end_s = description.metrics.declare<double>("end_s", "s", "when the run ended");

  CountingRecord() {
    description.measure = [this](const PlannerRun& run, nlohmann::json& out) {
      std::int64_t sum = 0;
      for (const PlannerEvent& e : run.events) sum += call.get(e.decisions.own).value_or(0);
      call_sum.set(out, sum);
      end_s.set(out, run.end_time_s);
    };
  }
  CountingRecord(const CountingRecord&) = delete;
};

const CountingRecord& counting_record() {
  static const CountingRecord record;
  return record;
}

// Flies to the mission's one waypoint, recording its call number.
class CountingPlanner final : public Planner {
 public:
  PlanResult plan(const Observation& o) override {
    PlanResult result;
    counting_record().call.set(result.decisions.own, ++calls_);
    const Eigen::Vector3d& goal = o.mission.front().position_m;
    if ((goal - o.state.position_m).norm() < 0.3) {
      result.status = PlanStatus::reached;
      result.decisions.reached_waypoints.push_back(0);
    }
    result.command = command::GoTo{goal, 1.0, true};
    return result;
  }
  nlohmann::json parameters() const override { return nlohmann::json::object(); }

 private:
  std::int64_t calls_ = 0;
};

std::unique_ptr<Planner> make_counting(const ParamsBlock&, const PlannerContext&) {
  return std::make_unique<CountingPlanner>();
}

// Records whose metric names are another metric's, and one whose measure writes what it did not declare.
struct ClashingRecords {
  PlannerRecord generic, mission, undeclared;
  ClashingRecords() {
    generic.metrics.declare<double>("path_length_m", "m", "a generic metric's name");
    mission.metrics.declare<double>("leg0_path_length_m", "m", "a mission metric's name");
    undeclared.metrics.declare<double>("declared_m", "m", "what it declares");
    undeclared.measure = [](const PlannerRun&, nlohmann::json& out) { out["not_declared_m"] = 1.0; };
  }
};

const ClashingRecords& clashing() {
  static const ClashingRecords records;
  return records;
}

// Registered once per process (the registry is global; ctest runs each test in its own process).
void register_test_planners() {
  static const bool registered = [] {
    const std::vector<VehicleType> quad = {VehicleType::quadrotor};
    add_linked_planners({{"counting", "test: records its call numbers", &make_counting, quad,
                          &counting_record().description},
                         {"clash_generic", "test", &make_counting, quad, &clashing().generic},
                         {"clash_mission", "test", &make_counting, quad, &clashing().mission},
                         {"measures_undeclared", "test", &make_counting, quad, &clashing().undeclared}},
                        "test_run");
    return true;
  }();
  (void)registered;
}

Scene one_waypoint_scene(const std::string& planner) {
  return parse_scene(nlohmann::json::parse(R"j({"world": {"time_limit_s": 20}, "objects": [
    {"alias": "floor", "type": "plane"},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
     "mission": {"waypoints": [{"position_m": [3, 0, 1.5]}]}, "planner": {"name": ")j" +
                                           planner + R"j("}}]})j"),
                     "inline.json", std::filesystem::temp_directory_path());
}

TEST(PlannerMetrics, AreMeasuredFromTheRecordedEventsIntoRunJson) {
  register_test_planners();
  const Scene scene = one_waypoint_scene("counting");
  const EpisodeResult result = run_episode(scene, &make_vehicle, &create_planner);
  ASSERT_EQ(result.only().metrics.outcome, Outcome::reached) << result.only().metrics.reason;
  const nlohmann::json metrics = run_json(scene, result, {}, {}).at("metrics");

  // Every call was recorded (its own field is never empty), numbered 1..n: the sum is n (n + 1) / 2.
  const std::int64_t n = metrics.at("planner_calls").get<std::int64_t>();
  ASSERT_GT(n, 1);
  ASSERT_EQ(static_cast<std::int64_t>(result.only().events.size()), n);
  EXPECT_EQ(counting_record().call_sum.get(metrics), n * (n + 1) / 2);
  EXPECT_EQ(counting_record().end_s.get(metrics), metrics.at("sim_time_s").get<double>());
  // Read back through the declarations, as a reader of run.json would.
  counting_record().description.metrics.check(
      nlohmann::json{{"call_sum", metrics.at("call_sum")}, {"end_s", metrics.at("end_s")}}, "run.json", "/metrics");
  // Beside the generic ones and the mission's, which are all still there.
  EXPECT_TRUE(metrics.contains("path_length_m"));
  EXPECT_TRUE(metrics.contains("leg0_path_length_m"));
}

TEST(PlannerMetrics, AStraightRunGainsNoKey) {
  // A planner whose record declares no metrics changes nothing: the metrics are the generic ones and the mission's.
  const Scene scene = one_waypoint_scene("straight");
  const EpisodeResult result = run_episode(scene, &make_vehicle, &create_planner);
  nlohmann::json expected = nlohmann::json::object();
  const RecordFields mission = mission_metric_fields(scene.vehicles.front());
  for (const RecordFieldInfo& f : mission.fields()) expected[f.name] = true;
  nlohmann::json keys = nlohmann::json::object();
  for (const auto& [key, value] : result.only().metrics.declared.items()) keys[key] = true;
  EXPECT_EQ(keys, expected);
}

void expect_refused(const std::string& planner, const std::string& what) {
  register_test_planners();
  const Scene scene = one_waypoint_scene(planner);
  try {
    run_episode(scene, &make_vehicle, &create_planner);
    ADD_FAILURE() << planner << " was not refused";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("planner \"" + planner + "\""));
    EXPECT_THAT(e.what(), HasSubstr(what));
  }
}

TEST(PlannerMetrics, ANameOfAGenericMetricIsRefusedBeforeTheRun) {
  expect_refused("clash_generic", "declares metric \"path_length_m\", expected names other than");
}

TEST(PlannerMetrics, ANameOfAMissionMetricIsRefusedBeforeTheRun) {
  expect_refused("clash_mission", "declares metric \"leg0_path_length_m\", expected names other than");
}

TEST(PlannerMetrics, AMeasureWritingAnUndeclaredKeyIsRefused) {
  expect_refused("measures_undeclared", "not_declared_m");
}

}  // namespace
}  // namespace campo
