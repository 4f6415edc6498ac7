#include "sweep/expansion.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/random.hpp"
#include "campo/scene_loader.hpp"
#include "campo/version.hpp"
#include "scene/scene_overrides.hpp"

namespace campo {

namespace {

// FNV-1a, to name the start jitter's random stream by a word rather than a magic number.
constexpr std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return h;
}
constexpr std::uint64_t kStartJitterStream = fnv1a("start_jitter");

// A seeded generator object of a scene document and where it is.
struct GeneratorObject {
  std::string alias;
  std::string pointer;        ///< of its "seed", through aliases: "/objects/field/seed"
  std::string index_pointer;  ///< the same through indices: "/objects/1/seed"
};

// Every seeded generator among `objects` and their children, in document order.
void find_generators(const nlohmann::json& objects, const std::string& alias_path, const std::string& index_path,
                     std::vector<GeneratorObject>& found) {
  if (!objects.is_array()) return;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const nlohmann::json& object = objects[i];
    if (!object.is_object()) continue;
    const std::string alias = object.value("alias", "");
    // Aliases are required and unique (the scene is validated later); an index stands in for a bad one.
    const std::string by_alias = alias_path + "/" + (alias.empty() ? std::to_string(i) : alias);
    const std::string by_index = child_pointer(index_path, i);
    const std::string type = object.value("type", "");
    if (std::find(kSeededGeneratorTypes.begin(), kSeededGeneratorTypes.end(), type) != kSeededGeneratorTypes.end()) {
      found.push_back({alias, by_alias + "/seed", by_index + "/seed"});
    }
    if (const auto children = object.find("children"); children != object.end()) {
      find_generators(*children, by_alias + "/children", by_index + "/children", found);
    }
  }
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

// One point of the parameter space: a value per axis, and how runs name it.
struct AxisPoint {
  std::vector<nlohmann::json> values;  // one per axis
  std::vector<std::string> origins;    // spec pointer of each value, for errors
  std::string label;                   // "__resolution-256" or "__sample-3"
};

std::vector<AxisPoint> axis_points(const SweepSpec& spec) {
  std::vector<AxisPoint> points;
  if (spec.sampling) {
    const auto samples = sample_axes(spec);
    for (std::size_t s = 0; s < samples.size(); ++s) {
      AxisPoint point{samples[s], {}, "__sample-" + std::to_string(s + 1)};
      for (const SweepAxis& axis : spec.axes) point.origins.push_back(axis.origin);
      points.push_back(std::move(point));
    }
    return points;
  }
  // Odometer over the axes' value indices, the last axis turning fastest.
  std::vector<std::size_t> index(spec.axes.size(), 0);
  while (true) {
    AxisPoint point;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      const SweepAxis& axis = spec.axes[a];
      point.values.push_back(axis.values[index[a]]);
      point.origins.push_back(child_pointer(axis.origin + "/values", index[a]));
      point.label += "__" + axis.name + "-" + value_id_label(axis.values[index[a]]);
    }
    points.push_back(std::move(point));
    std::size_t a = spec.axes.size();
    while (a > 0 && ++index[a - 1] == spec.axes[a - 1].values.size()) index[--a] = 0;
    if (a == 0) break;
  }
  return points;
}

constexpr const char* kSeedPointer = "/world/seed";

// What the run is, not where it sits in the spec: its name (scene, planner,
// values, seed) and effective document (as text) give the same ID in any
// order or shard, and the name keeps identical documents apart (a scene under
// two names, a value drawn twice).
std::string run_id(const std::string& name, const std::string& document_text) {
  return sha256_hex(std::string(library_version()) + "\n" + name + "\n" + document_text).substr(0, 16);
}

// The text (dump()) of a document for any /world/seed, from two dumps: an
// unsigned integer is written as its digits and nothing else changes, so the
// texts at seeds 1 and 2 differ in that one character, and every seed's text
// is their common prefix, its digits, their common suffix. Saves a dump per
// run of a sweep (most of the time of `campo sweep --list`).
class SeededText {
 public:
  explicit SeededText(nlohmann::json document) {
    document["world"]["seed"] = std::uint64_t{1};
    const std::string one = document.dump();
    document["world"]["seed"] = std::uint64_t{2};
    const std::string two = document.dump();
    std::size_t p = 0;
    while (p < one.size() && one[p] == two[p]) ++p;
    if (one.size() != two.size() || p == one.size() || one.compare(p + 1, std::string::npos, two, p + 1) != 0) {
      throw std::logic_error("SeededText: the seed is not one digit of the document's text");
    }
    prefix_ = one.substr(0, p);
    suffix_ = one.substr(p + 1);
  }
  std::string with(std::uint64_t seed) const { return prefix_ + std::to_string(seed) + suffix_; }

