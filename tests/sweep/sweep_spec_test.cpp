// Sweep specs: strict reading, expansion into runs, start jitter.
#include "sweep/sweep_spec.hpp"

#include <filesystem>
#include <fstream>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "planners/registry.hpp"
#include "sim/json_reader.hpp"
#include "sweep/expansion.hpp"
#include "vehicles/vehicle.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class SweepSpecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_sweep_spec_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& text, const std::string& name = "spec.json") {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  // The error of reading and expanding `text`, or "" if it is valid.
  std::string error_of(const std::string& text) {
    try {
      expand_sweep(read_sweep_spec(write(text)));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(SweepSpecTest, ErrorsNameFilePointerAndExpectation) {
  const std::string spec = (dir_ / "spec.json").string();
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seed": 3})"),
              HasSubstr(spec + ": /seed: unknown key \"seed\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "speed", "values": [1], "set": ["/world/time_limit_s"], "colour": 1}]})"),
              HasSubstr(spec + ": /axes/0/colour: unknown key \"colour\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"count": "3"}})"),
              HasSubstr(spec + ": /seeds/count: expected an integer in [1, 100000], got \"3\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": "two_barriers"})"),
              HasSubstr(spec + ": /scenes: expected an array of 1 to 100 elements"));
  EXPECT_THAT(error_of(R"({"scenes": ["two_barriers"]})"), HasSubstr("missing required key \"campo_sweep\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "Speed", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ": /axes/0/name: expected an axis name"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "runs", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr("not also a table column"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "v", "values": [1, 1.0], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ": /axes/0/values/1: expected values with distinct labels"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "start_jitter": {"vehicle": "drone"}})"),
              HasSubstr(spec + ": /start_jitter: missing required key \"radius_m\""));
}

TEST_F(SweepSpecTest, BadPointersFailBeforeAnythingRuns) {
  const std::string spec = (dir_ / "spec.json").string();
  // Not a pointer at all.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"objects/drone": 1}})"),
              HasSubstr(spec + ": /set/objects~1drone: expected a JSON pointer"));
  // A pointer through an alias the scene does not have.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "set": {"/objects/drones/planner/name": "straight"}})"),
              HasSubstr(spec + ": /set/~1objects~1drones~1planner~1name: in scene two_barriers: no element with "
                               "alias \"drones\""));
  // A key the scene format does not know: the run's scene is validated, naming the run.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "x", "values": [1, 2], "set": ["/world/colour"]}]})"),
              HasSubstr(spec + ": /scenes/0: run two_barriers__x-1__seed-1: scenes/two_barriers.json: "
                               "/world/colour: unknown key"));
  // Two sources for one pointer, the seed included.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"/world/seed": 4}})"),
              HasSubstr(spec + ": /set/~1world~1seed: expected a pointer set in one place only"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"/world/time_limit_s": 4},
                           "axes": [{"name": "t", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ": /axes/0/set/0: expected a pointer set in one place only"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["missing.json"]})"),
              HasSubstr(spec + ": /scenes/0: cannot load the scene"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "start_jitter": {"vehicle": "goal", "radius_m": 1}})"),
              HasSubstr(spec + ": /start_jitter/vehicle: expected a vehicle of scene two_barriers, got \"goal\""));
}

TEST_F(SweepSpecTest, ExpandsScenesAxesAndSeedsInOrder) {
  // A scene beside the spec, by relative path, and a bundled one.
  fs::copy_file(fs::path(CAMPO_SOURCE_DIR) / "scenes/two_barriers.json", dir_ / "local.json");
  const SweepSpec spec = read_sweep_spec(write(R"({
    "campo_sweep": 1, "name": "order",
    "scenes": ["local.json", "two_barriers"],
    "set": {"/world/time_limit_s": 5, "/objects/drone/planner/name": "straight"},
    "axes": [{"name": "speed", "values": [0.5, 1], "set": ["/objects/drone/planner/params/speed_mps"]},
             {"name": "res", "values": [[16, 8], [32, 16], [64, 32]],
              "set": ["/objects/drone/sensors/scanner/resolution"]}],
    "seeds": {"first": 7, "count": 2}})"));
  EXPECT_EQ(spec.name, "order");
  const std::vector<SweepRun> runs = expand_sweep(spec);
  ASSERT_EQ(runs.size(), 2u * 2u * 3u * 2u);
  EXPECT_EQ(runs[0].id, "local__speed-0.5__res-16x8__seed-7");
  EXPECT_EQ(runs[1].id, "local__speed-0.5__res-16x8__seed-8");
  EXPECT_EQ(runs[2].id, "local__speed-0.5__res-32x16__seed-7");
  EXPECT_EQ(runs[6].id, "local__speed-1__res-16x8__seed-7");
  EXPECT_EQ(runs[12].id, "two_barriers__speed-0.5__res-16x8__seed-7");
  EXPECT_EQ(runs.back().id, "two_barriers__speed-1__res-64x32__seed-8");
  std::set<std::string> ids;
  for (const SweepRun& run : runs) ids.insert(run.id);
  EXPECT_EQ(ids.size(), runs.size());

  const SweepRun& run = runs[3];
  EXPECT_EQ(run.scene, "local");
  EXPECT_EQ(run.scene_file, dir_ / "local.json");
  EXPECT_EQ(run.seed, 8u);
  EXPECT_EQ(run.params, nlohmann::json({{"speed", 0.5}, {"res", {32, 16}}}));
  // Fixed overrides (by pointer), then the axes in order, then the seed.
  EXPECT_EQ(run.overrides, (std::vector<std::string>{"/objects/drone/planner/name=\"straight\"",
                                                     "/world/time_limit_s=5",
                                                     "/objects/drone/planner/params/speed_mps=0.5",
                                                     "/objects/drone/sensors/scanner/resolution=[32,16]",
                                                     "/world/seed=8"}));
  EXPECT_EQ(run.scene_sha256.size(), 64u);

  const nlohmann::json manifest = sweep_manifest(spec, runs);
  EXPECT_EQ(manifest["runs"].size(), runs.size());
  EXPECT_EQ(manifest["runs"][3]["id"], run.id);
  EXPECT_EQ(manifest["spec"]["name"], "order");
}

