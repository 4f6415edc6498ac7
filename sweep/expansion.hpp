#pragma once
/// A sweep spec expanded into its runs (scene x axis values x seeds), each
/// validated before anything runs, and the manifest that records them.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/scene.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {

/// One run of a sweep.
struct SweepRun {
  std::string id;                      ///< stable and filesystem-safe: "two_barriers__resolution-256__seed-1"
  std::string scene;                   ///< the scene's label
  std::filesystem::path scene_file;
  nlohmann::json params;               ///< axis name -> value
  std::uint64_t seed = 0;              ///< written to /world/seed
  std::vector<std::string> overrides;  ///< "POINTER=JSON", in order: set, axes, seed, start jitter
  std::string scene_sha256;            ///< of the scene file's bytes
};

/// Extra validation of a run's scene (e.g. vehicle and planner parameters,
/// which live outside sim/); throws InputError.
using SceneCheck = std::function<void(const Scene&)>;

/// Expands the spec in order: scenes, then the axes' values (first axis
/// outermost), then seeds. Every run's scene is loaded with its overrides and
/// validated (parse_scene, then `check` if given); any error is an InputError
/// naming the spec file, the spec's JSON pointer and the run.
std::vector<SweepRun> expand_sweep(const SweepSpec& spec, const SceneCheck& check = {});

/// Horizontal offset of the start jitter of `seed`: uniform in the disc of
/// `radius_m`, from campo::Rng, the same for every scene and axis value of a
/// seed (so the values are compared from the same starts).
Eigen::Vector2d start_jitter_offset(std::uint64_t seed, double radius_m);

/// sweep.json: {"spec_file", "spec" (as read), "runs": [{id, scene,
/// scene_file, params, seed, overrides}]}.
nlohmann::json sweep_manifest(const SweepSpec& spec, const std::vector<SweepRun>& runs);

}  // namespace campo
