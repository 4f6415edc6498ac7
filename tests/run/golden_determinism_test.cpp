// Golden determinism: fixed scenes and seed must end in committed world-state hashes,
// in process and through the program, whatever the number of worker processes (`campo
// sweep --jobs`) or the threads Embree, llvmpipe and TBB may use (`taskset` to one core).
//
// A change that alters any run's physics, sensing or planning changes these hashes: when the
// change is intended, run `build/campo run scenes/NAME.json --out DIR` and copy run.json's
// "final_state_hash" here (read it with a 64-bit integer reader; jq rounds it to a double),
// saying in the commit message why the runs changed.
#include <cstdint>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"
#include "sensors/fan_kernels.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

struct Golden {
  const char* scene;
  std::uint64_t final_state_hash;
  // Where a CPU without AVX2 casts the LIDAR ray by ray through Embree instead of as a fan:
  // the same run to the last digit printed, other last bits (0: no fan in this run).
  std::uint64_t final_state_hash_without_fan = 0;

  std::uint64_t expected() const {
    return final_state_hash_without_fan != 0 && !fan::kernels_available() ? final_state_hash_without_fan
                                                                            : final_state_hash;
  }
};

// One scene per family of planner and way of sensing: depth camera + depth_reactive
// (quadrotor), rover_route (rover, planar LIDAR cast ray by ray), dstar_lite_3d (quadrotor,
// LIDAR mapping), depth_reactive over terrain and trees (a 256 x 256 LIDAR cast as a fan on
// an AVX2 CPU), and four quadrotors with depth_reactive in one world, each sensing the
// others (several vehicles, issue 33). Seed 0, the scenes' own settings.
constexpr Golden kGolden[] = {
    {"two_barriers", 13199764301223187531ULL},
    {"vineyard", 9546240697463451486ULL},
    {"zigzag", 16317398135073404678ULL},
    {"trees_rolling_terrain", 17313695312406008818ULL, 15540033448196965860ULL},
    {"four_drones_crossing", 9328167319752546133ULL},
};

std::uint64_t hash_in(const fs::path& run_json) {
  std::ifstream in(run_json);
  const nlohmann::json record = nlohmann::json::parse(in);
  return record.at("final_state_hash").get<std::uint64_t>();
}

class GoldenDeterminism : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("campo_golden_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    spec_ = dir_ / "golden.json";
    std::ofstream(spec_) << R"({"campo_sweep": 1, "name": "golden",
                                "scenes": ["two_barriers", "vineyard", "zigzag", "trees_rolling_terrain",
                                           "four_drones_crossing"],
                                "seeds": {"first": 0, "count": 1}})";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs the sweep with `prefix` before the program (e.g. "taskset -c 0") and checks every
  // kept run's hash.
  void expect_sweep_golden(const std::string& prefix, int jobs) {
    const fs::path out = dir_ / ("sweep_jobs" + std::to_string(jobs));
    const std::string command = prefix + " " + CAMPO_BINARY + " sweep " + spec_.string() + " --out " + out.string() +
                                " --jobs " + std::to_string(jobs) + " --keep-runs >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    for (const Golden& g : kGolden) {
      EXPECT_EQ(hash_in(out / "runs" / (std::string(g.scene) + "__seed-0") / "run.json"), g.expected())
          << g.scene << " with " << command;
    }
  }

  fs::path dir_;
  fs::path spec_;
};

TEST_F(GoldenDeterminism, InProcessRunsEndInTheCommittedStateHashes) {
  for (const Golden& g : kGolden) {
    const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + g.scene + ".json");
    EpisodeOptions options;
    options.make_sensor = range_sensor_factory();
    const EpisodeResult result = run_episode(scene, &make_vehicle, &create_planner, options);
    EXPECT_EQ(result.final_state_hash, g.expected()) << g.scene;
  }
}

TEST_F(GoldenDeterminism, SweepRunsEndInTheCommittedStateHashesWithTwoWorkers) { expect_sweep_golden("", 2); }

TEST_F(GoldenDeterminism, SweepRunsEndInTheCommittedStateHashesOnOneCore) {
  if (std::system("taskset -c 0 true >/dev/null 2>&1") != 0) GTEST_SKIP() << "taskset cannot pin to core 0 here";
  expect_sweep_golden("taskset -c 0", 1);
}

}  // namespace
}  // namespace campo
