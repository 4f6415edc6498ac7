#include "sweep/sweep_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>

#include "campo/json_reader.hpp"
#include "sweep/bundled.hpp"
#include "sweep/results.hpp"
#include "sweep/table.hpp"

namespace campo {

namespace {

bool label_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == '.';
}

SweepScene read_scene(const JsonNode& node, const std::filesystem::path& spec_file) {
  const std::string entry = node.as_string();
  SweepScene scene;
  scene.origin = node.pointer();
  if (entry.ends_with(".json")) {
    const std::filesystem::path path(entry);
    scene.file = path.is_absolute() ? path : spec_file.parent_path() / path;
    scene.label = path.stem().string();
  } else {
    scene.label = entry;
  }
  const bool valid = !scene.label.empty() && scene.label.front() != '.' &&
                     std::all_of(scene.label.begin(), scene.label.end(), label_char);
  if (!valid) node.fail("a bundled scene name or a path to a \".json\" file named with letters, digits, '_', '-' or '.'");
  if (scene.file.empty()) {
    try {
      scene.file = bundled_scene(entry);
    } catch (const InputError& e) {  // where in the spec, and where it was looked for
      throw InputError(node.file(), node.pointer(), e.message());
    }
  }
  return scene;
}

// A JSON pointer into a scene: "/..." without '=', which ends the pointer of a "--set" assignment.
std::string read_pointer(const JsonNode& node) {
  const std::string pointer = node.as_string();
  if (pointer.size() < 2 || pointer.front() != '/' || pointer.find('=') != std::string::npos) {
    node.fail("a JSON pointer into the scene such as \"/objects/drone/planner/name\" (without '=')");
  }
  return pointer;
}

// An axis value: a scalar or a flat array of scalars, which has a label.
nlohmann::json read_axis_value(const JsonNode& node) {
  const nlohmann::json& v = node.value();
  const auto scalar = [](const nlohmann::json& x) { return x.is_number() || x.is_string() || x.is_boolean(); };
  const bool valid = scalar(v) || (v.is_array() && !v.empty() && std::all_of(v.begin(), v.end(), scalar));
  if (!valid) node.fail("a number, string or boolean, or a non-empty array of them");
  return v;
}

// A planner entry: "name", or {"name", "label", "params"}.
SweepPlanner read_planner(const JsonNode& node) {
  SweepPlanner planner;
  planner.origin = node.pointer();
  planner.params = nlohmann::json::object();
  if (node.value().is_string()) {
    planner.name = node.as_string();
  } else {
    if (!node.value().is_object()) node.fail("a planner name or an object {\"name\", \"label\", \"params\"}");
    ObjectReader r(node);
    planner.name = r.required("name").as_string();
    if (auto params = r.optional("params")) {
      if (!params->value().is_object()) params->fail("an object of planner parameters");
      planner.params = params->value();
    }
    planner.label = planner.name;
    r.read("label", planner.label);
    r.finish();
  }
  if (planner.label.empty()) planner.label = planner.name;
  if (!std::all_of(planner.label.begin(), planner.label.end(), label_char)) {
    node.fail("a planner label of letters, digits, '_', '-' or '.' (it names runs)");
  }
  return planner;
}

SweepSampling read_sampling(const JsonNode& node, int max_samples) {
  ObjectReader r(node);
  SweepSampling sampling;
  sampling.method = r.required("method").as_choice({"random", "latin_hypercube"}) == 0
                        ? SweepSampling::Method::random
                        : SweepSampling::Method::latin_hypercube;
  sampling.samples = static_cast<int>(r.required("samples").as_int(1, max_samples));
  r.read_seed("seed", sampling.seed);
  r.finish();
  return sampling;
}

// "range": {"from", "to", "step" | "count"} as values, or without either an interval to sample.
void read_range(const JsonNode& node, SweepAxis& axis, std::size_t max_values) {
  ObjectReader r(node);
  const JsonNode from_node = r.required("from");
  const JsonNode to_node = r.required("to");
  const double from = from_node.as_number();
  const double to = to_node.as_number();
  if (!(to > from)) to_node.fail("a number > from (" + value_label(from_node.value()) + ")");
  const auto step = r.optional("step");
  const auto count = r.optional("count");
  r.finish();
  if (step && count) node.fail("either \"step\" or \"count\", not both");
  if (!step && !count) {
    axis.interval = std::pair{from, to};
    return;
  }
  // Integers stay integers when every value is one (resolutions, counts).
  const bool integers = from_node.value().is_number_integer() && to_node.value().is_number_integer() &&
                        (!step || step->value().is_number_integer());
  std::size_t n = 0;
  double delta = 0.0;
  if (step) {
    delta = step->as_number(Range::positive());
    // Counted as a double (to - from may overflow to infinity), checked before it becomes a count.
    const double steps = std::floor((to - from) / delta * (1.0 + 1e-12));
    if (!(steps < static_cast<double>(max_values))) {
      step->fail("a step giving at most " + std::to_string(max_values) + " values");
    }
    n = static_cast<std::size_t>(steps) + 1;
  } else {
    n = static_cast<std::size_t>(count->as_int(2, static_cast<std::int64_t>(max_values)));
    delta = (to - from) / static_cast<double>(n - 1);
  }
  for (std::size_t i = 0; i < n; ++i) {
    // 12 significant digits, so stepped values read as written (0.3, not 0.30000000000000004).
    const double v = round_significant(from + static_cast<double>(i) * delta, 12);
    if (integers && std::rint(v) == v) {
      axis.values.emplace_back(static_cast<std::int64_t>(v));
    } else {
      axis.values.emplace_back(v);
    }
  }
}

StartJitter read_start_jitter(const JsonNode& node) {
  ObjectReader r(node);
  StartJitter jitter;
  jitter.origin = node.pointer();
  jitter.vehicle = r.required("vehicle").as_string();
  jitter.radius_m = r.required("radius_m").as_number({0.0, 1e3, true, false});
  r.finish();
  return jitter;
}

class SpecParser {
 public:
  SpecParser(const std::filesystem::path& file, const SweepLimits& limits) : file_(file), limits_(limits) {}

