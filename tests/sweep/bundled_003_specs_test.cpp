// The sweep specs of seed 003's reproduction (campo reproduce) expand into valid runs of the sizes the report says.
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "campo/planner_registry.hpp"
#include "campo/vehicle_factory.hpp"
#include "sweep/expansion.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

std::size_t count_valid_runs(const std::string& file, std::set<std::string>* planners = nullptr) {
  const SweepSpec spec = read_sweep_spec(fs::path("scenes/sweeps") / file);
  const std::vector<SweepRun> runs = expand_sweep(spec, [](const Scene& scene) {
    for (const VehicleDef& vehicle : scene.vehicles) {
      validate_vehicle_params(vehicle);
      create_planner(vehicle.planner, {vehicle.type, &scene});
    }
  });
  if (planners) {
    for (const SweepRun& run : runs) planners->insert(run.planner);
  }
  return runs.size();
}

TEST(BundledSweeps, Seed003SpecsAreValid) {
  std::set<std::string> planners;
  // Fig. 45: 20 random draws for each of four follow-the-gap settings; the 5 m rows and boxes anywhere, 20 each.
  EXPECT_EQ(count_valid_runs("vineyard_random_003.json", &planners), 4u * 20u);
  EXPECT_EQ(planners, (std::set<std::string>{"campo", "printed_gaps", "printed", "bare"}));
  EXPECT_EQ(count_valid_runs("vineyard_random_rows5_003.json"), 20u);
  EXPECT_EQ(count_valid_runs("vineyard_random_anywhere_003.json"), 20u);
  // Fig. 46: 25 walker start times and speeds, campo's and the printed follow-the-gap.
  EXPECT_EQ(count_valid_runs("vineyard_gap_003.json"), 2u * 25u);
  EXPECT_EQ(count_valid_runs("vineyard_fig44_003.json"), 2u * 5u * 2u);
  EXPECT_EQ(count_valid_runs("vineyard_lookahead_003.json"), 5u);
  EXPECT_EQ(count_valid_runs("vineyard_offstart_003.json"), 10u);
}

}  // namespace
}  // namespace campo
