// Seed 000 (reactive depth-map quadrotor): 000 §5.4-5.5, Table 5.1, Fig. 5.5, Fig. 5.6.
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "campo/json_reader.hpp"
#include "render/run_files.hpp"
#include "reproduce/claims.hpp"
#include "reproduce/trajectory_checks.hpp"
#include "sweep/results.hpp"

namespace campo {

namespace fs = std::filesystem;

namespace {

// 000 Tabella 5.1, the second scenario (trees on rolling terrain), as printed.
struct ThesisRow {
  int resolution;
  int reached, discarded;
  double length_m, ratio, time_s;
};
constexpr ThesisRow kThesisTable51[] = {
    {256, 2, 0, 24.16, 1.04, 58.6},  {256, 2, 1, 23.83, 1.03, 72.0},  {256, 3, 0, 23.43, 1.01, 82.5},
    {128, 2, 1, 23.62, 1.02, 73.0},  {128, 4, 1, 24.08, 1.03, 92.0},  {128, 3, 1, 23.54, 1.01, 72.1},
    {64, 4, 5, 24.99, 1.07, 129.6},  {64, 3, 2, 24.19, 1.04, 80.7},   {64, 3, 1, 23.68, 1.02, 80.3},
    {32, 4, 1, 23.73, 1.02, 85.8},   {32, 3, 2, 24.05, 1.03, 106.2},  {32, 3, 2, 23.79, 1.02, 78.3},
};
constexpr double kThesisRatioLow = 1.01, kThesisRatioHigh = 1.07;
constexpr double kRatioCeiling = 1.15;      // no run above (the thesis: never above 1.10)
constexpr double kClearanceFloor_m = 0.05;  // no run closer (true clearance)

std::string mean_sd(const std::optional<Summary>& s, int decimals) {
  if (!s) return "–";
  return fixed(s->mean, decimals) + (s->n > 1 ? " ± " + fixed(s->sd, decimals) : "");
}

std::string minutes_seconds(double seconds) {
  const int minutes = static_cast<int>(seconds / 60.0);
  return std::to_string(minutes) + ":" + (seconds - 60.0 * minutes < 10.0 ? "0" : "") +
         fixed(seconds - 60.0 * minutes, 1);
}

struct ResolutionCell {
  std::vector<const RunResult*> runs;
  std::optional<double> max_ratio_reached;
  std::optional<double> min_clearance_m;
};

void table_5_1(const Workbench& bench, std::vector<fs::path>& tree_runs, Claim& claim) {
  claim.thesis =
      "000 §5.5, Tabella 5.1 (second scenario, trees on rolling terrain; start and goal 23.27 m apart): three runs "
      "per depth-map resolution 256/128/64/32, intermediate waypoints reached 2-4 and discarded 0-5, normalised "
      "path length 1.01-1.07 (\"the ratio to the straight-line distance never exceeds 1.10\"), times 58.6-129.6 s "
      "at 0.6 m/s. The first scenario (two barriers) \"was solved in the same way even at 16 x 16\". The thesis's "
      "rows:\n\n";
  std::vector<std::vector<std::string>> thesis_rows;
  for (std::size_t i = 0; i < std::size(kThesisTable51); ++i) {
    const ThesisRow& r = kThesisTable51[i];
    thesis_rows.push_back({std::to_string(i + 1), std::to_string(r.resolution), std::to_string(r.reached),
                           std::to_string(r.discarded), fixed(r.length_m, 2), fixed(r.ratio, 2),
                           minutes_seconds(r.time_s)});
  }
  claim.thesis += markdown_table({"#", "Resolution", "Reached", "Discarded", "Length (m)", "Normalised", "Time"},
                                 thesis_rows);

  const std::vector<int> resolutions = bench.quick() ? std::vector<int>{64, 16} : std::vector<int>{256, 128, 64, 32, 16};
  const fs::path spec = bench.spec("scenes/sweeps/resolution_000.json", [&](nlohmann::json& d) {
    d["seeds"]["count"] = 1;
    d["axes"][0]["values"] = resolutions;
  });
  const fs::path dir = bench.work("resolution_000");
  claim.commands.push_back(
      bench.campo({"sweep", spec.string(), "--out", dir.string(), "--keep-runs", "--jobs", std::to_string(bench.jobs())}));

  const ResultsFile results = read_results(dir / "results.jsonl");
  std::map<std::pair<std::string, int>, ResolutionCell> cells;
  std::set<std::uint64_t> seeds;
  for (const RunResult& run : results.runs) {
    const int resolution = run.params.at("resolution").get<int>();
    ResolutionCell& cell = cells[{run.scene, resolution}];
    cell.runs.push_back(&run);
    seeds.insert(run.seed);
    if (!run.completed) continue;
    if (run.metrics.outcome == "reached") {
      cell.max_ratio_reached = std::max(cell.max_ratio_reached.value_or(0.0), run.metrics.path_ratio);
    }
    if (run.metrics.min_clearance_m) {
      cell.min_clearance_m = std::min(cell.min_clearance_m.value_or(1e300), *run.metrics.min_clearance_m);
    }
    if (resolution == resolutions.front() && run.scene == "trees_rolling_terrain") {
      tree_runs.push_back(dir / run_dir(run.name));
    }
  }

  TargetCheck check;
  std::vector<std::vector<std::string>> rows;
  for (const std::string scene : {"trees_rolling_terrain", "two_barriers"}) {
    for (int resolution : resolutions) {
      const auto found = cells.find({scene, resolution});
      if (found == cells.end()) continue;
      const ResolutionCell& cell = found->second;
      const auto summary = [&](const std::string& metric) {
        return summarize_metric(cell.runs, metric, metric == "success" ? MetricKind::rate : MetricKind::number);
      };
      const auto success = summary("success");
      const auto ratio = summary("path_ratio@reached");
      int collisions = 0;
      for (const RunResult* r : cell.runs) collisions += r->completed ? r->metrics.collisions : 0;
      rows.push_back({scene, std::to_string(resolution), std::to_string(cell.runs.size()),
                      success ? fixed(100.0 * success->mean, 0) + " %" : "–",
                      mean_sd(summary("waypoints_reached@reached"), 1),
                      mean_sd(summary("waypoints_discarded@reached"), 1), mean_sd(summary("path_length_m@reached"), 2),
                      mean_sd(ratio, 3), cell.max_ratio_reached ? fixed(*cell.max_ratio_reached, 3) : "–",
                      mean_sd(summary("sim_time_s@reached"), 1), std::to_string(collisions),
                      cell.min_clearance_m ? fixed(*cell.min_clearance_m, 3) : "–"});
      const std::string where = scene + " at " + std::to_string(resolution);
      check.expect(cell.min_clearance_m && *cell.min_clearance_m >= kClearanceFloor_m,
                   "true clearance >= " + fixed(kClearanceFloor_m, 2) + " m on " + where);
      // The thesis measured 256 down to 32; at 16 campo reports without a target.
      if (resolution < 32) continue;
      check.expect(success && success->mean == 1.0, "success 100 % on " + where);
      if (scene == "trees_rolling_terrain") {
        check.expect(ratio && ratio->mean >= kThesisRatioLow - 0.005 && ratio->mean <= kThesisRatioHigh + 0.005,
                     "mean path ratio inside the thesis's 1.01-1.07 on " + where);
        check.expect(cell.max_ratio_reached && *cell.max_ratio_reached <= kRatioCeiling,
                     "no path ratio above " + fixed(kRatioCeiling, 2) + " on " + where);
      }
    }
  }
  const bool scene_varies = read_json_file(spec).value("vary_scene_with_seed", false);
  claim.measured = "Seeds per resolution and scene: " + std::to_string(seeds.size()) + " (start jittered within 0.25 m, "
                   "1 cm range noise, " +
                   (scene_varies ? std::string("the trees and terrain re-drawn per seed")
                                 : std::string("the same trees and terrain in every run, as in the thesis's runs")) +
                   "); means ± sd over "
                   "the runs that reached the goal; the path ratio's maximum over those runs; true clearance is the "
                   "minimum signed distance between the drone's collision box and any obstacle over the whole "
                   "run.\n\n" +
                   markdown_table({"Scene", "Resolution", "Runs", "Success", "Reached", "Discarded", "Length (m)",
                                   "Normalised", "Max normalised", "Time (s)", "Collisions", "Min clearance (m)"},
                                  rows);
  // Side by side per resolution: the thesis's three runs against campo's on the trees.
  std::vector<std::vector<std::string>> side_by_side;
  for (int resolution : resolutions) {
    std::vector<double> ratios, times;
    for (const ThesisRow& r : kThesisTable51) {
      if (r.resolution != resolution) continue;
      ratios.push_back(r.ratio);
      times.push_back(r.time_s);
    }
    const auto found = cells.find({"trees_rolling_terrain", resolution});
    if (found == cells.end()) continue;
    std::vector<double> campo_ratios, campo_times;
    for (const RunResult* r : found->second.runs) {
      if (!r->completed || r->metrics.outcome != "reached") continue;
      campo_ratios.push_back(r->metrics.path_ratio);
      campo_times.push_back(r->metrics.time_s);
    }
    const auto range = [](const std::vector<double>& v, int decimals) -> std::string {
      if (v.empty()) return "–";
      const Summary s = summarize_values(v);
      return fixed(s.mean, decimals) + " (" + fixed(*std::min_element(v.begin(), v.end()), decimals) + "-" +
             fixed(*std::max_element(v.begin(), v.end()), decimals) + ")";
    };
    side_by_side.push_back({std::to_string(resolution), ratios.empty() ? "–" : std::to_string(ratios.size()),
                            range(ratios, 3), range(times, 1), std::to_string(found->second.runs.size()),
                            std::to_string(campo_ratios.size()), range(campo_ratios, 3), range(campo_times, 1)});
  }
  // Mean ground speeds: the thesis's times are the one column campo does not come near, said plainly.
  double thesis_length_m = 0.0, thesis_time_s = 0.0, campo_length_m = 0.0, campo_time_s = 0.0;
  for (const ThesisRow& r : kThesisTable51) {
    thesis_length_m += r.length_m;
    thesis_time_s += r.time_s;
  }
  for (const RunResult& run : results.runs) {
    if (!run.completed || run.metrics.outcome != "reached" || run.scene != "trees_rolling_terrain") continue;
    campo_length_m += run.metrics.path_length_m;
    campo_time_s += run.metrics.time_s;
  }
  const std::string speeds =
      campo_time_s > 0.0
          ? "\nTimes: campo's drone covers the trees at " + fixed(campo_length_m / campo_time_s, 2) +
                " m/s on average over its reached runs, the thesis's at " +
                fixed(thesis_length_m / thesis_time_s, 2) +
                " m/s over its 12 rows, both under the 0.6 m/s limit; the thesis does not break its times down "
                "(hovering while replanning, stops at waypoints), so the difference is reported, not explained.\n"
          : "";
  claim.measured += "\nThe trees side by side, mean (minimum-maximum) over the runs that reached the goal:\n\n" +
                    markdown_table({"Resolution", "Thesis runs", "Thesis normalised", "Thesis time (s)", "campo runs",
                                    "campo reached", "campo normalised", "campo time (s)"},
                                   side_by_side) + speeds;
  // The thesis's ratio range is the trees'; the barriers' ratios are reported beside the targets, not hidden.
  std::vector<std::string> barrier_notes;
  for (int resolution : resolutions) {
    const auto found = cells.find({"two_barriers", resolution});
    if (found == cells.end() || !found->second.max_ratio_reached) continue;
    if (*found->second.max_ratio_reached > kRatioCeiling) {
      barrier_notes.push_back(std::to_string(resolution) + " x " + std::to_string(resolution) + " (worst " +
                              fixed(*found->second.max_ratio_reached, 3) + ")");
    }
  }
  if (!barrier_notes.empty()) {
    std::string list;
    for (const std::string& note : barrier_notes) list += (list.empty() ? "" : ", ") + note;
    claim.measured += "\nOutside the targets, which are the trees' (Tabella 5.1 is the second scenario): on the two "
                      "barriers some runs exceed a normalised length of " + fixed(kRatioCeiling, 2) + " at " + list +
                      ". At coarse resolutions the dilation margin, rounded up to whole pixels, narrows the 2 m "
                      "passage, and waypoints set in it are discarded more often.\n";
  }
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

void fig_5_6(const Workbench& bench, const std::vector<fs::path>& runs, Claim& claim) {
  claim.thesis = "000 §5.5.1, Figura 5.6: \"the solutions of some of the tests\", several flown paths through the "
                 "trees drawn on one map.";
  if (runs.empty()) {
    claim.measured = "No run of the trees was kept.";
    claim.verdict = Verdict::not_reproduced;
    claim.verdict_reason = "Nothing to draw.";
    return;
  }
  std::vector<std::string> args{"render"};
  for (const fs::path& run : runs) args.push_back(run.string());
  const fs::path out = bench.work("fig_5_6");
  args.insert(args.end(), {"--kind", "overlay", "--out", out.string()});
  claim.commands.push_back(bench.campo(args));
  claim.figures.push_back({bench.publish(out / "overlay.png", "000_fig_5_6_overlay.png"),
                           "The runs of the trees at the highest resolution, one colour each."});
  claim.measured = std::to_string(runs.size()) + " runs of the trees at the sweep's highest resolution (the seeds of "
                   "the Table 5.1 sweep), one colour each.";
  claim.verdict = Verdict::reproduced;
  claim.verdict_reason = "The figure is drawn from the recorded runs.";
}

void terrain_following(const Workbench& bench, Claim& claim) {
  constexpr double kAltitudeChangeMin_m = 1.5;  // the issue's "at least 1.5 m"
  constexpr double kBandMax_m = 1.0;            // height above ground held within 1 m while the altitude changes
  constexpr double kEndMargin_m = 2.0;          // take-off and arrival are not terrain following
  claim.thesis = "000 §5.4: \"This configuration lets us show another property of the system: it follows the slope "
                 "of the terrain automatically (Figura 5.5).\" Figura 5.5: \"the path chosen by the drone; note how "
                 "the algorithm adapts to the unevenness of the terrain.\"";
  const fs::path run = bench.work("trees_rolling_terrain");
  claim.commands.push_back(bench.campo({"run", "scenes/trees_rolling_terrain.json", "--out", run.string()}));
  const RecordedRun recorded = load_run_dir(run);
  const TrajectoryTable trajectory = read_trajectory_table(run / "trajectory.csv");
  const TerrainFollowing t = measure_terrain_following(
      trajectory.column("x_m"), trajectory.column("y_m"), trajectory.column("z_m"),
      trajectory.column("height_above_ground_m"), kEndMargin_m);
  const std::string outcome = recorded.record.at("/metrics/outcome"_json_pointer).get<std::string>();
  claim.figures.push_back({bench.publish(run / "side.png", "000_fig_5_5_side.png"),
                           "Side view: the flown altitude over the terrain profile under the path."});
  claim.figures.push_back({bench.publish(run / "map.png", "000_fig_5_5_map.png"),
                           "Map: the path among the trees over the terrain's contours."});
  claim.measured = "The bundled trees scene, seed 0 (" + std::to_string(t.samples) + " trajectory samples, the first "
                   "and last " + fixed(kEndMargin_m, 0) + " m excluded): outcome " + outcome + ", altitude " +
                   fixed(t.altitude_min_m, 2) + " to " + fixed(t.altitude_max_m, 2) + " m (a change of " +
                   fixed(t.altitude_change_m(), 2) + " m) while the height above the ground stayed between " +
                   fixed(t.height_above_ground_min_m, 2) + " and " + fixed(t.height_above_ground_max_m, 2) +
                   " m (a band of " + fixed(t.band_m(), 2) + " m). The side view draws the terrain profile under "
                   "the flown path.";
  TargetCheck check;
  check.expect(outcome == "reached", "the goal is reached");
  check.expect(t.altitude_change_m() >= kAltitudeChangeMin_m,
               "the altitude changes by at least " + fixed(kAltitudeChangeMin_m, 1) + " m");
  check.expect(t.samples > 0 && t.band_m() <= kBandMax_m,
               "the height above ground stays within a " + fixed(kBandMax_m, 1) + " m band");
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

void sensor_sweep(const Workbench& bench, Claim& claim) {
  claim.thesis = "000, Conclusions: \"further tests should evaluate the algorithm as other characteristics of the "
                 "drone vary, such as the LIDAR's field of view or its maximum range.\" (not measured in the thesis)";
  const fs::path spec = bench.spec("scenes/sweeps/sensor_000.json", [](nlohmann::json& d) {
    d["seeds"]["count"] = 1;
    d["axes"][0]["values"] = {60, 120};
    d["axes"][1]["values"] = {5, 20};
  });
  const fs::path dir = bench.work("sensor_000");
  claim.commands.push_back(
      bench.campo({"sweep", spec.string(), "--out", dir.string(), "--jobs", std::to_string(bench.jobs())}));
  std::string table;
  claim.commands.push_back(bench.campo({"table", dir.string(), "--no-chart"}, table));
  for (const std::string metric : {"success", "path_ratio@reached"}) {
    const fs::path png = dir / (metric.substr(0, metric.find('@')) + ".png");
    claim.commands.push_back(bench.campo({"plot", dir.string(), "--x", "max_range_m", "--y", metric, "--group",
                                          "fov_deg", "--out", png.string()}));
    claim.figures.push_back({bench.publish(png, "000_sensor_sweep_" + png.filename().string()),
                             metric == "success" ? "Success rate against the maximum range, one line per field of view."
                                                 : "Normalised path length of the runs that reached the goal against "
                                                   "the maximum range, one line per field of view."});
  }
  claim.measured = "The trees at 64 x 64, field of view (horizontal = vertical) against maximum range; each cell over "
                   "its seeds:\n\n" + table;
  claim.verdict = Verdict::reproduced;
  claim.verdict_reason = "A new experiment the thesis proposed; the table and the plots are its result, with nothing in the thesis to compare them to.";
}

}  // namespace

std::vector<Claim> seed_000_claims(const Workbench& bench) {
  std::vector<Claim> claims;
  std::vector<fs::path> tree_runs;
  claims.push_back(measure_claim("000", "Table 5.1 side by side", [&](Claim& c) { table_5_1(bench, tree_runs, c); }));
  claims.push_back(measure_claim("000", "Fig. 5.6, several runs on one map", [&](Claim& c) { fig_5_6(bench, tree_runs, c); }));
  claims.push_back(measure_claim("000", "Fig. 5.5, terrain following", [&](Claim& c) { terrain_following(bench, c); }));
  claims.push_back(measure_claim("000", "Future work: field of view and maximum range",
                                 [&](Claim& c) { sensor_sweep(bench, c); }));
  return claims;
}

}  // namespace campo
