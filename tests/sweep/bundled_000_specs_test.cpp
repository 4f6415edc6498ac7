// The sweep specs of seed 000's reproduction (campo reproduce) expand into valid runs of the sizes the report says,
// and the thesis's trees differ from the bundled ones in exactly what the report's departure lists.
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/vehicle_factory.hpp"
#include "sweep/expansion.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

std::size_t valid_runs(const std::string& file, std::set<std::string>* planners = nullptr) {
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

TEST(BundledSweeps, Seed000SpecsAreValid) {
  // Table 5.1: two scenes, five resolutions, ten seeds; the thesis's trees beside; both printed planners beside.
  EXPECT_EQ(valid_runs("resolution_000.json"), 2u * 5u * 10u);
  EXPECT_EQ(valid_runs("resolution_thesis_trees_000.json"), 5u * 10u);
  std::set<std::string> planners;
  EXPECT_EQ(valid_runs("resolution_printed_000.json", &planners), 2u * 2u * 5u * 10u);
  EXPECT_EQ(planners, (std::set<std::string>{"printed_checks", "printed"}));
}

TEST(BundledSweeps, TheThesisTreesDifferOnlyInCountCrownHeightAndRelief) {
  nlohmann::json bundled = read_json_file("scenes/trees_rolling_terrain.json");
  nlohmann::json thesis = read_json_file("scenes/thesis/trees_rolling_terrain_000.json");
  const auto object = [](nlohmann::json& scene, const std::string& alias) -> nlohmann::json& {
    for (nlohmann::json& o : scene.at("objects")) {
      if (o.at("alias") == alias) return o;
    }
    throw std::runtime_error("no " + alias);
  };
  EXPECT_EQ(object(thesis, "forest").at("count"), 30);
  EXPECT_EQ(object(bundled, "forest").at("count"), 20);
  EXPECT_EQ(object(thesis, "forest").at("trunk_height_m"), nlohmann::json({2.5, 4.0}));
  EXPECT_EQ(object(thesis, "terrain").at("amplitude_m"), 1.5);
  EXPECT_EQ(object(bundled, "terrain").at("amplitude_m"), 3.0);
  // Everything else is the same.
  for (nlohmann::json* scene : {&bundled, &thesis}) {
    (*scene).erase("name");
    (*scene).erase("description");
    object(*scene, "forest").erase("count");
    object(*scene, "forest").erase("trunk_height_m");
    object(*scene, "terrain").erase("amplitude_m");
  }
  EXPECT_EQ(bundled, thesis);
}

}  // namespace
}  // namespace campo
