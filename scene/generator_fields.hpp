#pragma once
/// The keys of the generator objects (SPEC §3), declared once: the loader reads
/// them (the object's "alias", "type", "pose", "color" and "friction" it reads
/// itself), and docs/scene-format.md's tables are generated from them. Bounds
/// that are loader limits come from `limits`.
#include "campo/config_fields.hpp"
#include "campo/scene_loader.hpp"
#include "scene/generators.hpp"

namespace campo {

ConfigFields<RollingTerrainConfig> rolling_terrain_fields();
/// The loader checks afterwards that area_max_m > area_min_m (either may be the default).
ConfigFields<TreesConfig> trees_fields(const SceneLimits& limits = {});
ConfigFields<VineyardConfig> vineyard_fields(const SceneLimits& limits = {});
ConfigFields<GridObstaclesConfig> grid_obstacles_fields(const SceneLimits& limits = {});

}  // namespace campo
