#include <iostream>
#include <string>
#include <vector>

#include "campo/scene_loader.hpp"
#include "tools/commands.hpp"
#include "tools/plugin_options.hpp"
#include "tools/scene_checks.hpp"

namespace campo::cli {

Command add_validate(CLI::App& app) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto plugins = std::make_shared<std::vector<std::string>>();
  app.add_option("files", *files, "Scene files (JSON) to check")->required()->check(input_path());
  add_plugin_option(app, *plugins);
  app.footer(
      "Every file is checked in full: unknown keys, wrong types, out-of-range values,\n"
      "duplicate aliases, dangling references, unreadable data files, vehicle and planner\n"
      "parameters, and a first vehicle without a mission (or no vehicle) are errors, exactly\n"
      "what campo run refuses; a scene naming a plugin's planner needs --plugin.\n"
      "Prints one line per file; exits 0 if all are valid, 2 otherwise.");
  return [files, plugins] {
    load_plugins(*plugins);
    int failures = 0;
    for (const auto& file : *files) {
      try {
        const Scene scene = load_scene(file);
        // What `campo run FILE` checks, in its order: a vehicle with a mission to run, then the
        // parameters that vehicles/ and planners/ check (of every vehicle, as run checks them too).
        check_runnable(scene);
        check_vehicles_and_planners(scene);
        std::cout << "ok " << file << ": " << scene.shapes.size() << " shapes, "
                  << scene.frames.size() << " frames, " << scene.movers.size() << " movers, "
                  << scene.vehicles.size() << " vehicles\n";
      } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        ++failures;
      }
    }
    return failures == 0 ? kOk : kBadInput;
  };
}

}  // namespace campo::cli
