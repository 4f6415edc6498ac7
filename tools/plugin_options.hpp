#pragma once
/// The planner plugin options the commands share: --plugin PATH (run, sweep,
/// validate) and the planner list of `campo run --list-planners`.
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace campo::cli {

/// Adds the repeatable option --plugin PATH, collected into `paths`.
void add_plugin_option(CLI::App& app, std::vector<std::string>& paths);

/// Loads the plugins given with --plugin, in order; throws InputError.
void load_plugins(const std::vector<std::string>& paths);

/// One line per planner, built-in ones first: "NAME (SOURCE): DESCRIPTION".
void print_planners(std::ostream& out);

}  // namespace campo::cli
