#include "tools/plugin_options.hpp"

#include "campo/planner_registry.hpp"
#include "tools/path_options.hpp"

namespace campo::cli {

void add_plugin_option(CLI::App& app, std::vector<std::string>& paths) {
  app.add_option("--plugin", paths,
                 "Load a planner plugin (a shared library built against campo, docs/extending.md) and its "
                 "planners; repeatable")
      ->type_name("PATH")
      ->check(input_path());
}

void load_plugins(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) load_planner_plugin(path, "command line", "--plugin");
}

void print_planners(std::ostream& out) {
  for (const PlannerEntry& entry : planner_registry()) {
    out << entry.name << " (" << entry.source << "): " << entry.description << "\n";
  }
}

}  // namespace campo::cli
