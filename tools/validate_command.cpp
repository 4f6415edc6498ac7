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
      "duplicate aliases, dangling references, unreadable data files, and vehicle and\n"
      "planner parameters are errors; a scene naming a plugin's planner needs --plugin.\n"
      "Prints one line per file; exits 0 if all are valid, 2 otherwise.");
  return [files, plugins] {
    load_plugins(*plugins);
    int failures = 0;
    for (const auto& file : *files) {
      try {
        const Scene scene = load_scene(file);
        // Parameters checked by vehicles/ and planners/ are part of the file too.
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
