#include "sweep/expansion.hpp"

#include <cmath>
#include <numbers>
#include <string_view>

#include "sim/json_reader.hpp"
#include "sim/random.hpp"
#include "sim/scene_loader.hpp"
#include "sim/scene_overrides.hpp"

namespace campo {

namespace {

// FNV-1a, to name the start jitter's random stream by a word rather than a magic number.
constexpr std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return h;
}
constexpr std::uint64_t kStartJitterStream = fnv1a("start_jitter");

// An InputError's message without its "file: pointer: " prefix.
std::string message_of(const InputError& e) {
  const std::size_t prefix = e.file().size() + 2 + (e.pointer().empty() ? 0 : e.pointer().size() + 2);
  const std::string what = e.what();
  return prefix < what.size() ? what.substr(prefix) : what;
}

// The element of the scene's top-level "objects" with this alias, and its index.
std::pair<const nlohmann::json*, std::size_t> top_level_object(const nlohmann::json& document,
                                                               const std::string& alias) {
  const auto objects = document.find("objects");
  if (objects == document.end() || !objects->is_array()) return {nullptr, 0};
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const nlohmann::json& object = (*objects)[i];
    if (object.is_object() && object.value("alias", "") == alias) return {&object, i};
  }
  return {nullptr, 0};
}

// Builds the runs of one scene, each with its document validated.
class SceneExpander {
 public:
  SceneExpander(const SweepSpec& spec, const SweepScene& scene, const SceneCheck& check)
      : spec_(spec), scene_(scene), check_(check), spec_file_(spec.file.string()), scene_file_(scene.file.string()) {
    try {
      bytes_ = read_text_file(scene.file);
      document_ = parse_json_text(bytes_, scene_file_);
    } catch (const InputError& e) {
      throw InputError(spec_file_, scene.origin, std::string("cannot load the scene: ") + e.what());
    }
    sha256_ = sha256_hex(bytes_);
  }

  /// The run with the value values[axis][index[axis]] of every axis and this seed.
  SweepRun run(const std::vector<std::size_t>& index, std::uint64_t seed) const {
    SweepRun run;
    run.scene = scene_.label;
    run.scene_file = scene_.file;
    run.seed = seed;
    run.scene_sha256 = sha256_;
    run.params = nlohmann::json::object();
    run.id = scene_.label;
    for (std::size_t a = 0; a < spec_.axes.size(); ++a) {
      const SweepAxis& axis = spec_.axes[a];
      run.params[axis.name] = axis.values[index[a]];
      run.id += "__" + axis.name + "-" + value_id_label(axis.values[index[a]]);
    }
    run.id += "__seed-" + std::to_string(seed);

    nlohmann::json document = document_;
    for (const SweepOverride& o : spec_.set) apply(document, run, o.pointer, o.value, o.origin);
    for (std::size_t a = 0; a < spec_.axes.size(); ++a) {
      const SweepAxis& axis = spec_.axes[a];
      const std::string origin = child_pointer(axis.origin + "/values", index[a]);
      for (const std::string& pointer : axis.pointers) apply(document, run, pointer, axis.values[index[a]], origin);
    }
    apply(document, run, "/world/seed", seed, "/seeds");
    if (spec_.start_jitter) apply_start_jitter(document, run, *spec_.start_jitter);

    const Scene scene = validated(document, run);
    if (spec_.start_jitter && !scene.find_vehicle(spec_.start_jitter->vehicle)) {
      throw InputError(spec_file_, spec_.start_jitter->origin + "/vehicle",
                       "expected a vehicle of scene " + scene_.label + ", got \"" + spec_.start_jitter->vehicle + "\"");
    }
    return run;
  }

 private:
  // The run's scene, validated like a scene file; errors name the run.
  Scene validated(const nlohmann::json& document, const SweepRun& run) const {
    try {
      Scene scene = parse_scene(document, scene_file_, scene_.file.parent_path(), sha256_);
      if (check_) check_(scene);
      return scene;
    } catch (const InputError& e) {
      throw InputError(spec_file_, scene_.origin, "run " + run.id + ": " + e.what());
    }
  }

  // Applies one override to the document and records it in the run.
  void apply(nlohmann::json& document, SweepRun& run, const std::string& pointer, const nlohmann::json& value,
             const std::string& origin) const {
    const std::string assignment = pointer + "=" + value.dump();
    try {
      apply_override(document, assignment);
    } catch (const InputError& e) {
      throw InputError(spec_file_, origin, "in scene " + scene_.label + ": " + message_of(e));
    }
    run.overrides.push_back(assignment);
  }

  // The start moved within the disc, from the vehicle's position in the document so far.
  void apply_start_jitter(nlohmann::json& document, SweepRun& run, const StartJitter& jitter) const {
    const auto [vehicle, index] = top_level_object(document, jitter.vehicle);
    if (!vehicle) {
      throw InputError(spec_file_, jitter.origin + "/vehicle",
                       "expected the alias of a vehicle at the top level of \"objects\" in scene " + scene_.label +
                           ", got \"" + jitter.vehicle + "\"");
    }
    Eigen::Vector3d start = Eigen::Vector3d::Zero();  // the scene format's default position
    const auto pose = vehicle->find("pose");
    if (pose != vehicle->end() && pose->is_object() && pose->contains("position_m")) {
      const std::string pointer = child_pointer("/objects", index) + "/pose/position_m";
      start = JsonNode((*pose)["position_m"], scene_file_, pointer).as_vector3();
    }
    start.head<2>() += start_jitter_offset(run.seed, jitter.radius_m);
    apply(document, run, "/objects/" + jitter.vehicle + "/pose/position_m",
          nlohmann::json{start.x(), start.y(), start.z()}, jitter.origin);
  }

  const SweepSpec& spec_;
  const SweepScene& scene_;
  const SceneCheck& check_;
  std::string spec_file_;
  std::string scene_file_;
  std::string bytes_;
  nlohmann::json document_;
  std::string sha256_;
};

}  // namespace

std::vector<SweepRun> expand_sweep(const SweepSpec& spec, const SceneCheck& check) {
  std::vector<SweepRun> runs;
  for (const SweepScene& scene : spec.scenes) {
    const SceneExpander expander(spec, scene, check);
    // Odometer over the axes' value indices, the last axis turning fastest.
    std::vector<std::size_t> index(spec.axes.size(), 0);
    while (true) {
      for (int k = 0; k < spec.seed_count; ++k) runs.push_back(expander.run(index, spec.first_seed + k));
      std::size_t a = spec.axes.size();
      while (a > 0 && ++index[a - 1] == spec.axes[a - 1].values.size()) index[--a] = 0;
      if (a == 0) break;
    }
  }
  return runs;
}

Eigen::Vector2d start_jitter_offset(std::uint64_t seed, double radius_m) {
  Rng rng(Rng::derive_seed(seed, kStartJitterStream));
  // sqrt of a uniform radius fraction: uniform over the disc's area.
  const double r = radius_m * std::sqrt(rng.uniform01());
  const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
  return {r * std::cos(angle), r * std::sin(angle)};
}

nlohmann::json sweep_manifest(const SweepSpec& spec, const std::vector<SweepRun>& runs) {
  nlohmann::json list = nlohmann::json::array();
  for (const SweepRun& run : runs) {
    list.push_back({{"id", run.id},
                    {"scene", run.scene},
                    {"scene_file", run.scene_file.string()},
                    {"params", run.params},
                    {"seed", run.seed},
                    {"overrides", run.overrides}});
  }
  return {{"spec_file", spec.file.string()}, {"spec", spec.document}, {"runs", list}};
}

}  // namespace campo
