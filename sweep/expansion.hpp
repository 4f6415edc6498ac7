#pragma once
/// A sweep spec expanded into its runs (scene x axis values x seeds), each
/// validated before anything runs, and the manifest that records them.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/scene.hpp"
#include "scene/scene_overrides.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {

/// One run of a sweep.
struct SweepRun {
  /// 16 hex digits of the SHA-256 of the campo version, the run's name and
  /// its effective scene document (scene, every override, the seed): the same
  /// run has the same ID in every spec, order and shard.
  std::string id;
  std::string name;                    ///< readable and filesystem-safe: "two_barriers__resolution-256__seed-1" (the scene's name, value_id_label)
  /// The scene's name (its "name", else its file's stem): what run.json's
  /// provenance, replays and videos call it; in results and tables too.
  std::string scene;
  std::string planner;                 ///< the planner's label (the scene's planner name without "planners")
  std::filesystem::path scene_file;
  nlohmann::json params;               ///< axis name -> value
  std::uint64_t seed = 0;              ///< written to /world/seed
  /// In order: planner, set, axes, seed, generator seeds (vary_scene_with_seed), start jitter; their
  /// texts ("POINTER=JSON") are what the manifest and results record.
  std::vector<SceneOverride> overrides;
  std::string scene_sha256;            ///< of the scene file's bytes
};

/// Extra validation of a run's scene (e.g. vehicle and planner parameters,
/// which live outside scene/); throws InputError.
using SceneCheck = std::function<void(const Scene&)>;

/// The sampled axis values of a spec with "sampling": samples x axes, the same
/// for every scene and planner. Random: each value uniform; Latin hypercube:
/// each axis cut into `samples` equal slices, each slice drawn once, in an
/// order shuffled per axis. Intervals give numbers rounded to 6 significant
/// digits; value lists are sliced by index. Deterministic in the sampling seed.
std::vector<std::vector<nlohmann::json>> sample_axes(const SweepSpec& spec);

/// Expands the spec in order: scenes, then planners, then the axes' values
/// (first axis outermost) or the samples, then seeds. Every run's scene is loaded with its overrides and
/// validated (parse_scene, then `check` if given); any error is an InputError
/// naming the spec file, the spec's JSON pointer and the run.
std::vector<SweepRun> expand_sweep(const SweepSpec& spec, const SceneCheck& check = {});

/// expand_sweep's runs, in its order, each handed to `emit` as soon as it is
/// validated and then dropped: memory does not grow with the runs (`campo
/// sweep --list` of 100,000 runs). Runs that differ in their seed alone
/// (neither "vary_scene_with_seed" nor "start_jitter") share the validation
/// of their first seed: /world/seed changes nothing a check looks at. An
/// error may come after some runs were emitted.
void for_each_sweep_run(const SweepSpec& spec, const SceneCheck& check,
                        const std::function<void(const SweepRun&)>& emit);

/// Object types of the scene format whose shapes come from a seeded
/// generator (scene/generators.hpp), re-seeded by "vary_scene_with_seed".
inline constexpr std::array<std::string_view, 3> kSeededGeneratorTypes{"rolling_terrain", "trees", "vineyard"};

/// The seed "vary_scene_with_seed" gives the generator object `alias` in the
/// run of `seed`: Rng::derive_seed(seed, FNV-1a-64("vary_scene_with_seed/" +
/// alias)), kept to 53 bits. The same for every scene, planner and axis value
/// of a run seed (values compared on the same worlds), different per
/// generator (two patches of trees are not placed alike).
std::uint64_t generator_seed(std::uint64_t seed, const std::string& alias);

/// Horizontal offset of the start jitter of `seed`: uniform in the disc of
/// `radius_m`, from campo::Rng, the same for every scene and axis value of a
/// seed (so the values are compared from the same starts).
Eigen::Vector2d start_jitter_offset(std::uint64_t seed, double radius_m);

/// The run's line of the manifest: {id, name, scene, planner, params, seed, overrides, scene_file}.
nlohmann::json manifest_entry(const SweepRun& run);

/// sweep.json: {"spec_file", "spec" (as read), "spec_sha256" (of the spec
/// as read, canonical), "campo_version", "runs": [manifest_entry...]}.
nlohmann::json sweep_manifest(const SweepSpec& spec, const std::vector<SweepRun>& runs);

/// The spec's identity in results and merges: SHA-256 of its canonical JSON.
std::string spec_sha256(const SweepSpec& spec);

/// Shard `index` (1-based) of `count`: runs i with i mod count == index - 1,
/// so the shards are disjoint, cover the manifest, and differ in size by at most one.
std::vector<SweepRun> shard_of(const std::vector<SweepRun>& runs, int index, int count);

}  // namespace campo