  SweepSpec parse(const nlohmann::json& document) {
    SweepSpec spec;
    spec.file = file_;
    spec.document = document;
    spec.name = file_.stem().string();
    // Every error of the spec that can be found is collected (each key, and
    // each scene, planner, override and axis, checked on its own) and thrown
    // as one InputError; another format version is thrown at once.
    ObjectReader r(JsonNode(document, file_.string(), ""), &errors_);
    r.check([&] {
      const JsonNode version = r.required("campo_sweep");
      if (version.as_int(1, 1000) != 1) version.fail("format version 1");
    });
    if (!r.ok()) errors_.throw_if_any();
    r.read("name", spec.name);
    r.read("description", spec.description);

    // Loaded by `campo sweep` before the runs are expanded (the parser itself loads nothing).
    if (auto plugins = r.optional("plugins")) {
      r.check([&] {
        for (const JsonNode& node : plugins->as_array(0, limits_.max_plugins)) {
          r.check([&] {
            const std::filesystem::path path(node.as_string());
            SweepPlugin plugin{(path.is_absolute() ? path : file_.parent_path() / path).lexically_normal(),
                               node.pointer()};
            for (const SweepPlugin& other : spec.plugins) {
              if (other.file == plugin.file) {
                node.fail("plugins named once each (" + plugin.file.string() + " appears twice)");
              }
            }
            spec.plugins.push_back(std::move(plugin));
          });
        }
      });
    }

    std::set<std::string> labels;
    r.check([&] {
      for (const JsonNode& node : r.required("scenes").as_array(1, limits_.max_scenes)) {
        r.check([&] {
          SweepScene scene = read_scene(node, file_);
          if (!labels.insert(scene.label).second) {
            node.fail("scenes with distinct names (\"" + scene.label + "\" appears twice)");
          }
          spec.scenes.push_back(std::move(scene));
        });
      }
    });
    const auto planners = r.optional("planners");
    if (planners) {
      std::set<std::string> planner_labels;
      r.check([&] {
        for (const JsonNode& node : planners->as_array(1, limits_.max_planners)) {
          r.check([&] {
            SweepPlanner planner = read_planner(node);
            if (!planner_labels.insert(planner.label).second) {
              node.fail("planners with distinct labels (\"" + planner.label + "\" appears twice)");
            }
            spec.planners.push_back(std::move(planner));
          });
        }
      });
    }
    // The seeds own the world seed.
    writers_.emplace("/world/seed", "/seeds");
    if (auto set = r.optional("set")) {
      r.check([&] {
        ObjectReader s(*set);
        if (set->value().size() > limits_.max_pointers) {
          set->fail("at most " + std::to_string(limits_.max_pointers) + " overrides");
        }
        // Keys come sorted, so a pointer is applied before the pointers below it.
        for (const auto& item : set->value().items()) {
          // Named, not a structured binding: clang (the fuzz build) cannot capture one in a lambda.
          const std::string& key = item.key();
          const nlohmann::json& value = item.value();
          r.check([&] {
            const JsonNode node = *s.optional(key);
            read_pointer(JsonNode(nlohmann::json(key), node.file(), node.pointer()));
            claim(key, node);
            spec.set.push_back({key, value, node.pointer()});
          });
        }
      });
    }
    const std::size_t errors_before_axes = errors_.count();
    if (auto axes = r.optional("axes")) {
      r.check([&] {
        for (const JsonNode& node : axes->as_array(0, limits_.max_axes)) {
          r.check([&] {
            SweepAxis axis = read_axis(node);
            for (const SweepAxis& other : spec.axes) {
              if (other.name == axis.name) node.fail("axes with distinct names (\"" + axis.name + "\" appears twice)");
            }
            spec.axes.push_back(std::move(axis));
          });
        }
      });
    }
    const bool axes_ok = errors_.count() == errors_before_axes;  // an axis with errors is not a missing axis
    if (auto seeds = r.optional("seeds")) {
      r.check([&] {
        ObjectReader s(*seeds, r.errors());
        s.read_seed("first", spec.first_seed);
        s.read("count", spec.seed_count, 1, limits_.max_seeds);
        s.finish();
        // The last seed, first + count - 1, is a seed too.
        if (s.ok() &&
            spec.first_seed > std::numeric_limits<std::uint64_t>::max() - static_cast<std::uint64_t>(spec.seed_count - 1)) {
          seeds->fail("seeds first .. first + count - 1 that are all in [0, 18446744073709551615]");
        }
      });
    }
    if (auto jitter = r.optional("start_jitter")) {
      r.check([&] {
        spec.start_jitter = read_start_jitter(*jitter);
        claim("/objects/" + spec.start_jitter->vehicle + "/pose/position_m", *jitter);
      });
    }
    if (planners) {
      // The planners own the first vehicle's planner choice.
      for (const auto& [pointer, origin] : writers_) {
        if (pointer.ends_with("/planner") || pointer.ends_with("/planner/name")) {
          errors_.add(InputError(file_.string(), origin,
                                 "expected no planner choice when \"planners\" is given (it sets " + pointer +
                                     "); set the planner's parameters instead"));
        }
      }
    }
    if (auto sampling = r.optional("sampling")) {
      r.check([&] {
        spec.sampling = read_sampling(*sampling, static_cast<int>(limits_.max_runs));
        if (spec.axes.empty() && axes_ok) sampling->fail("a sampling of at least one axis (\"axes\" is empty)");
      });
    } else {
      for (const SweepAxis& axis : spec.axes) {
        if (axis.interval) {
          errors_.add(InputError(file_.string(), axis.origin + "/range",
                                 "expected a \"step\" or \"count\" (a range without them is an interval, only for "
                                 "\"sampling\")"));
        }
      }
    }
    r.read("time_limit_s", spec.time_limit_s, Range::positive());
    r.read("vary_scene_with_seed", spec.vary_scene_with_seed);
    // Read by `campo table`, which checks its fields against the results.
    if (auto table = r.optional("table")) r.check([&] { read_table_request(*table); });
    r.finish();
    errors_.throw_if_any();

    std::size_t runs = spec.scenes.size() * static_cast<std::size_t>(spec.seed_count) *
                       std::max<std::size_t>(spec.planners.size(), 1);
    const auto check_runs = [&] {
      if (runs > limits_.max_runs) {
        throw InputError(file_.string(), "", "expands to more than " + std::to_string(limits_.max_runs) + " runs");
      }
    };
    check_runs();
    if (spec.sampling) {
      runs *= static_cast<std::size_t>(spec.sampling->samples);
      check_runs();
    } else {
      for (const SweepAxis& axis : spec.axes) {
        runs *= axis.values.size();
        check_runs();
      }
    }
    return spec;
  }

