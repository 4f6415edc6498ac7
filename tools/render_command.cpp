#include <algorithm>
#include <charconv>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "campo/json_reader.hpp"
#include "tools/commands.hpp"
#include "tools/run_figures.hpp"

namespace campo::cli {

namespace {

struct RenderOptions {
  std::vector<std::string> runs;
  std::vector<std::string> kinds{"map", "side"};
  std::vector<std::string> steps;  // --step: replanning step numbers or "all"
  std::vector<double> at_s;        // --at: instants of --kind sequence
  std::string out;
};

// --step values: whole numbers, or "all" for every replanning step (nullopt).
std::optional<std::vector<int>> parse_steps(const std::vector<std::string>& values) {
  std::vector<int> steps;
  for (const std::string& v : values) {
    if (v == "all") return std::nullopt;
    int k = -1;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), k);
    if (ec != std::errc() || end != v.data() + v.size() || k < 0) {
      throw InputError("command line", "--step", "expected a replanning step (0, 1, ...) or \"all\", got \"" + v + "\"");
    }
    steps.push_back(k);
  }
  return steps;
}

int run_render(const RenderOptions& o) {
  const bool replan_steps = !o.steps.empty();
  if (!o.at_s.empty() && std::find(o.kinds.begin(), o.kinds.end(), "sequence") == o.kinds.end()) {
    throw InputError("command line", "--at", "gives the instants of --kind sequence; add --kind sequence");
  }
  if (replan_steps && std::find(o.kinds.begin(), o.kinds.end(), "depth") == o.kinds.end()) {
    throw InputError("command line", "--step", "draws replanning steps of --kind depth; add --kind depth");
  }
  const std::optional<std::vector<int>> step_indices = replan_steps ? parse_steps(o.steps) : std::nullopt;
  // Load every run first, and find the steps asked for: bad input stops before anything is drawn.
  std::vector<RecordedRun> runs;
  for (const auto& dir : o.runs) runs.push_back(load_run_dir(dir));
  std::vector<std::vector<ReplanStep>> steps;
  if (replan_steps) {
    for (const RecordedRun& run : runs) steps.push_back(find_replan_steps(run, step_indices));
  }
  for (const std::string& kind : o.kinds) {
    if (kind == "overlay") {
      const std::filesystem::path out = o.out.empty() ? std::filesystem::path(".") : std::filesystem::path(o.out);
      std::filesystem::create_directories(out);
      std::cout << "wrote " << write_overlay(runs, out).string() << "\n";
      continue;
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const RecordedRun& run = runs[i];
      const std::filesystem::path out = o.out.empty() ? run.dir : std::filesystem::path(o.out) / run.dir.filename();
      std::filesystem::create_directories(out);
      if (kind == "sequence") {
        std::cout << "wrote " << write_sequence(run, o.at_s, out).string() << "\n";
        continue;
      }
      const auto files = kind == "depth" && replan_steps ? write_replan_figures(run, steps[i], out)
                                                         : write_figure(run, kind, out);
      for (const auto& file : files) std::cout << "wrote " << file.string() << "\n";
    }
  }
  return kOk;
}

}  // namespace

Command add_render(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  app.add_option("runs", o->runs, "Run directories written by campo run")->required()->check(CLI::ExistingDirectory);
  app.add_option("--kind", o->kinds,
                 "Figures to draw: map, side, heightmap (mapping planners), depth, snapshot, overlay, sequence "
                 "(repeatable)")
      ->check(CLI::IsMember({"map", "side", "heightmap", "depth", "snapshot", "overlay", "sequence"}))
      ->capture_default_str();
  app.add_option("--step", o->steps,
                 "With --kind depth: draw replanning step K of a depth_reactive run instead of the recorded depth "
                 "maps (repeatable; \"all\" for every step)");
  app.add_option("--at", o->at_s,
                 "With --kind sequence: an instant to draw, simulated seconds (repeatable; default: four instants "
                 "around the first side switch of follow-the-gap's chosen gap)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--out", o->out,
                 "Output directory (default: each run's own directory; for overlay, the current directory)");
  app.footer(
      "Draws figures from recorded run files alone (run.json, trajectory.csv, scene.json), without\n"
      "simulating again. map: top-down map with terrain contours, obstacles, the path coloured by time,\n"
      "waypoints reached and discarded. side: altitude over the terrain profile. depth: the depth maps\n"
      "recorded with campo run --record-depth N, grey and colour-mapped; with --step K, the depth map\n"
      "replanning step K read (replans/), next to the dilated and thresholded maps recomputed from the\n"
      "recorded planner parameters, with W', its safety sphere, the chosen pixel, the scan line and the\n"
      "new waypoint. snapshot: a perspective colour view rendered off-screen with OSMesa. overlay: every\n"
      "run given on one map, one colour each. sequence: the map at several instants, 2 x 2 (seed 003\n"
      "Fig. 46): track so far, movers where they were, the rover and follow-the-gap's chosen direction.\n"
      "Examples: campo render out/run1 out/run2 out/run3 --kind overlay --out figures\n"
      "          campo render out/run1 --kind depth --step 0 --step 3\n"
      "          campo render out/gap --kind sequence --at 6 --at 9 --at 12 --at 16");
  return [o] { return run_render(*o); };
}

}  // namespace campo::cli
