#pragma once
/// Closed-loop runs of the bundled scenes for the planner tests.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"
#include "scene/scene_overrides.hpp"

namespace campo::testing {

/// Runs scenes/NAME.json with `--set` style overrides applied; the scene must use `planner`.
inline EpisodeResult run_bundled(const std::string& name, const std::string& planner,
                                 const std::vector<std::string>& overrides = {}) {
  const std::string file = std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json";
  nlohmann::json document = nlohmann::json::parse(std::ifstream(file));
  for (const std::string& assignment : overrides) apply_override(document, parse_override(assignment));
  const Scene scene = parse_scene(document, file, std::filesystem::path(file).parent_path());
  EXPECT_EQ(scene.vehicles.front().planner.name, planner);
  return run_episode(scene, &make_vehicle, &create_planner);
}

/// Mission waypoints the planner reported reached (Decisions::reached_waypoints).
inline int waypoints_reached(const EpisodeResult& r) {
  int reached = 0;
  for (const PlannerEvent& e : r.only().events) reached += static_cast<int>(e.decisions.reached_waypoints.size());
  return reached;
}

}  // namespace campo::testing
