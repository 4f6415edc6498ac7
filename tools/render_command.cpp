#include <algorithm>
#include <charconv>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "campo/json_reader.hpp"
#include "core/output_dir.hpp"
#include "render/replay.hpp"
#include "render/video_encoder.hpp"
#include "sweep/progress.hpp"
#include "tools/commands.hpp"
#include "render/run_figures.hpp"
#include "render/run_video.hpp"

namespace campo::cli {

namespace {

struct RenderOptions {
  std::vector<std::string> runs;
  std::vector<std::string> kinds{"map", "side"};  // --kind: names of figure kinds (figure_kind_names)
  std::vector<std::string> steps;  // --step: replanning step numbers or "all"
  std::vector<double> at_s;        // --at: instants of --kind sequence
  std::string out;
  std::string vehicle;             // --vehicle: whose sensor panel, depth figures and sequence (default: the first)
  VideoOptions video;
  std::string size = "1600x900";   // --size of video frames
  FigureFormats formats = kPngOnly;  // --figure-format
};

bool wants(const std::vector<FigureKind>& kinds, FigureKind kind) {
  return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

// --kind's names as kinds: every one known, as --kind's check takes them from the same table.
std::vector<FigureKind> figure_kinds(const std::vector<std::string>& names) {
  std::vector<FigureKind> kinds;
  for (const std::string& name : names) kinds.push_back(figure_kind_from_string(name).value());
  return kinds;
}

// --size: "WIDTHxHEIGHT", even sides of at least 480 x 270.
cv::Size parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, rest = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || x != 'x' || w < 480 || h < 270 || w > 3840 ||
      h > 2160 || w % 2 || h % 2) {
    throw InputError("command line", "--size",
                     "expected WIDTHxHEIGHT with even sides from 480x270 to 3840x2160, got \"" + text + "\"");
  }
  return {w, h};
}

// The folders a render makes: kept while the command runs, and those still empty when it
// fails are removed again.
using MadeFolders = std::vector<OutputDirectory>;

// The folder of one run's figures: --out/RUN, or the run's own directory.
std::filesystem::path figure_dir(const RenderOptions& o, const RecordedRun& run, MadeFolders& made) {
  const std::filesystem::path dir = o.out.empty() ? run.dir : std::filesystem::path(o.out) / run.dir.filename();
  made.emplace_back(dir);
  return dir;
}

// Where the video of `run` goes: --out itself when it names a video file, else video.mp4 in
// --out (or the run's directory).
std::filesystem::path video_path(const RenderOptions& o, const RecordedRun& run, MadeFolders& made) {
  if (!o.out.empty() && video_format_of(o.out)) return o.out;
  return figure_dir(o, run, made) / "video.mp4";
}

// The file or folder --out names can be written, before any run is read.
void check_out(const RenderOptions& o, bool one_file) {
  if (o.out.empty()) {
    for (const std::string& run : o.runs) check_output_directory(run, "run directory");
  } else if (one_file) {
    check_output_file(o.out, "--out");
  } else {
    check_output_directory(o.out, "--out");
  }
}

// A bar on a terminal, a line every tenth otherwise: "[#####.....] 120/600 frames | ETA 12s".
class FrameProgress {
 public:
  FrameProgress() : tty_(::isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()) {}
  void operator()(std::size_t done, std::size_t total) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = done > 0 ? elapsed * static_cast<double>(total - done) / static_cast<double>(done) : 0.0;
    const std::string counts = std::to_string(done) + "/" + std::to_string(total) + " frames";
    if (tty_) {
      const int width = 30, filled = static_cast<int>(width * done / std::max<std::size_t>(total, 1));
      std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, '.') << "] " << counts
                << " | ETA " << format_duration(eta) << "\033[K" << std::flush;
      if (done == total) std::cerr << "\r\033[K" << std::flush;
    } else if (done == total || done * 10 / total != (done - 1) * 10 / total) {
      std::cerr << "video: " << counts << ", " << format_duration(elapsed) << " elapsed\n";
    }
  }

 private:
  bool tty_;
  std::chrono::steady_clock::time_point start_;
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
  const std::vector<FigureKind> kinds = figure_kinds(o.kinds);
  const bool replan_steps = !o.steps.empty();
  if (!o.at_s.empty() && !wants(kinds, FigureKind::sequence)) {
    throw InputError("command line", "--at", "gives the instants of --kind sequence; add --kind sequence");
  }
  if (replan_steps && !wants(kinds, FigureKind::depth)) {
    throw InputError("command line", "--step", "draws replanning steps of --kind depth; add --kind depth");
  }
  const bool video_file = !o.out.empty() && video_format_of(o.out).has_value();
  if (video_file && (o.runs.size() != 1 || kinds.size() != 1 || !wants(kinds, FigureKind::video))) {
    throw InputError("command line", "--out",
                     "names a video file, which holds one run's --kind video alone; give a directory for several");
  }
  const bool html_file = std::filesystem::path(o.out).extension() == ".html";
  if (html_file && (kinds.size() != 1 || !wants(kinds, FigureKind::replay))) {
    throw InputError("command line", "--out", "names an HTML file, which holds --kind replay alone; give a directory");
  }
  check_out(o, video_file || html_file);
  // Bounded work whatever is given (docs/limits.md): the runs of a replay, the runs made into videos.
  if (wants(kinds, FigureKind::replay)) check_replay_runs(o.runs.size());
  if (wants(kinds, FigureKind::video)) check_video_runs(o.runs.size(), o.video);
  VideoOptions video = o.video;
  if (wants(kinds, FigureKind::video)) video.frame_px = parse_size(o.size);
  const std::optional<std::vector<int>> step_indices = replan_steps ? parse_steps(o.steps) : std::nullopt;
  // Load every run first, and find the steps asked for: bad input stops before anything is drawn.
  // A replay alone reads its runs one at a time (render/replay.hpp): nothing loaded up front.
  const bool replay_only = std::all_of(kinds.begin(), kinds.end(), [](FigureKind k) { return k == FigureKind::replay; });
  std::vector<RecordedRun> runs;
  if (!replay_only) {
    for (const auto& dir : o.runs) runs.push_back(load_run_dir(dir, o.vehicle));
  } else if (!o.vehicle.empty()) {
    for (const auto& dir : o.runs) load_run_dir(dir, o.vehicle);  // an unknown --vehicle stops before anything is written
  }
  std::vector<std::vector<ReplanStep>> steps;
  if (replan_steps) {
    for (const RecordedRun& run : runs) steps.push_back(find_replan_steps(run, step_indices));
  }
  MadeFolders made;
  for (const FigureKind kind : kinds) {
    switch (kind) {
      case FigureKind::replay: {
        // Every run in one page; beside the run when there is one, else in the current directory.
        std::filesystem::path file = html_file ? std::filesystem::path(o.out)
                                     : !o.out.empty() ? std::filesystem::path(o.out) / "replay.html"
                                     : o.runs.size() == 1 ? std::filesystem::path(o.runs.front()) / "replay.html"
                                                        : std::filesystem::path("replay.html");
        if (file.has_parent_path()) made.emplace_back(file.parent_path());
        const std::vector<std::filesystem::path> dirs(o.runs.begin(), o.runs.end());
        write_file_atomically(file, replay_html(replay_only ? replay_data(dirs) : replay_data(runs)));
        std::cout << "wrote " << file.string() << "\n";
        break;
      }
      case FigureKind::overlay: {
        const std::filesystem::path out = o.out.empty() ? std::filesystem::path(".") : std::filesystem::path(o.out);
        made.emplace_back(out);
        for (const auto& file : write_overlay(runs, out, o.formats)) std::cout << "wrote " << file.string() << "\n";
        break;
      }
      case FigureKind::video:
        for (const RecordedRun& run : runs) {
          const std::filesystem::path file = video_path(o, run, made);
          FrameProgress progress;
          write_video(run, video, file, std::ref(progress));
          std::cout << "wrote " << file.string() << "\n";
        }
        break;
      case FigureKind::sequence:
        for (const RecordedRun& run : runs) {
          const std::filesystem::path out = figure_dir(o, run, made);
          for (const auto& file : write_sequence(run, o.at_s, out, o.formats)) std::cout << "wrote " << file.string() << "\n";
        }
        break;
      case FigureKind::map:
      case FigureKind::side:
      case FigureKind::heightmap:
      case FigureKind::depth:
      case FigureKind::snapshot:
        for (std::size_t i = 0; i < runs.size(); ++i) {
          const RecordedRun& run = runs[i];
          const std::filesystem::path out = figure_dir(o, run, made);
          const auto files = kind == FigureKind::depth && replan_steps
                                 ? write_replan_figures(run, steps[i], out, o.formats)
                                 : write_figure(run, kind, out, o.formats);
          for (const auto& file : files) std::cout << "wrote " << file.string() << "\n";
        }
        break;
    }
  }
  return kOk;
}

}  // namespace