 private:
  std::string prefix_, suffix_;
};

// Builds the runs of one scene, each with its document validated.
class SceneExpander {
 public:
  SceneExpander(const SweepSpec& spec, const SweepScene& scene, const SceneCheck& check)
      : spec_(spec), scene_(scene), check_(check), spec_file_(spec.file.string()), scene_file_(scene.file.string()) {
    try {
      bytes_ = read_text_file(scene.file);
      document_ = parse_json_text(bytes_, scene_file_);
      // Planners go to the first vehicle, as `campo run` drives it.
      const Scene base = parse_scene(document_, scene_file_, scene.file.parent_path(), "");
      // One name per scene: the one run.json's provenance, replays and videos give it (its "name",
      // else its file's stem), in results and tables too; run names need it filesystem-safe.
      name_ = base.name;
      name_id_ = value_id_label(nlohmann::json(name_));
      if (!base.vehicles.empty()) {
        vehicle_ = base.vehicles.front().alias;
        planner_ = base.vehicles.front().planner.name;
      }
    } catch (const InputError& e) {
      // Each error of the scene on a line of its own, with its place in the scene file.
      throw nested_error(with_locations(e, scene_file_, bytes_), spec_file_, scene.origin, "cannot load the scene: ");
    }
    sha256_ = sha256_hex(bytes_);
    if (!spec.planners.empty() && !top_level_object(document_, vehicle_).first) {
      throw InputError(spec_file_, "/planners",
                       "expected a scene whose first vehicle is at the top level of \"objects\" (scene " + name_ + ")");
    }
  }

  /// The runs of this planner (null: the scene's) and axis point, one per seed in order, each handed to
  /// `emit` once validated.
  void runs(const SweepPlanner* planner, const AxisPoint& point, const std::function<void(const SweepRun&)>& emit) {
    SweepRun run;
    run.scene = name_;
    if (planner) run.planner = planner->label;
    run.scene_file = scene_.file;
    run.scene_sha256 = sha256_;
    run.params = nlohmann::json::object();
    const std::string name = name_id_ + (planner ? "__" + planner->label : "") + point.label + "__seed-";
    run.name = name + std::to_string(spec_.first_seed);  // errors of the overrides below name the first run

    nlohmann::json document = document_;
    if (planner) apply_planner(document, run, *planner);
    for (const SweepOverride& o : spec_.set) apply(document, run, o.pointer, o.value, o.origin);
    for (std::size_t a = 0; a < spec_.axes.size(); ++a) {
      const SweepAxis& axis = spec_.axes[a];
      run.params[axis.name] = point.values[a];
      for (const std::string& pointer : axis.pointers) apply(document, run, pointer, point.values[a], point.origins[a]);
    }
    const std::size_t shared_overrides = run.overrides.size();
    // Without vary_scene_with_seed and start_jitter the seeds' documents differ in /world/seed alone, which
    // no check looks at (it only seeds noise, generators' streams and planners): the first seed's run is
    // validated and the others share its verdict, and their documents' text, which the IDs hash, is the
    // first one's with the seed's digits in place of its own (SeededText).
    const bool seed_only = !spec_.vary_scene_with_seed && !spec_.start_jitter;
    std::optional<SeededText> text;
    for (int k = 0; k < spec_.seed_count; ++k) {
      const std::uint64_t seed = spec_.first_seed + static_cast<std::uint64_t>(k);
      run.seed = seed;
      run.name = name + std::to_string(seed);
      run.overrides.resize(shared_overrides);
      if (text) {
        // As apply() records it; appended piece by piece (GCC 12 warns falsely, -Wrestrict, about "=" + string).
        std::string seed_override(kSeedPointer);
        seed_override += '=';
        seed_override += std::to_string(seed);
        run.overrides.push_back({kSeedPointer, seed, std::move(seed_override)});
        run.id = run_id(run.name, text->with(seed));
        emit(run);
        continue;
      }
      nlohmann::json copy;
      if (!seed_only) copy = document;
      nlohmann::json& seeded = seed_only ? document : copy;
      apply(seeded, run, kSeedPointer, seed, "/seeds");
      if (spec_.vary_scene_with_seed) apply_generator_seeds(seeded, run);
      if (spec_.start_jitter) apply_start_jitter(seeded, run, *spec_.start_jitter);

      if (!seed_only || k == 0) {
        const Scene scene = validated(seeded, run);
        if (!planner) {
          // The scene's planner as the overrides left it.
          const std::string& scene_planner = scene.vehicles.empty() ? std::string() : scene.vehicles.front().planner.name;
          run.planner = scene_planner.empty() ? std::string(kDefaultPlanner) : scene_planner;
        }
        if (spec_.start_jitter && !scene.find_vehicle(spec_.start_jitter->vehicle)) {
          throw InputError(spec_file_, spec_.start_jitter->origin + "/vehicle",
                           "expected a vehicle of scene " + name_ + ", got \"" + spec_.start_jitter->vehicle +
                               "\"");
        }
      }
      run.id = run_id(run.name, seeded.dump());
      emit(run);
      if (seed_only && spec_.seed_count > 1) text = SeededText(seeded);
    }
  }

