// The planner contract (include/campo/planner.hpp), checked on every registered planner the
// same way, plugins included: typed statuses with reasons, determinism, no exception when
// sensors are missing or have not scanned yet, parameters that read back to themselves,
// other vehicle types refused with an InputError, and the goal reached on a trivial mission
// for every vehicle type the planner declares.
#include <cmath>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {
namespace {

// Open flat ground, the vehicle's usual sensor, one waypoint 6 m east. The quadrotor takes
// off from the ground and its waypoint is 7 m up (one level of seed 001's D* Lite grid above
// take-off ground: below that level the mapped ground blocks the grid).
std::string trivial_scene_json(VehicleType vehicle) {
  const bool quadrotor = vehicle == VehicleType::quadrotor;
  const std::string body =
      quadrotor ? R"("alias": "vehicle", "type": "quadrotor", "pose": {"position_m": [5.25, 5.25, 0.2]},
        "sensors": [{"alias": "scanner", "type": "lidar", "preset": "scanner3d", "mount": {"position_m": [0.15, 0, 0]}}],
        "mission": {"waypoints": [{"position_m": [11.25, 5.25, 7.0]}]})"
                : R"("alias": "vehicle", "type": "rover", "pose": {"position_m": [5.25, 5.25, 0.4]},
        "sensors": [{"alias": "scanner", "type": "lidar", "preset": "planar180", "mount": {"position_m": [0.75, 0, 0.25]}}],
        "mission": {"waypoints": [{"position_m": [11.25, 5.25, 0.0], "heading_deg": 0}]})";
  return R"({"campo_scene": 1, "name": "contract",
    "world": {"physics_step_s": 0.004166666666666667, "control_rate_hz": 60, "sensor_rate_hz": 10,
              "time_limit_s": 90, "seed": 0},
    "objects": [{"alias": "ground", "type": "plane"}, {)" +
         body + "}]}";
}

Scene trivial_scene(VehicleType vehicle, const std::string& planner) {
  Scene scene = load_scene_text(trivial_scene_json(vehicle), "contract.json");
  scene.vehicles[0].planner = PlannerSpec{planner, "", {nlohmann::json::object(), "contract.json", "/planner/params"}};
  return scene;
}

PlannerContext context_of(const Scene& scene) {
  return PlannerContext{scene.vehicles[0].type, &scene, &scene.vehicles[0]};
}

const VehicleType kVehicleTypes[] = {VehicleType::quadrotor, VehicleType::rover};

bool declares(const PlannerEntry& entry, VehicleType vehicle) {
  for (VehicleType v : entry.vehicles) {
    if (v == vehicle) return true;
  }
  return false;
}

bool valid_status(PlanStatus s) {
  switch (s) {
    case PlanStatus::running:
    case PlanStatus::reached:
    case PlanStatus::no_path:
    case PlanStatus::invalid_start:
    case PlanStatus::aborted:
      return true;
  }
  return false;
}

void expect_typed(const PlanResult& r, const std::string& where) {
  EXPECT_TRUE(valid_status(r.status)) << where;
  if (r.status != PlanStatus::running) EXPECT_FALSE(r.reason.empty()) << where << ": " << to_string(r.status);
}

// A planner under contract: a registered name, and the plugin that registers it (empty for
// built-in planners), loaded by the test that needs it so that other tests of this program
// see only the plugins they load themselves.
struct Contracted {
  std::string name;
  std::string plugin;
};

void PrintTo(const Contracted& c, std::ostream* os) { *os << c.name << (c.plugin.empty() ? "" : " of " + c.plugin); }

class PlannerContract : public ::testing::TestWithParam<Contracted> {
 protected:
  void SetUp() override {
    if (!GetParam().plugin.empty()) {
      load_planner_plugin(std::filesystem::path(CAMPO_TEST_PLUGIN_DIR) / GetParam().plugin, "contract test", "");
    }
    for (const PlannerEntry& e : planner_registry()) {
      if (e.name == GetParam().name) entry_ = e;
    }
    ASSERT_EQ(entry_.name, GetParam().name) << "not registered";
  }
  const PlannerEntry& entry() const { return entry_; }

 private:
  PlannerEntry entry_;
};

TEST_P(PlannerContract, DeclaresAtLeastOneVehicleTypeAndADescription) {
  EXPECT_FALSE(entry().vehicles.empty());
  EXPECT_FALSE(entry().description.empty());
}

