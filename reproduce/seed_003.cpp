// Seed 003 (vineyard rover): 003 §3.6-3.7, Fig. 45 and Fig. 46.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/run_files.hpp"
#include "reproduce/claims.hpp"
#include "reproduce/trajectory_checks.hpp"

namespace campo {

namespace fs = std::filesystem;

namespace {

std::string metrics_table(const std::vector<std::pair<std::string, nlohmann::json>>& runs) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& [label, m] : runs) {
    rows.push_back({label, m.at("outcome").get<std::string>(), fixed(m.at("sim_time_s").get<double>(), 1),
                    fixed(m.at("path_length_m").get<double>(), 1), std::to_string(m.at("collisions").get<int>()),
                    fixed(m.at("min_clearance_m").get<double>(), 2) + " (" + m.value("nearest_obstacle", "") + ")",
                    fixed(m.value("cross_track_rms_m", 0.0), 2), fixed(m.value("cross_track_max_m", 0.0), 2),
                    fixed(m.value("avoiding_time_s", 0.0), 1)});
  }
  return markdown_table({"Run", "Outcome", "Time (s)", "Path (m)", "Collisions", "Min clearance (m)",
                         "Cross-track rms (m)", "Cross-track max (m)", "Avoiding (s)"},
                        rows);
}

// After each avoidance (intervals closer than kMergeGap_s merged), how close the rover came back to its route
// before the next avoidance or the end: the smallest cross-track error in that stretch.
std::vector<std::pair<AvoidanceSpan, double>> rejoins(const RecordedRun& run) {
  constexpr double kMergeGap_s = 3.0;
  std::vector<AvoidanceSpan> spans;
  for (const auto& [start, end] : run.view.avoiding_s) {
    if (!spans.empty() && start - spans.back().end_s < kMergeGap_s) spans.back().end_s = end;
    else spans.push_back({start, end});
  }
  std::vector<Eigen::Vector2d> route;
  for (const Eigen::Vector3d& p : run.view.planned_path) route.push_back(p.head<2>());
  std::vector<std::pair<AvoidanceSpan, double>> out;
  for (std::size_t i = 0; i < spans.size(); ++i) {
    const double until = i + 1 < spans.size() ? spans[i + 1].start_s : run.view.track.back().time_s;
    double closest = std::numeric_limits<double>::infinity();
    for (const TrackPoint& p : run.view.track) {
      if (p.time_s < spans[i].end_s || p.time_s > until) continue;
      closest = std::min(closest, distance_to_polyline(p.position_m.head<2>(), route));
    }
    out.push_back({spans[i], closest});
  }
  return out;
}

