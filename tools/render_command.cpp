#include <iostream>
#include <string>
#include <vector>

#include "tools/commands.hpp"
#include "tools/figures.hpp"

namespace campo::cli {

namespace {

struct RenderOptions {
  std::vector<std::string> runs;
  std::vector<std::string> kinds{"map", "side"};
  std::string out;
};

int run_render(const RenderOptions& o) {
  // Load every run first: a bad directory stops before anything is drawn.
  std::vector<RecordedRun> runs;
  for (const auto& dir : o.runs) runs.push_back(load_run_dir(dir));
  for (const std::string& kind : o.kinds) {
    if (kind == "overlay") {
      const std::filesystem::path out = o.out.empty() ? std::filesystem::path(".") : std::filesystem::path(o.out);
      std::filesystem::create_directories(out);
      std::cout << "wrote " << write_overlay(runs, out).string() << "\n";
      continue;
    }
    for (const RecordedRun& run : runs) {
      const std::filesystem::path out = o.out.empty() ? run.dir : std::filesystem::path(o.out) / run.dir.filename();
      std::filesystem::create_directories(out);
      for (const auto& file : write_figure(run, kind, out)) std::cout << "wrote " << file.string() << "\n";
    }
  }
  return kOk;
}

}  // namespace

Command add_render(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  app.add_option("runs", o->runs, "Run directories written by campo run")->required()->check(CLI::ExistingDirectory);
  app.add_option("--kind", o->kinds, "Figures to draw: map, side, depth, snapshot, overlay (repeatable)")
      ->check(CLI::IsMember({"map", "side", "depth", "snapshot", "overlay"}))
      ->capture_default_str();
  app.add_option("--out", o->out,
                 "Output directory (default: each run's own directory; for overlay, the current directory)");
  app.footer(
      "Draws figures from recorded run files alone (run.json, trajectory.csv, scene.json), without\n"
      "simulating again. map: top-down map with terrain contours, obstacles, the path coloured by time,\n"
      "waypoints reached and discarded. side: altitude over the terrain profile. depth: the depth maps\n"
      "recorded with campo run --record-depth N, grey and colour-mapped. snapshot: a perspective colour\n"
      "view rendered off-screen with OSMesa. overlay: every run given on one map, one colour each.\n"
      "Example: campo render out/run1 out/run2 out/run3 --kind overlay --out figures");
  return [o] { return run_render(*o); };
}

}  // namespace campo::cli
