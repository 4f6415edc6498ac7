// The mission's per-leg and per-gate metrics (metrics/mission_metrics.hpp):
// measured on hand-made trajectories, written through their declarations
// under the keys run.json has always had, and read back through them.
#include "metrics/mission_metrics.hpp"

#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "campo/json_reader.hpp"

namespace campo {
namespace {

TrajectorySample mission_sample_at(double t, double x, double y, double z) {
  TrajectorySample s;
  s.time_s = t;
  s.state.position_m = {x, y, z};
  return s;
}

// A quadrotor flying from (0, 0, 10) to waypoint A (10, 0, 10), then to B (10, 10, 10) through a gate.
struct TwoLegs : ::testing::Test {
  TwoLegs() {
    def.mission = {{{10, 0, 10}}, {{10, 10, 10}}};
    def.gates = {{"slot", Eigen::AlignedBox2d(Eigen::Vector2d(9, 4), Eigen::Vector2d(11, 6)), 5.0},
                 {"never", Eigen::AlignedBox2d(Eigen::Vector2d(-9, -9), Eigen::Vector2d(-8, -8)), std::nullopt}};
    trajectory = {mission_sample_at(0, 0, 0, 10), mission_sample_at(1, 5, 0, 10), mission_sample_at(2, 10, 0, 10),
                  mission_sample_at(3, 10, 5, 10), mission_sample_at(4, 10, 5, 10), mission_sample_at(5, 10, 10, 10)};
    // Heights above ground: the gate's ceiling of 5 m is met from t = 4 only.
    for (std::size_t i = 0; i < trajectory.size(); ++i) trajectory[i].height_above_ground_m = i >= 4 ? 3.0 : 8.0;
  }
  VehicleDef def;
  const Eigen::Vector3d start{0, 0, 10};
  std::vector<TrajectorySample> trajectory;
};

TEST_F(TwoLegs, EachLegIsMeasuredBetweenTheSamplesThatReachedItsEnds) {
  const std::vector<std::optional<std::size_t>> reached{2, 5};
  nlohmann::json record;
  write_mission_metrics(def, start, trajectory, reached, record);
  EXPECT_DOUBLE_EQ(*get_unless_null(record, LegMetricFields(0).path_length_m), 10.0);
  EXPECT_DOUBLE_EQ(*get_unless_null(record, LegMetricFields(1).path_length_m), 10.0);  // samples 2 to 5
  EXPECT_EQ(get_unless_null(record, LegMetricFields(0).lateral_before_climb_m), std::nullopt);  // level: no climb
  EXPECT_EQ(GateMetricFields("slot").passed.get(record), true);
  EXPECT_EQ(get_unless_null(record, GateMetricFields("slot").time_s), 4.0);
  EXPECT_EQ(GateMetricFields("never").passed.get(record), false);
  EXPECT_EQ(get_unless_null(record, GateMetricFields("never").time_s), std::nullopt);
  // Under run.json's keys, unmeasured ones present as null, and nothing else.
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "leg0_path_length_m": 10.0, "leg0_lateral_before_climb_m": null,
    "leg1_path_length_m": 10.0, "leg1_lateral_before_climb_m": null,
    "gate_slot_passed": true, "gate_slot_time_s": 4.0,
    "gate_never_passed": false, "gate_never_time_s": null})");
  EXPECT_EQ(record, expected);
  // Every key written is declared, in mission_metric_fields' order: legs, then gates.
  const RecordFields fields = mission_metric_fields(def);
  std::vector<std::string> declared;
  for (const RecordFieldInfo& f : fields.fields()) declared.push_back(f.name);
  EXPECT_EQ(declared, (std::vector<std::string>{"leg0_path_length_m", "leg0_lateral_before_climb_m",
                                                "leg1_path_length_m", "leg1_lateral_before_climb_m",
                                                "gate_slot_passed", "gate_slot_time_s", "gate_never_passed",
                                                "gate_never_time_s"}));
  EXPECT_EQ(fields.find("gate_slot_passed")->type, RecordType::flag);
  EXPECT_EQ(fields.find("gate_slot_time_s")->unit, "s");
}

TEST_F(TwoLegs, ALegWithAnEndNotReachedIsNull) {
  // Waypoint A never reported reached: neither leg has a length (leg 1 has no first sample).
  const std::vector<std::optional<std::size_t>> b_only{std::nullopt, 5};
  nlohmann::json record;
  write_mission_metrics(def, start, trajectory, b_only, record);
  ASSERT_TRUE(LegMetricFields(0).path_length_m.in(record));
  EXPECT_TRUE(record.at("leg0_path_length_m").is_null());
  EXPECT_EQ(get_unless_null(record, LegMetricFields(0).path_length_m), std::nullopt);
  EXPECT_EQ(get_unless_null(record, LegMetricFields(1).path_length_m), std::nullopt);
}

TEST_F(TwoLegs, ALegThatClimbsReportsHowFarItMovedSidewaysFirst) {
  // Leg 0 flown 3 m to the side of its line, then up 6 m over a wall, then on: 3 m sideways before the climb.
  trajectory = {mission_sample_at(0, 0, 0, 10), mission_sample_at(1, 3, 3, 10), mission_sample_at(2, 5, 0, 16), mission_sample_at(3, 10, 0, 10)};
  const std::vector<std::optional<std::size_t>> reached{3, std::nullopt};
  nlohmann::json record;
  write_mission_metrics(def, start, trajectory, reached, record);
  EXPECT_DOUBLE_EQ(*get_unless_null(record, LegMetricFields(0).lateral_before_climb_m), 3.0);
  EXPECT_EQ(get_unless_null(record, LegMetricFields(1).lateral_before_climb_m), std::nullopt);
}

TEST(MissionMetricFields, AReaderRefusesAValueOfAnotherType) {
  const nlohmann::json record = {{"leg2_path_length_m", "far"}, {"gate_roof_passed", 1}};
  EXPECT_THROW(get_unless_null(record, LegMetricFields(2).path_length_m), InputError);
  EXPECT_THROW(GateMetricFields("roof").passed.get(record), InputError);
  EXPECT_EQ(get_unless_null(record, LegMetricFields(3).path_length_m), std::nullopt);  // absent
  EXPECT_EQ(get_unless_null(nlohmann::json(), LegMetricFields(0).path_length_m), std::nullopt);
}

}  // namespace
}  // namespace campo
