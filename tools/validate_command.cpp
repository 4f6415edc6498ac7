#include <iostream>
#include <string>
#include <vector>

#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "session/scene_checks.hpp"
#include "sweep/expansion.hpp"
#include "sweep/sweep_spec.hpp"
#include "tools/commands.hpp"
#include "tools/plugin_options.hpp"

namespace campo::cli {

namespace {

// A scene file: the loader reports every error it finds, those of the vehicles' and planners'
// parameter blocks with them; the checks that need a loaded scene report theirs once it loads.
void validate_scene(const std::string& file, const std::string& text) {
  const Scene scene = load_scene_text(text, file, {}, parameter_checks());
  try {
    // What `campo run FILE` checks, in its order: a vehicle with a mission to run, then the
    // parameters that vehicles/ and planners/ check (of every vehicle, as run checks them too).
    check_runnable(scene);
    check_vehicles_and_planners(scene);
  } catch (const InputError& e) {
    throw with_locations(with_aliases(e, file, parse_json_text(text, file)), file, text);
  }
  std::cout << "ok " << file << ": " << scene.shapes.size() << " shapes, " << scene.frames.size() << " frames, "
            << scene.movers.size() << " movers, " << scene.vehicles.size() << " vehicles\n";
}

// A sweep spec: every error of the spec, then each run's scene validated as `campo sweep` does.
void validate_sweep_spec(const std::string& file, const std::string& text) {
  const SweepSpec spec = read_sweep_spec_text(text, file);
  for (const SweepPlugin& plugin : spec.plugins) load_planner_plugin(plugin.file, spec.file.string(), plugin.origin);
  std::size_t runs = 0;
  try {
    for_each_sweep_run(
        spec,
        [](const Scene& scene) {
          check_runnable(scene);
          check_vehicles_and_planners(scene);
        },
        [&](const SweepRun&) { ++runs; });
  } catch (const InputError& e) {
    throw with_locations(e, file, text);  // a run's scene that does not load, at the spec's scene entry
  }
  std::cout << "ok " << file << ": sweep spec, " << spec.scenes.size() << " scenes, " << runs << " runs\n";
}

}  // namespace

Command add_validate(CLI::App& app) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto plugins = std::make_shared<std::vector<std::string>>();
  app.add_option("files", *files, "Scene files or sweep specs (JSON) to check")->required()->check(input_path());
  add_plugin_option(app, *plugins);
  app.footer(
      "Every file is checked in full: unknown keys, wrong types, out-of-range values,\n"
      "duplicate aliases, dangling references, unreadable data files, vehicle and planner\n"
      "parameters, and a first vehicle without a mission (or no vehicle) are errors, exactly\n"
      "what campo run refuses; a scene naming a plugin's planner needs --plugin. A sweep spec\n"
      "(a file with \"campo_sweep\") is checked as campo sweep checks it, every run's scene included.\n"
      "Every error of a file is reported (the first 20, then their count), one line each:\n"
      "FILE:LINE:COLUMN: /json/pointer (aliases): what was expected.\n"
      "Prints one line per valid file; exits 0 if all are valid, 2 otherwise.");
  return [files, plugins] {
    load_plugins(*plugins);
    int failures = 0;
    for (const auto& file : *files) {
      try {
        const std::string text = read_text_file(file);
        const nlohmann::json document = parse_json_text(text, file);
        if (document.is_object() && document.contains("campo_sweep")) {
          validate_sweep_spec(file, text);
        } else {
          validate_scene(file, text);
        }
      } catch (const InputError& e) {
        print_input_error(std::cerr, e);
        ++failures;
      }
    }
    return failures == 0 ? kOk : kBadInput;
  };
}

}  // namespace campo::cli
