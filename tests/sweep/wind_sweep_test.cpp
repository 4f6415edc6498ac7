// The world's wind as a sweep axis (/world/wind/speed_mps): each run's scene has the wind of
// its value, its world blows it, its run.json records it, and the runs fly differently.
#include <filesystem>
#include <map>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "campo/world.hpp"
#include "scene/scene_overrides.hpp"
#include "sweep/expansion.hpp"
#include "sweep/sweep_spec.hpp"
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using campo::testing::lines_of;
using campo::testing::Result;
using campo::testing::slurp;

// Two barriers with the straight planner for 5 s, the wind blowing toward +y at 0 or 6 m/s.
constexpr const char* kWindSpec = R"({
  "campo_sweep": 1,
  "name": "wind",
  "scenes": ["two_barriers"],
  "set": { "/objects/drone/planner/name": "straight", "/world/time_limit_s": 5,
           "/objects/drone/sensors/scanner/resolution": [16, 16], "/world/wind/direction_deg": 90 },
  "axes": [ { "name": "wind", "values": [0, 6], "set": ["/world/wind/speed_mps"] } ],
  "seeds": { "first": 1, "count": 1 }
})";

class WindSweep : public campo::testing::CliTest {};

campo::Scene wind_run_scene(const campo::SweepRun& run) {
  nlohmann::json document = campo::read_json_file(run.scene_file);
  for (const campo::SceneOverride& o : run.overrides) campo::apply_override(document, campo::parse_override(o.text));
  return campo::parse_scene(document, run.scene_file.string(), run.scene_file.parent_path());
}

TEST_F(WindSweep, EachRunsSceneAndWorldHaveItsWind) {
  const std::vector<campo::SweepRun> runs = campo::expand_sweep(campo::read_sweep_spec(write("wind.json", kWindSpec)));
  ASSERT_EQ(runs.size(), 2u);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const double speed = i == 0 ? 0.0 : 6.0;
    EXPECT_EQ(runs[i].params.at("wind"), speed);
    const campo::Scene scene = wind_run_scene(runs[i]);
    EXPECT_EQ(scene.world.wind.speed_mps, speed);
    const campo::World world(scene);
    const Eigen::Vector3d wind = world.wind_mps({0.0, 0.0, 2.0});
    EXPECT_NEAR((wind - Eigen::Vector3d(0.0, speed, 0.0)).norm(), 0.0, 1e-12);
  }
}

TEST_F(WindSweep, RunsRecordTheirWindAndFlyDifferently) {
  const Result sweep = campo("sweep " + write("wind.json", kWindSpec) + " --out " + (dir_ / "o").string() + " --keep-runs");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  std::map<double, nlohmann::json> record_of;  // by wind speed
  for (const std::string& text : lines_of(slurp(dir_ / "o" / "results.jsonl"))) {
    const nlohmann::json line = nlohmann::json::parse(text);
    EXPECT_EQ(line["status"], "completed");
    const nlohmann::json record =
        nlohmann::json::parse(slurp(dir_ / "o" / line["run_dir"].get<std::string>() / "run.json"));
    record_of[line["params"]["wind"].get<double>()] = record;
  }
  ASSERT_EQ(record_of.size(), 2u);
  for (const auto& [speed, record] : record_of) {
    const nlohmann::json& wind = record["parameters"]["world"]["wind"];
    EXPECT_EQ(wind["speed_mps"], speed);
    EXPECT_EQ(wind["direction_deg"], 90.0);
    EXPECT_EQ(wind["gust"], "none");
  }
  // A 6 m/s side wind moves the drone: the runs end in other states.
  EXPECT_NE(record_of[0.0]["final_state_hash"], record_of[6.0]["final_state_hash"]);
}

}  // namespace
