// campo: physics simulator with embedded planners for robot-navigation research.
#include <filesystem>
#include <iostream>
#include <map>

#include "campo/json_reader.hpp"
#include "run/provenance.hpp"
#include "tools/commands.hpp"
#include "tools/path_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "campo: a Bullet-based simulator of a quadrotor and a skid-steer rover with ray-cast LIDAR,\n"
      "V-REP-like JSON scenes and embedded navigation planners.\n"
      "Run 'campo SUBCOMMAND --help' for the options of each subcommand.",
      "campo"};
  app.set_version_flag("--version", campo::campo_version_string());
  // A refused command line reads like every other refused input (--help and --version print as CLI11 prints them).
  app.failure_message(campo::cli::parse_error_message);
  app.require_subcommand(1);
  app.fallthrough(false);

  std::map<CLI::App*, campo::cli::Command> commands;
  const auto add = [&](campo::cli::Command (*adder)(CLI::App&), const char* name,
                       const char* description) {
    CLI::App* sub = app.add_subcommand(name, description);
    commands[sub] = adder(*sub);
  };
  add(campo::cli::add_run, "run", "Run one closed-loop episode of a scene and write metrics, trajectory and a map");
  add(campo::cli::add_render, "render", "Draw figures (map, side view, depth maps, snapshot, overlay ...; PNG, PDF, SVG) from recorded runs");
  add(campo::cli::add_validate, "validate", "Check scene files strictly; report every error with its JSON path");
  add(campo::cli::add_scan, "scan", "Cast one LIDAR scan in a scene and write ranges, hits, depth map and point cloud");
  add(campo::cli::add_sweep, "sweep", "Run every combination of scenes, parameter values and seeds of a sweep spec");
  add(campo::cli::add_table, "table", "Summarize a sweep as a table (Markdown, CSV, LaTeX) and a chart");
  add(campo::cli::add_plot, "plot", "Plot a metric of a sweep against a field (line or box plot; PNG, PDF, SVG)");
  add(campo::cli::add_merge, "merge", "Combine the results of several directories of one sweep (e.g. its shards) into one");
  add(campo::cli::add_plan, "plan", "Plan on a 2D grid map (MovingAI format) with A*, D* Lite, LPA* or RRT*, or a Dubins path between two poses");
  add(campo::cli::add_reproduce, "reproduce",
      "Regenerate the reproduction report of the seed theses (docs/reproductions.md) and its figures");
  add(campo::cli::add_bench, "bench", "Measure LIDAR throughput and closed-loop real-time factor on the bundled scenes");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : campo::cli::kBadInput;
  }
  try {
    for (const auto& [sub, run] : commands) {
      if (sub->parsed()) return run();
    }
  } catch (const campo::InputError& e) {
    campo::cli::print_input_error(std::cerr, e);
    return campo::cli::kBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    // The file system refused (a full disk, a read-only folder, a file where a folder should be):
    // the place to write is refused, not a bug; every path campo writes is meant to become an
    // OutputError first, this is the net under them.
    std::cerr << "error: " << campo::printable(e.path1().empty() ? std::string("file system") : e.path1().string())
              << ": " << e.code().message() << "\n";
    return campo::cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << campo::printable(e.what()) << "\n";
    return campo::cli::kInternalError;
  }
  return campo::cli::kInternalError;
}
