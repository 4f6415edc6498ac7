#pragma once
/// Sweep spec files (docs/sweeps.md): which scenes, which fixed overrides,
/// which parameters to sweep over which values, how many seeds. Read strictly:
/// every error names the file, the JSON pointer and what was expected.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace campo {

/// A scene-document override: `value` written at the JSON `pointer` (aliases
/// may stand for array indices, as with `campo run --set`).
struct SweepOverride {
  std::string pointer;    ///< e.g. "/objects/drone/planner/name"
  nlohmann::json value;   ///< any JSON
  std::string origin;     ///< JSON pointer in the spec file it came from (for errors)
};

/// One scene of the sweep.
struct SweepScene {
  std::string label;           ///< run IDs and the table's scene column: bundled name or file stem
  std::filesystem::path file;  ///< the scene file
  std::string origin;          ///< JSON pointer in the spec file
};

/// One planner of the sweep, given to the scene's first vehicle.
struct SweepPlanner {
  std::string label;         ///< run names and the table's planner field: `label`, default the name
  std::string name;          ///< registry name
  nlohmann::json params;     ///< object: parameters set on top of the scene's (or alone, for another planner)
  std::string origin;        ///< JSON pointer in the spec file
};

/// A planner plugin the runs need (docs/extending.md).
struct SweepPlugin {
  std::filesystem::path file;  ///< the shared library, relative paths resolved against the spec file's folder
  std::string origin;          ///< JSON pointer in the spec file
};

/// One swept parameter: each value in turn is written to every pointer.
struct SweepAxis {
  std::string name;                   ///< [a-z][a-z0-9_]*, the table column and the ID label
  std::vector<nlohmann::json> values; ///< scalars or flat arrays, distinct, in spec order (from "values" or a stepped "range")
  /// A "range" without step or count: sampled uniformly in [from, to] (sampling only).
  std::optional<std::pair<double, double>> interval;
  std::vector<std::string> pointers;  ///< JSON pointers into the scene
  std::string origin;                 ///< JSON pointer of the axis in the spec file
};

/// Instead of every combination of the axes' values, `samples` points drawn
/// from them: each axis independently uniform (random) or stratified into
/// `samples` equal slices visited once each (Latin hypercube).
struct SweepSampling {
  enum class Method { random, latin_hypercube };
  Method method = Method::latin_hypercube;
  int samples = 1;          ///< >= 1
  std::uint64_t seed = 1;   ///< of the draws (not of the runs, which have their own seeds)
};

/// Moves a vehicle's start to a point uniformly distributed in a horizontal
/// disc around its scene start, drawn from the run's seed.
struct StartJitter {
  std::string vehicle;    ///< alias of a vehicle at the top level of the scene's "objects"
  double radius_m = 0.0;  ///< disc radius, > 0
  std::string origin;     ///< JSON pointer in the spec file
};

/// A validated sweep spec.
struct SweepSpec {
  std::filesystem::path file;            ///< the spec file
  nlohmann::json document;               ///< the spec as read
  std::string name;                      ///< default: the file stem
  std::string description;
  std::vector<SweepPlugin> plugins;      ///< distinct files, loaded before the runs are expanded
  std::vector<SweepScene> scenes;        ///< at least one, distinct labels
  std::vector<SweepPlanner> planners;    ///< empty: each scene's own planner
  std::vector<SweepOverride> set;        ///< fixed overrides, by pointer (parents before children)
  std::vector<SweepAxis> axes;           ///< cartesian product, the first axis outermost
  std::uint64_t first_seed = 1;          ///< run seeds first_seed .. first_seed + seed_count - 1
  int seed_count = 1;                    ///< >= 1
  std::optional<StartJitter> start_jitter;
  std::optional<SweepSampling> sampling;
  double time_limit_s = 3600.0;          ///< wall-clock limit of one run, after which it is stopped and recorded as failed
  /// Each run's seed also re-seeds every seeded scene generator (rolling
  /// terrain, trees, vineyard) of its scene, so the seeds vary the world
  /// (generator_seed); false: the generators keep the scene file's seeds.
  bool vary_scene_with_seed = false;
};

/// Limits that stop a spec from expanding beyond reason.
struct SweepLimits {
  std::size_t max_scenes = 100;
  std::size_t max_axes = 8;
  std::size_t max_values = 1000;    ///< per axis
  std::size_t max_planners = 100;
  std::size_t max_plugins = 16;
  std::size_t max_pointers = 64;    ///< per `set` and per axis
  int max_seeds = 100000;
  std::size_t max_runs = 100000;    ///< after expansion
};

/// Reads and validates a spec file. Scene entries ending in ".json" are paths
/// relative to the spec file; others name bundled scenes (sweep/bundled.hpp).
SweepSpec read_sweep_spec(const std::filesystem::path& file, const SweepLimits& limits = {});

/// read_sweep_spec of `text` as if it were the content of `file` (which names it
/// in errors and resolves relative scene paths); the file is not read. For the
/// fuzz target (fuzz/) and specs held in memory.
SweepSpec read_sweep_spec_text(const std::string& text, const std::filesystem::path& file,
                               const SweepLimits& limits = {});

/// Validates an already-parsed spec document; `file` names it in errors and
/// resolves relative scene paths.
SweepSpec parse_sweep_spec(const nlohmann::json& document, const std::filesystem::path& file,
                           const SweepLimits& limits = {});

/// The label of a parameter value in run IDs and tables: numbers in their
/// shortest form, strings as they are, arrays joined with 'x' ("256x256").
std::string value_label(const nlohmann::json& value);
/// `value` printed with `digits` significant digits and read back: short labels for computed values.
double round_significant(double value, int digits);
/// value_label() made filesystem-safe for run IDs: characters other than
/// letters, digits, '.', '_', '+' and '-' become '_'.
std::string value_id_label(const nlohmann::json& value);

}  // namespace campo