  /// The most seeded generators re-seeded in one run's scene so far.
  std::size_t generators() const { return generators_; }
  /// The scene's name, as its runs and results call it.
  const std::string& name() const { return name_; }

 private:
  // The run's scene, validated like a scene file; errors name the run.
  Scene validated(const nlohmann::json& document, const SweepRun& run) const {
    try {
      Scene scene = parse_scene(document, scene_file_, scene_.file.parent_path(), sha256_);
      if (check_) check_(scene);
      return scene;
    } catch (const InputError& e) {
      throw nested_error(with_locations(with_aliases(e, scene_file_, document), scene_file_, bytes_), spec_file_,
                         scene_.origin, "run " + run.name + ": ");
    }
  }

  // Applies one override to the document and records it in the run.
  void apply(nlohmann::json& document, SweepRun& run, const std::string& pointer, const nlohmann::json& value,
             const std::string& origin) const {
    SceneOverride assignment = make_override(pointer, value);
    try {
      apply_override(document, assignment);
    } catch (const InputError& e) {
      throw InputError(spec_file_, origin, "in scene " + name_ + ": " + e.message());
    }
    run.overrides.push_back(std::move(assignment));
  }

  // The planner of the first vehicle: its parameters on top of the scene's
  // when it is the scene's planner, alone otherwise (the scene's belong to another planner).
  void apply_planner(nlohmann::json& document, SweepRun& run, const SweepPlanner& planner) const {
    const std::string base = "/objects/" + vehicle_ + "/planner";
    if (planner.name != planner_) {
      apply(document, run, base, {{"name", planner.name}, {"params", planner.params}}, planner.origin);
      return;
    }
    for (const auto& [key, value] : planner.params.items()) {
      apply(document, run, base + "/params/" + key, value, planner.origin + "/params/" + key);
    }
  }

  // Every seeded generator re-seeded from the run seed, as the document stands after set and the axes.
  void apply_generator_seeds(nlohmann::json& document, SweepRun& run) {
    std::vector<GeneratorObject> generators;
    if (const auto objects = document.find("objects"); objects != document.end()) {
      find_generators(*objects, "/objects", "/objects", generators);
    }
    for (const GeneratorObject& g : generators) {
      // The seed must have one writer, as every other pointer.
      const auto conflict = [&](const std::string& pointer, const std::string& origin) {
        if (pointer != g.pointer && pointer != g.index_pointer) return;
        throw InputError(spec_file_, "/vary_scene_with_seed",
                         "expected no other override of a generator's seed when the run seeds vary the scene (" +
                             pointer + " is also set at " + origin + ", scene " + name_ + ")");
      };
      for (const SweepOverride& o : spec_.set) conflict(o.pointer, o.origin);
      for (const SweepAxis& axis : spec_.axes) {
        for (const std::string& pointer : axis.pointers) conflict(pointer, axis.origin);
      }
      apply(document, run, g.pointer, generator_seed(run.seed, g.alias), "/vary_scene_with_seed");
    }
    generators_ = std::max(generators_, generators.size());
  }