TEST_F(SweepSpecTest, NoAxesGiveOneRunPerSceneAndSeed) {
  const std::vector<SweepRun> runs =
      expand_sweep(read_sweep_spec(write(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"count": 3}})")));
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].id, "two_barriers__seed-1");
  EXPECT_EQ(runs[2].overrides, std::vector<std::string>{"/world/seed=3"});
  EXPECT_EQ(runs[0].params, nlohmann::json::object());
}

TEST_F(SweepSpecTest, ValueLabelsAreShortAndFilesystemSafe) {
  EXPECT_EQ(value_label(0.25), "0.25");
  EXPECT_EQ(value_label(256), "256");
  EXPECT_EQ(value_label(nlohmann::json({16, 8})), "16x8");
  EXPECT_EQ(value_label("a b/c"), "a b/c");
  EXPECT_EQ(value_id_label("a b/c"), "a_b_c");
  EXPECT_EQ(value_id_label(true), "true");
}

TEST(StartJitter, DeterministicInsideTheDiscAndDifferentPerSeed) {
  std::set<std::pair<double, double>> offsets;
  double farthest = 0.0;
  for (std::uint64_t seed = 0; seed < 500; ++seed) {
    const Eigen::Vector2d d = start_jitter_offset(seed, 0.25);
    EXPECT_EQ(d, start_jitter_offset(seed, 0.25));
    EXPECT_LE(d.norm(), 0.25);
    farthest = std::max(farthest, d.norm());
    offsets.insert({d.x(), d.y()});
  }
  EXPECT_EQ(offsets.size(), 500u);
  EXPECT_GT(farthest, 0.2);  // the whole disc is used, not only its centre
}

TEST_F(SweepSpecTest, StartJitterMovesTheSceneStartTheSameForEveryAxisValue) {
  const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(R"({
    "campo_sweep": 1, "scenes": ["two_barriers"],
    "axes": [{"name": "limit", "values": [5, 6], "set": ["/world/time_limit_s"]}],
    "seeds": {"first": 1, "count": 2},
    "start_jitter": {"vehicle": "drone", "radius_m": 0.25}})")));
  ASSERT_EQ(runs.size(), 4u);
  const auto start_of = [](const SweepRun& run) {
    const std::string& last = run.overrides.back();
    const std::string prefix = "/objects/drone/pose/position_m=";
    EXPECT_EQ(last.substr(0, prefix.size()), prefix);
    return nlohmann::json::parse(last.substr(prefix.size()));
  };
  // two_barriers starts the drone at (0, 0, 1.5).
  for (const SweepRun& run : runs) {
    const nlohmann::json p = start_of(run);
    const Eigen::Vector2d d = start_jitter_offset(run.seed, 0.25);
    EXPECT_DOUBLE_EQ(p[0].get<double>(), d.x());
    EXPECT_DOUBLE_EQ(p[1].get<double>(), d.y());
    EXPECT_DOUBLE_EQ(p[2].get<double>(), 1.5);
  }
  EXPECT_EQ(start_of(runs[0]), start_of(runs[2]));  // seed 1 at both limits
  EXPECT_NE(start_of(runs[0]), start_of(runs[1]));  // seeds 1 and 2
}

TEST(BundledSweeps, ResolutionSweepOfSeed000IsValid) {
  const SweepSpec spec = read_sweep_spec(fs::path("scenes/sweeps/resolution_000.json"));
  const std::vector<SweepRun> runs = expand_sweep(spec, [](const Scene& scene) {
    for (const VehicleDef& vehicle : scene.vehicles) {
      validate_vehicle_params(vehicle);
      create_planner(vehicle.planner, {vehicle.type, &scene});
    }
  });
  ASSERT_EQ(runs.size(), 2u * 5u * 3u);
  EXPECT_EQ(runs.front().id, "two_barriers__resolution-256__seed-1");
  EXPECT_EQ(runs.back().id, "trees_rolling_terrain__resolution-16__seed-3");
}

}  // namespace
}  // namespace campo