Command add_render(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  app.add_option("runs", o->runs, "Run directories written by campo run")->required()->check(existing_directory());
  app.add_option("--kind", o->kinds,
                 "Figures to draw: map, side, heightmap (mapping planners), depth, snapshot, overlay, sequence, "
                 "video, replay (repeatable)")
      ->check(CLI::IsMember(figure_kind_names()))
      ->capture_default_str();
  app.add_option("--step", o->steps,
                 "With --kind depth: draw replanning step K of a depth_reactive run instead of the recorded depth "
                 "maps (repeatable; \"all\" for every step)");
  app.add_option("--at", o->at_s,
                 "With --kind sequence: an instant to draw, simulated seconds (repeatable; default: four instants "
                 "around the first side switch of follow-the-gap's chosen gap)")
      ->check(non_negative_number());
  app.add_option("--out", o->out,
                 "Output directory (default: each run's own directory; for overlay, the current directory); with "
                 "--kind video alone and one run, the video file itself (.mp4 or .gif); with --kind replay alone, the "
                 "page itself (.html)");
  app.add_option("--fps", o->video.fps, "With --kind video: frames per second of the video")
      ->check(CLI::Range(1.0, 60.0))
      ->capture_default_str();
  app.add_option("--speed", o->video.speed,
                 "With --kind video: playback speed, simulated seconds per second of video (2 = twice as fast)")
      ->check(CLI::Range(0.05, 100.0))
      ->capture_default_str();
  app.add_option("--size", o->size, "With --kind video: frame size in pixels, WIDTHxHEIGHT (even sides)")
      ->capture_default_str();
  app.add_option("--vehicle", o->vehicle,
                 "In a run of several vehicles, the one whose sensor panel (video), replanning steps (--step) and "
                 "sequence are drawn (default: the first); maps, side views, snapshots, videos and replays show them all");
  add_figure_format_option(app, &o->formats);
  app.footer(
      "Draws figures from recorded run files alone (run.json, trajectory.csv or trajectory_<alias>.csv,\n"
      "scene.json), without simulating again. map: top-down map with terrain contours, obstacles, the\n"
      "path coloured by time, waypoints reached and discarded. side: altitude over the terrain profile.\n"
      "depth: the depth maps\n"
      "recorded with campo run --record-depth N, grey and colour-mapped; with --step K, the depth map\n"
      "replanning step K read (replans/), next to the dilated and thresholded maps recomputed from the\n"
      "recorded planner parameters, with W', its safety sphere, the chosen pixel, the scan line and the\n"
      "new waypoint. snapshot: a perspective colour view rendered off-screen with OSMesa. overlay: every\n"
      "run given on one map, one colour each. sequence: the map at several instants, 2 x 2 (seed 003\n"
      "Fig. 46): track so far, movers where they were, the rover and follow-the-gap's chosen direction.\n"
      "video: an animation (H.264 .mp4, or .gif) encoded by the ffmpeg program: the map with the track\n"
      "growing, the sensor panel of that moment (the depth map of the latest replanning with the planner's\n"
      "overlays; else the depth maps or planar scans recorded with campo run --record-depth N, a planar scan\n"
      "drawn around the vehicle with follow-the-gap's gap; else the gap decisions alone) and a strip with\n"
      "the clock, speed, altitude, clearance, distance and the planner's state; the end held a second.\n"
      "replay: one self-contained HTML page (three.js inside; opens offline) with every run given in 3D:\n"
      "terrain, obstacles, movers, vehicles, tracks and the returns recorded with --record-depth N, a time\n"
      "slider, play/pause, speed, camera orbit and a legend (default: replay.html beside the one run).\n"
      "A run of several vehicles: map, side, snapshot, video and replay show every vehicle, each in its colour\n"
      "(a colour-blind-safe palette) named in the legend, its start, goal and footprint; the sensor panel,\n"
      "--step and sequence are those of --vehicle (default the first).\n"
      "Every figure but video and replay can be written as PNG, PDF and SVG (--figure-format png,pdf,svg):\n"
      "the same drawing in each; PDF and SVG are vector files (lines, markers and text stay sharp at any\n"
      "zoom; text is text in the PDF), with the terrain shading, depth maps and snapshots embedded as images.\n"
      "Examples: campo render out/run1 out/run2 out/run3 --kind overlay --out figures\n"
      "          campo render out/run1 --kind depth --step 0 --step 3\n"
      "          campo render out/run1 --kind map --kind side --figure-format png,pdf,svg\n"
      "          campo render out/gap --kind sequence --at 6 --at 9 --at 12 --at 16\n"
      "          campo render out/run1 --kind video --out run1.mp4 --speed 2\n"
      "          campo render out/run1 out/run2 --kind replay --out replay.html");
  return [o] { return run_render(*o); };
}

}  // namespace campo::cli