void fig_45(const Workbench& bench, Claim& claim) {
  constexpr double kRejoin_m = 0.1;
  constexpr double kClearanceFloor_m = 0.05;
  claim.thesis = "003 §3.7, Fig. 45: \"obstacles were inserted randomly in a portion of the map; the rover is able "
                 "to go around them, deviating from the initially computed path but always continuing toward the "
                 "goal ... also in complicated situations, such as near a curve and in areas occupied by multiple "
                 "obstacles\"; \"Pure Pursuit also allows re-entering the path once the deviation is over\".";
  const fs::path run_dir = bench.work("003_fig45");
  claim.commands.push_back(bench.campo({"run", "scenes/vineyard_obstacles.json", "--out", run_dir.string()}));
  const RecordedRun run = load_run_dir(run_dir);
  const nlohmann::json& m = run.record.at("metrics");
  std::vector<std::vector<std::string>> rows;
  TargetCheck check;
  for (const auto& [span, closest] : rejoins(run)) {
    rows.push_back({fixed(span.start_s, 1) + "-" + fixed(span.end_s, 1), fixed(closest, 3)});
    check.expect(closest <= kRejoin_m, "back within " + fixed(kRejoin_m, 1) + " m of the route after the avoidance "
                                           "ending at " + fixed(span.end_s, 1) + " s");
  }
  check.expect(m.at("outcome") == "reached", "the route is completed");
  check.expect(m.at("collisions").get<int>() == 0 && m.at("min_clearance_m").get<double>() >= kClearanceFloor_m,
               "no collision, true clearance at least " + fixed(kClearanceFloor_m, 2) + " m");
  check.expect(rows.size() >= 3, "the three places (row, headland turn, cluster) each make an avoidance");
  claim.measured = "scenes/vineyard_obstacles.json: a box in the first inter-row, one on the headland turn between "
                   "the rows and a cluster of three in the second inter-row, each in the route's way (placed by "
                   "hand, where the thesis drew them at random, so that every case it names occurs: a row, a curve, "
                   "several obstacles together); the rover's local planner follow-the-gap, pure pursuit on the route.\n\n" +
                   metrics_table({{"vineyard_obstacles", m}}) +
                   "\nEach avoidance (intervals less than 3 s apart merged) and the smallest distance to the route "
                   "after it, before the next one:\n\n" +
                   markdown_table({"Avoiding (s)", "Back to the route (m)"}, rows);
  claim.figures.push_back({bench.publish(run_dir / "map.png", "003_fig_45_map.png"),
                           "Fig. 45: the route, the obstacles and the track, amber where the rover was avoiding."});
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

void fig_46(const Workbench& bench, Claim& claim) {
  claim.thesis = "003 §3.7, Fig. 46: \"an obstacle crosses the rover's field of view from left to right. Initially "
                 "the obstacle is on the vehicle's left (a), so the algorithm selects the opening on the right and "
                 "starts heading to it. Then the obstacle starts moving right (b), cutting the rover's way and "
                 "increasingly blocking the opening on its right. The algorithm reacts by inverting the turning "
                 "direction (c), favouring the new opening on the left ... the rover passes the obstacle safely (d) "
                 "and continues along the original path.\"";
  const fs::path run_dir = bench.work("003_fig46");
  claim.commands.push_back(bench.campo({"run", "scenes/vineyard_gap.json", "--out", run_dir.string()}));
  claim.commands.push_back(bench.campo({"render", run_dir.string(), "--kind", "sequence"}));
  const RecordedRun run = load_run_dir(run_dir);
  const nlohmann::json& m = run.record.at("metrics");
  // The chosen gaps in time order: which side of the route each lies on (its centre) and the heading steered for.
  std::vector<std::vector<std::string>> rows;
  std::vector<int> sides;
  for (const PlannerEvent& event : run.events) {
    const std::optional<GapDecision>& gap = event.decisions.gap;
    if (!gap || !gap->chosen) continue;
    const ChosenGap& chosen = *gap->chosen;
    const int side = chosen.center_deg > 0.0 ? 1 : -1;
    if (sides.empty() || sides.back() != side) {
      sides.push_back(side);
      rows.push_back({fixed(event.time_s, 1), side > 0 ? "left" : "right", fixed(chosen.center_deg, 1),
                      fixed(chosen.heading_deg, 1)});
    }
  }
  TargetCheck check;
  check.expect(sides.size() >= 2 && sides[0] < 0 && sides[1] > 0, "the first gap chosen is on the right, then the "
                                                                   "rover switches to the left");
  check.expect(sides.size() == 2, "it does not switch back");
  check.expect(m.at("outcome") == "reached" && m.at("collisions").get<int>() == 0,
               "it passes without collision and completes the route");
  check.expect(m.value("cross_track_max_m", 1e9) < 1.0, "it stays within 1 m of the route");
  claim.measured = "scenes/vineyard_gap.json: a person 0.6 m left of the route ahead walks right across it from 8 s "
                   "(a mover); the rover's local planner follow-the-gap with the thesis's own gaps (range "
                   "discontinuities). The chosen gap each time it changed sides (events.jsonl, decisions.gap: "
                   "gap_center_deg, the gap's centre, and gap_heading_deg, the heading steered for, both relative to "
                   "the route, positive left):\n\n" +
                   markdown_table({"Time (s)", "Side", "Gap centre (°)", "Heading (°)"}, rows) + "\n" +
                   metrics_table({{"vineyard_gap", m}});
  claim.figures.push_back({bench.publish(run_dir / "sequence.png", "003_fig_46_sequence.png"),
                           "Fig. 46 (a)-(d): the walker, the track so far and the chosen gap at four instants."});
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

void not_stuck(const Workbench& bench, Claim& claim) {
  constexpr double kLongestAvoidance_s = 30.0;
  claim.thesis = "003 §3.6 and §2.4.2: gaps are found from \"two consecutive sensor measurements with a certain "
                 "discontinuity\", obstacles \"enlarged by a radius equal to r_rob\" (the point-robot approach); "
                 "the rover drives round the obstacle and on.";
  const fs::path run_dir = bench.work("003_thesis_gaps");
  claim.commands.push_back(bench.campo({"run", "scenes/vineyard_obstacles.json", "--set",
                                        "/objects/rover/planner/params/follow_the_gap/free_range_m=0", "--out",
                                        run_dir.string()}));
  const RecordedRun run = load_run_dir(run_dir);
  const nlohmann::json& m = run.record.at("metrics");
  double longest_s = 0.0;
  for (const auto& [start, end] : run.view.avoiding_s) longest_s = std::max(longest_s, end - start);
  TargetCheck check;
  check.expect(m.at("outcome") == "reached", "the route is completed");
  check.expect(longest_s < kLongestAvoidance_s, "no avoidance lasts " + fixed(kLongestAvoidance_s, 0) + " s or more");
  check.expect(m.at("collisions").get<int>() == 0, "no collision");
  claim.measured = "The Fig. 45 scene with the thesis's own gap definition (free_range_m 0: gaps only at range "
                   "discontinuities): the longest avoidance took " + fixed(longest_s, 1) + " s. Before the gaps' edges "
                   "were grown by the rover's radius and the stopped rover turned away from the obstacle's side, the "
                   "rover stood behind the first box from 7.6 s to 813 s and timed out at 900 s.\n\n" +
                   metrics_table({{"vineyard_obstacles, thesis gaps", m}});
  claim.figures.push_back({bench.publish(run_dir / "map.png", "003_thesis_gaps_map.png"),
                           "Follow-the-gap with the thesis's gaps on the Fig. 45 scene."});
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

}  // namespace

std::vector<Claim> seed_003_claims(const Workbench& bench) {
  std::vector<Claim> claims;
  claims.push_back(measure_claim("003", "Fig. 45, obstacles on the route", [&](Claim& c) { fig_45(bench, c); }));
  claims.push_back(measure_claim("003", "Fig. 46, a crossing obstacle and follow-the-gap",
                                 [&](Claim& c) { fig_46(bench, c); }));
  claims.push_back(measure_claim("003", "Follow-the-gap with the thesis's gaps does not get stuck",
                                 [&](Claim& c) { not_stuck(bench, c); }));
  return claims;
}

}  // namespace campo