 private:
  // Every scene pointer is written by one source only, so no value silently replaces another.
  void claim(const std::string& pointer, const JsonNode& at) {
    const auto [it, inserted] = writers_.emplace(pointer, at.pointer());
    if (!inserted) at.fail("a pointer set in one place only (\"" + pointer + "\" is also set at " + it->second + ")");
  }

  SweepAxis read_axis(const JsonNode& node) {
    ObjectReader r(node);
    SweepAxis axis;
    axis.origin = node.pointer();
    const JsonNode name = r.required("name");
    axis.name = name.as_string();
    const bool valid_name = !axis.name.empty() && axis.name.size() <= 32 && axis.name.front() >= 'a' &&
                            axis.name.front() <= 'z' &&
                            std::all_of(axis.name.begin(), axis.name.end(), [](char c) {
                              return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
                            });
    if (!valid_name) name.fail("an axis name of up to 32 lower-case letters, digits and '_', starting with a letter");
    const auto stats = table_stat_columns();
    // Runs have these fields of their own.
    const bool run_field = axis.name == "scene" || axis.name == "planner" || axis.name == "seed";
    if (run_field || std::find(stats.begin(), stats.end(), axis.name) != stats.end()) {
      name.fail("an axis name that is not also a run field (scene, planner, seed) or a table column");
    }
    const auto values = r.optional("values");
    const auto range = r.optional("range");
    if (values.has_value() == range.has_value()) node.fail("an axis with either \"values\" or \"range\"");
    if (range) read_range(*range, axis, limits_.max_values);
    const std::vector<JsonNode> listed = values ? values->as_array(1, limits_.max_values) : std::vector<JsonNode>{};
    for (const JsonNode& value : listed) axis.values.push_back(read_axis_value(value));
    // Distinct in run names, so no two runs share a name, an ID or a directory.
    std::set<std::string> labels;
    for (std::size_t i = 0; i < axis.values.size(); ++i) {
      const std::string label = value_id_label(axis.values[i]);
      if (labels.insert(label).second) continue;
      const std::string expected = "values with distinct labels in run names (\"" + label + "\" appears twice)";
      if (values) listed[i].fail(expected);
      range->fail(expected);
    }
    for (const JsonNode& pointer : r.required("set").as_array(1, limits_.max_pointers)) {
      axis.pointers.push_back(read_pointer(pointer));
      claim(axis.pointers.back(), pointer);
    }
    r.finish();
    return axis;
  }

