#pragma once
/// A small sweep's results.jsonl and sweep.json, written by hand, for the
/// table and plot tests: scenes two_barriers and trees, resolution 32 then
/// 16 (expansion order), seeds 1-3, some runs failed, one metric missing in
/// one run. The lines are in a shuffled order; the manifest gives the order.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sweep/results.hpp"

namespace campo::testing {

/// A results.jsonl line in the current format (content-hash id, name, planner ...), as JSON to adjust.
inline nlohmann::json fixture_run(const std::string& scene, int resolution, int seed, const std::string& outcome,
                                  double ratio, double time, const nlohmann::json& clearance = nullptr) {
  const std::string name = scene + "__resolution-" + std::to_string(resolution) + "__seed-" + std::to_string(seed);
  nlohmann::json line = {{"id", "id-" + name}, {"name", name}, {"scene", scene}, {"planner", "depth_reactive"},
                         {"params", {{"resolution", resolution}}}, {"seed", seed}, {"overrides", nlohmann::json::array()},
                         {"campo_version", "0.1.0"}, {"git_rev", "abc"}, {"scene_sha256", "00"}, {"spec_sha256", "11"},
                         {"wall_time_s", 1.5}};
  if (outcome == "failed") {
    line["status"] = "failed";
    line["reason"] = "out of memory";
    line["run_dir"] = nullptr;
    line["metrics"] = nullptr;
    line["triage"] = {{"kind", "exception"}};
  } else {
    line["status"] = "completed";
    line["run_dir"] = "runs/" + name;
    line["metrics"] = {{"outcome", outcome}, {"reason", "r"}, {"path_length_m", 10.0 * ratio}, {"path_ratio", ratio},
                       {"sim_time_s", time}, {"collisions", outcome == "collision" ? 1 : 0},
                       {"min_clearance_m", clearance}, {"hovered", seed != 2}};
    line["trajectory_sha256"] = "trajectory-of-" + name;
  }
  return line;
}

/// fixture_run() as a line of text.
inline std::string fixture_line(const std::string& scene, int resolution, int seed, const std::string& outcome,
                                double ratio, double time, const nlohmann::json& clearance = nullptr) {
  return fixture_run(scene, resolution, seed, outcome, ratio, time, clearance).dump() + "\n";
}

/// The results, lines not in expansion order.
inline std::string fixture_results() {
  return fixture_line("trees", 16, 1, "timeout", 2.0, 100)                 //
         + fixture_line("two_barriers", 32, 1, "reached", 1.0, 10, 0.5)   //
         + fixture_line("two_barriers", 32, 2, "reached", 2.0, 20, 0.7)   //
         + fixture_line("two_barriers", 32, 3, "collision", 3.0, 30)      // no clearance
         + fixture_line("two_barriers", 16, 1, "reached", 1.5, 40, 0.2)   //
         + fixture_line("two_barriers", 16, 2, "failed", 0, 0)            //
         + fixture_line("two_barriers", 16, 3, "failed", 0, 0)            //
         + fixture_line("trees", 32, 1, "reached", 1.2, 50, 1.0)          //
         + fixture_line("trees", 32, 2, "reached", 1.4, 70, 1.0)          //
         + fixture_line("trees", 32, 3, "reached", 1.0, 60, 1.0)          //
         + fixture_line("trees", 16, 2, "timeout", 2.0, 100)              //
         + fixture_line("trees", 16, 3, "failed", 0, 0);
}

/// sweep.json: the spec (with `table` when given) and the runs in expansion order.
inline std::string fixture_manifest(const nlohmann::json& table = nullptr) {
  nlohmann::json spec = {{"campo_sweep", 1}, {"name", "res"}, {"scenes", {"two_barriers", "trees.json"}},
                         {"axes", {{{"name", "resolution"}, {"values", {32, 16}}, {"set", {"/objects/drone/x"}}}}},
                         {"seeds", {{"first", 1}, {"count", 3}}}};
  if (!table.is_null()) spec["table"] = table;
  nlohmann::json runs = nlohmann::json::array();
  for (const char* scene : {"two_barriers", "trees"}) {
    for (int resolution : {32, 16}) {
      for (int seed = 1; seed <= 3; ++seed) {
        const std::string name =
            std::string(scene) + "__resolution-" + std::to_string(resolution) + "__seed-" + std::to_string(seed);
        runs.push_back({{"id", "id-" + name}, {"name", name}, {"scene", scene}, {"seed", seed}});
      }
    }
  }
  return nlohmann::json{{"spec_file", "specs/res.json"}, {"spec", spec}, {"runs", runs}, {"spec_sha256", "11"}}
             .dump(2);
}

/// A test with the fixture's results.jsonl and sweep.json in a fresh
/// directory of its own, read back as the table and the plot read them.
class FixtureSweepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("campo_fixture_sweep_" + std::string(test->test_suite_name()) + "_" + test->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "results.jsonl") << fixture_results();
    std::ofstream(dir_ / "sweep.json") << fixture_manifest();
    runs_ = read_results(dir_ / "results.jsonl").runs;
    layout_ = table_layout(dir_, runs_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  std::vector<RunResult> runs_;
  TableLayout layout_;
};

}  // namespace campo::testing
