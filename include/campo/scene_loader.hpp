#pragma once
/// Reading scene files (SPEC §3, docs/scene-format.md) into a validated Scene.
/// This is the one place where scene JSON is interpreted; every error is an
/// InputError naming the file, the JSON pointer and what was expected.
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "campo/json_reader.hpp"
#include "campo/scene.hpp"

namespace campo {

/// Limits that stop hostile scene files from exhausting memory or time.
struct SceneLimits {
  InputLimits json;                    ///< file size and JSON nesting
  int max_objects = 10000;             ///< objects written in the file, children included
  int max_child_depth = 12;            ///< nesting of "children"
  long max_shapes = 200000;            ///< shapes after generator expansion
  int max_trees = 10000;               ///< per trees generator
  long max_vineyard_posts = 100000;    ///< per vineyard generator
  int max_generated_obstacles = 10000; ///< vineyard obstacles, grid boxes
  int max_grid_cells_per_axis = 10000; ///< grid_obstacles rows and cols
  int max_waypoints = 10000;           ///< per mission, and per mover path
  int max_vehicles = 64;
  int max_sensors = 16;                ///< per vehicle
  long max_beams = 2048L * 2048L;      ///< per sensor
  std::uintmax_t max_mesh_file_bytes = 128u << 20;  ///< one mesh file (and a glTF's buffers together)
  long max_mesh_triangles = 2'000'000;  ///< in all "mesh" objects of a scene together (and so in one)
};

/// Checks of the blocks that other modules interpret, run by the loader on
/// each vehicle as it reads it, so that their errors come with the scene's
/// own, in one list and in the order of the file (a check throws InputError).
/// A check sees the vehicle's type and the block it checks, read without
/// errors; the rest of the scene is not loaded yet (what needs it is checked
/// once the scene loads). Unset checks are skipped.
struct SceneChecks {
  std::function<void(const VehicleDef&)> vehicle_params;  ///< the vehicle's "params" (def.type, def.params)
  std::function<void(const VehicleDef&)> planner;         ///< the planner's name and "params" (def.type, def.planner)
};

/// Loads and validates a scene file. Relative data paths (CSV/PNG terrain)
/// are resolved against the file's directory.
Scene load_scene(const std::filesystem::path& path, const SceneLimits& limits = {});

/// load_scene of `text` as if it were the content of the file `path` (which names
/// it in errors and whose directory resolves relative data paths); the file is
/// not read. For the fuzz target (fuzz/) and scenes held in memory.
Scene load_scene_text(const std::string& text, const std::filesystem::path& path, const SceneLimits& limits = {},
                      const SceneChecks& checks = {});

/// Validates an already-parsed scene document; `source` names it in errors
/// and `base_dir` resolves relative data paths. `source_sha256` is stored as given.
Scene parse_scene(const nlohmann::json& document, const std::string& source,
                  const std::filesystem::path& base_dir, const std::string& source_sha256 = "",
                  const SceneLimits& limits = {}, const SceneChecks& checks = {});

/// Widest field of view a depth camera renders in one perspective view, degrees.
inline constexpr double kMaxDepthCameraFov_deg = 150.0;

/// Reads a sensor block (also used by `campo scan` overrides): its type, then
/// the "preset" if any, then the other keys over it.
SensorDef parse_sensor(const JsonNode& node, const SceneLimits& limits = {});

/// Hex SHA-256 of a byte string (provenance of input files).
std::string sha256_hex(const std::string& bytes);

}  // namespace campo