  std::filesystem::path file_;
  SweepLimits limits_;
  std::map<std::string, std::string> writers_;  // scene pointer -> spec pointer that sets it
  InputErrors errors_;
};

}  // namespace

std::string value_label(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_float()) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, value.get<double>());
    return std::string(text, end);
  }
  if (value.is_array()) {
    std::string label;
    for (const auto& element : value) {
      if (!label.empty()) label += 'x';
      label += value_label(element);
    }
    return label;
  }
  return value.dump();  // integers and booleans
}

double round_significant(double value, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return std::strtod(text, nullptr);
}

std::string value_id_label(const nlohmann::json& value) {
  std::string label = value_label(value);
  for (char& c : label) {
    if (!label_char(c) && c != '+') c = '_';
  }
  return label;
}

SweepSpec read_sweep_spec(const std::filesystem::path& file, const SweepLimits& limits) {
  return read_sweep_spec_text(read_text_file(file), file, limits);
}

SweepSpec read_sweep_spec_text(const std::string& text, const std::filesystem::path& file,
                               const SweepLimits& limits) {
  const nlohmann::json document = parse_json_text(text, file.string());
  try {
    return parse_sweep_spec(document, file, limits);
  } catch (const InputError& e) {
    throw with_locations(e, file.string(), text);  // each error's line and column in the file
  }
}

SweepSpec parse_sweep_spec(const nlohmann::json& document, const std::filesystem::path& file,
                           const SweepLimits& limits) {
  try {
    return SpecParser(file, limits).parse(document);
  } catch (const InputError& e) {
    // Beside each index pointer, the axes and planners it goes through by their names.
    throw with_aliases(e, file.string(), document, "name");
  }
}

}  // namespace campo