  // The start moved within the disc, from the vehicle's position in the document so far.
  void apply_start_jitter(nlohmann::json& document, SweepRun& run, const StartJitter& jitter) const {
    const auto [vehicle, index] = top_level_object(document, jitter.vehicle);
    if (!vehicle) {
      throw InputError(spec_file_, jitter.origin + "/vehicle",
                       "expected the alias of a vehicle at the top level of \"objects\" in scene " + name_ +
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
  std::string vehicle_;  // alias of the first vehicle
  std::string planner_;  // its planner in the scene file
  std::size_t generators_ = 0;  // most seeded generators in one run's scene (vary_scene_with_seed)
  std::string name_;     // the scene's name (Scene::name)
  std::string name_id_;  // the same, filesystem-safe, in run names
};

}  // namespace

std::vector<std::vector<nlohmann::json>> sample_axes(const SweepSpec& spec) {
  if (!spec.sampling) return {};
  const auto n = static_cast<std::size_t>(spec.sampling->samples);
  const bool latin = spec.sampling->method == SweepSampling::Method::latin_hypercube;
  std::vector<std::vector<nlohmann::json>> samples(n);
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    // One stream per axis, so adding an axis does not change the others' draws.
    Rng rng(Rng::derive_seed(spec.sampling->seed, fnv1a(spec.axes[a].name)));
    std::vector<std::size_t> slice(n);
    std::iota(slice.begin(), slice.end(), std::size_t{0});
    if (latin) {
      for (std::size_t i = n; i > 1; --i) std::swap(slice[i - 1], slice[rng.uniform_int(0, static_cast<std::int64_t>(i - 1))]);
    }
    const SweepAxis& axis = spec.axes[a];
    for (std::size_t s = 0; s < n; ++s) {
      const double u = latin ? (static_cast<double>(slice[s]) + rng.uniform01()) / static_cast<double>(n) : rng.uniform01();
      if (axis.interval) {
        const auto [from, to] = *axis.interval;
        samples[s].emplace_back(round_significant(from + u * (to - from), 6));
      } else {
        const auto k = std::min(static_cast<std::size_t>(u * static_cast<double>(axis.values.size())), axis.values.size() - 1);
        samples[s].push_back(axis.values[k]);
      }
    }
  }
  return samples;
}

void for_each_sweep_run(const SweepSpec& spec, const SceneCheck& check,
                        const std::function<void(const SweepRun&)>& emit) {
  const std::vector<AxisPoint> points = axis_points(spec);
  std::vector<const SweepPlanner*> planners;
  for (const SweepPlanner& p : spec.planners) planners.push_back(&p);
  if (planners.empty()) planners.push_back(nullptr);  // each scene's own
  std::size_t generators = 0;
  std::map<std::string, std::string> scene_at;  // scene name -> where the spec names it
  for (const SweepScene& scene : spec.scenes) {
    SceneExpander expander(spec, scene, check);
    // Two files of one name would be one scene in every table.
    if (const auto [it, added] = scene_at.emplace(expander.name(), scene.origin); !added) {
      throw InputError(spec.file.string(), scene.origin,
                       "expected scenes with distinct names: " + scene.file.string() + " is named \"" + expander.name() +
                           "\" as the scene at " + it->second + " (set \"name\" in one of them)");
    }
    for (const SweepPlanner* planner : planners) {
      for (const AxisPoint& point : points) expander.runs(planner, point, emit);
    }
    generators += expander.generators();
  }
  // Asked to vary the scenes, a spec whose scenes have nothing to vary is a mistake, not a no-op.
  if (spec.vary_scene_with_seed && generators == 0) {
    std::string types;
    for (std::string_view t : kSeededGeneratorTypes) (types += types.empty() ? "" : ", ") += t;
    throw InputError(spec.file.string(), "/vary_scene_with_seed",
                     "expected a scene with a seeded generator (" + types + "), or false");
  }
}

std::vector<SweepRun> expand_sweep(const SweepSpec& spec, const SceneCheck& check) {
  std::vector<SweepRun> runs;
  for_each_sweep_run(spec, check, [&](const SweepRun& run) { runs.push_back(run); });
  return runs;
}

std::vector<SweepRun> shard_of(const std::vector<SweepRun>& runs, int index, int count) {
  std::vector<SweepRun> shard;
  for (std::size_t i = static_cast<std::size_t>(index - 1); i < runs.size(); i += static_cast<std::size_t>(count)) {
    shard.push_back(runs[i]);
  }
  return shard;
}

std::uint64_t generator_seed(std::uint64_t seed, const std::string& alias) {
  // 53 bits: JSON tools that read numbers as doubles (jq, JavaScript) keep the seed exact.
  return Rng::derive_seed(seed, fnv1a("vary_scene_with_seed/" + alias)) & ((std::uint64_t{1} << 53) - 1);
}

Eigen::Vector2d start_jitter_offset(std::uint64_t seed, double radius_m) {
  Rng rng(Rng::derive_seed(seed, kStartJitterStream));
  // sqrt of a uniform radius fraction: uniform over the disc's area.
  const double r = radius_m * std::sqrt(rng.uniform01());
  const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
  return {r * std::cos(angle), r * std::sin(angle)};
}

nlohmann::json manifest_entry(const SweepRun& run) {
  return {{"id", run.id},         {"name", run.name},           {"scene", run.scene},
          {"planner", run.planner}, {"params", run.params},     {"seed", run.seed},
          {"overrides", override_texts(run.overrides)}, {"scene_file", run.scene_file.string()}};
}

nlohmann::json sweep_manifest(const SweepSpec& spec, const std::vector<SweepRun>& runs) {
  nlohmann::json list = nlohmann::json::array();
  for (const SweepRun& run : runs) list.push_back(manifest_entry(run));
  return {{"spec_file", spec.file.string()},
          {"spec", spec.document},
          {"spec_sha256", spec_sha256(spec)},
          {"campo_version", library_version()},
          {"runs", list}};
}

std::string spec_sha256(const SweepSpec& spec) { return sha256_hex(spec.document.dump()); }

}  // namespace campo
