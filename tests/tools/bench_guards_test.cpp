// The speed figures docs/PERFORMANCE.md states its targets on, guarded: `campo bench guards
// --instructions` counts them under callgrind (LIDAR instructions per ray, physics steps of
// the quadrotor over the trees and the rover in the vineyard, depth_reactive's replanning at
// 256 x 256 on both seed 000 scenes, OctoMap's mapping of a 64 x 8 scan) and --compare holds
// each against bench/instruction_guards.json. Counts of one build agree to 0.1% from run to
// run; the margin (25%) covers other CPUs' library paths, so only a real regression fails.
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.hpp"
#include "tests/sanitizers.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

class BenchGuards : public testing::CliTest {};

const std::string kBaseline = std::string(CAMPO_SOURCE_DIR) + "/bench/instruction_guards.json";

TEST_F(BenchGuards, EveryGuardedFigureHoldsItsBaseline) {
#if defined(CAMPO_TEST_UNDER_ASAN)
  GTEST_SKIP() << "valgrind cannot run an AddressSanitizer build; the plain build runs this test";
#endif
  const std::string record = (dir_ / "guards.json").string();
  const auto guarded = campo("bench guards --instructions --tolerance 0.25 --json " + record + " --compare " + kBaseline);
  EXPECT_EQ(guarded.exit_code, 0) << guarded.out << guarded.err;
  EXPECT_THAT(guarded.out, Not(HasSubstr("SLOWER")));
  EXPECT_THAT(guarded.out, Not(HasSubstr("not in the baseline")));
  EXPECT_THAT(guarded.out, Not(HasSubstr("not comparable")));

  // The same figures as the baseline, each a count: none left unguarded, none stale.
  const nlohmann::json measured = nlohmann::json::parse(testing::slurp(record));
  const nlohmann::json baseline = nlohmann::json::parse(testing::slurp(kBaseline));
  std::set<std::string> measured_ids, baseline_ids;
  for (const auto& f : measured["figures"]) {
    measured_ids.insert(f["id"].get<std::string>());
    EXPECT_THAT(f["unit"].get<std::string>(), ::testing::StartsWith("instructions/"));
  }
  for (const auto& f : baseline["figures"]) baseline_ids.insert(f["id"].get<std::string>());
  EXPECT_EQ(measured_ids, baseline_ids);
  for (const char* id : {"lidar_scanner3d/trees_rolling_terrain/256", "lidar_scanner3d/vineyard/256",
                         "episode/trees_rolling_terrain/0", "episode/vineyard/0",
                         "replan/depth_reactive/two_barriers/256", "replan/depth_reactive/trees_rolling_terrain/256",
                         "mapping/octomap/bridge/64x8"}) {
    EXPECT_TRUE(measured_ids.count(id)) << id;
  }
}

}  // namespace
}  // namespace campo