TEST_P(PlannerContract, RefusesUndeclaredVehicleTypesWithAnInputError) {
  for (VehicleType v : kVehicleTypes) {
    if (declares(entry(), v)) continue;
    const Scene scene = trivial_scene(v, GetParam().name);
    EXPECT_THROW(create_planner(scene.vehicles[0].planner, context_of(scene)), InputError) << to_string(v);
  }
}

TEST_P(PlannerContract, ParametersReadBackToThemselves) {
  for (VehicleType v : kVehicleTypes) {
    if (!declares(entry(), v)) continue;
    Scene scene = trivial_scene(v, GetParam().name);
    const nlohmann::json first = create_planner(scene.vehicles[0].planner, context_of(scene))->parameters();
    ASSERT_TRUE(first.is_object());
    scene.vehicles[0].planner.params.values = first;
    EXPECT_EQ(create_planner(scene.vehicles[0].planner, context_of(scene))->parameters(), first) << to_string(v);
  }
}

TEST_P(PlannerContract, NoExceptionWithoutSensorsOrBeforeTheFirstScan) {
  for (VehicleType v : kVehicleTypes) {
    if (!declares(entry(), v)) continue;
    const Scene scene = trivial_scene(v, GetParam().name);
    const VehicleDef& def = scene.vehicles[0];
    Observation o;
    o.vehicle = v;
    o.state.position_m = def.pose.translation();
    o.state.orientation = Eigen::Quaterniond(def.pose.rotation());
    o.stable = true;
    o.mission = def.mission;

    const auto planner = create_planner(def.planner, context_of(scene));
    PlanResult r;
    ASSERT_NO_THROW(r = planner->plan(o)) << "no sensors, " << to_string(v);
    expect_typed(r, "no sensors");

    const SensorReading unscanned{def.sensors[0].alias, &def.sensors[0].range, nullptr, false};
    o.sensors = std::span<const SensorReading>(&unscanned, 1);
    const auto fresh = create_planner(def.planner, context_of(scene));
    for (int call = 0; call < 3; ++call) {
      o.time_s = call / 60.0;
      ASSERT_NO_THROW(r = fresh->plan(o)) << "no scan yet, call " << call << ", " << to_string(v);
      expect_typed(r, "no scan yet");
    }
  }
}

TEST_P(PlannerContract, ReachesATrivialMissionDeterministicallyWithTypedStatuses) {
  for (VehicleType v : kVehicleTypes) {
    if (!declares(entry(), v)) continue;
    const Scene scene = trivial_scene(v, GetParam().name);
    EpisodeOptions options;
    options.make_sensor = range_sensor_factory();
    int calls = 0;
    options.on_plan = [&](std::size_t, const Observation&, const PlanResult& r) {
      ++calls;
      expect_typed(r, "closed loop");
    };
    const EpisodeResult a = run_episode(scene, &make_vehicle, &create_planner, options);
    EXPECT_EQ(a.only().metrics.outcome, Outcome::reached) << to_string(v) << ": " << a.only().metrics.reason;
    EXPECT_GT(calls, 0);
    // 6 m (rover) or 9.2 m (quadrotor) away: a path more than twice that long is no "trivial" success.
    EXPECT_LT(a.only().metrics.path_length_m,
              2.0 * (scene.vehicles[0].mission[0].position_m - scene.vehicles[0].pose.translation()).norm())
        << to_string(v);

    options.on_plan = nullptr;
    const EpisodeResult b = run_episode(scene, &make_vehicle, &create_planner, options);
    EXPECT_EQ(a.final_state_hash, b.final_state_hash) << to_string(v);
    EXPECT_EQ(a.only().metrics.path_length_m, b.only().metrics.path_length_m) << to_string(v);
  }
}

// Every built-in planner, the example plugin's (examples/planner_plugin, built in the tree as a
// fixture) and the fixture plugin's planner that is meant to work.
std::vector<Contracted> contracted() {
  std::vector<Contracted> all;
  for (const PlannerEntry& e : planner_registry()) all.push_back({e.name, ""});
  all.push_back({"lidar_steer", "lidar_steer.so"});
  all.push_back({"fixture_goto", "two_planners.so"});
  return all;
}

INSTANTIATE_TEST_SUITE_P(Registered, PlannerContract, ::testing::ValuesIn(contracted()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace campo
