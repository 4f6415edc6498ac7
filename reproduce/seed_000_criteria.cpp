#include "reproduce/seed_000_criteria.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planners/depth_reactive_steps.hpp"

namespace campo {

namespace {

// 000 Tabella 5.1 as printed: resolution, waypoints reached and discarded, length (m), normalised, time (mm:ss.s in
// the thesis, seconds here).
constexpr ThesisTable51Row kTable51[] = {
    {256, 2, 0, 24.16, 1.04, 58.6},  {256, 2, 1, 23.83, 1.03, 72.0},  {256, 3, 0, 23.43, 1.01, 82.5},
    {128, 2, 1, 23.62, 1.02, 73.0},  {128, 4, 1, 24.08, 1.03, 92.0},  {128, 3, 1, 23.54, 1.01, 72.1},
    {64, 4, 5, 24.99, 1.07, 129.6},  {64, 3, 2, 24.19, 1.04, 80.7},   {64, 3, 1, 23.68, 1.02, 80.3},
    {32, 4, 1, 23.73, 1.02, 85.8},   {32, 3, 2, 24.05, 1.03, 106.2},  {32, 3, 2, 23.79, 1.02, 78.3},
};

}  // namespace

std::span<const ThesisTable51Row> thesis_table_5_1() { return kTable51; }

SampleStats sample_stats(const std::vector<double>& values) {
  SampleStats s;
  s.n = static_cast<int>(values.size());
  if (s.n == 0) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(squares / (s.n - 1));
  return s;
}

std::optional<bool> ratio_never_exceeds(const std::vector<DepthRun>& runs, double ceiling) {
  if (runs.empty()) return std::nullopt;
  return std::all_of(runs.begin(), runs.end(),
                     [&](const DepthRun& r) { return r.completed && r.reached && r.path_ratio <= ceiling; });
}

const char* passage_crossing_name(PassageCrossing c) {
  switch (c) {
    case PassageCrossing::through_gap: return "through the gap";
    case PassageCrossing::over: return "over a barrier";
    case PassageCrossing::around: return "around a barrier's outer end";
    case PassageCrossing::into_barrier: return "into a barrier";
    case PassageCrossing::never: return "never crossed";
  }
  return "?";
}

PassageCrossing first_passage_crossing(std::span<const double> x_m, std::span<const double> y_m,
                                       std::span<const double> z_m, const BarrierLine& b) {
  const std::size_t n = std::min({x_m.size(), y_m.size(), z_m.size()});
  for (std::size_t i = 1; i < n; ++i) {
    const double a = x_m[i - 1] - b.line_x_m, c = x_m[i] - b.line_x_m;
    if (a == 0.0 && c == 0.0) continue;
    if ((a < 0.0) == (c < 0.0) && a != 0.0 && c != 0.0) continue;
    const double f = a / (a - c);
    const double y = y_m[i - 1] + f * (y_m[i] - y_m[i - 1]), z = z_m[i - 1] + f * (z_m[i] - z_m[i - 1]);
    if (z >= b.top_m) return PassageCrossing::over;
    if (y > b.gap_lo_m && y < b.gap_hi_m) return PassageCrossing::through_gap;
    if (y < b.outer_lo_m || y > b.outer_hi_m) return PassageCrossing::around;
    return PassageCrossing::into_barrier;
  }
  return PassageCrossing::never;
}

double free_gap_columns(double edge_a_deg, double range_a_m, double edge_b_deg, double range_b_m, double margin_m,
                        double fov_deg, int pixels) {
  const double deg_per_px = fov_deg / pixels;
  const double width_px = std::abs(edge_b_deg - edge_a_deg) / deg_per_px;
  return width_px - margin_radius_px(margin_m, range_a_m, deg_per_px, pixels) -
         margin_radius_px(margin_m, range_b_m, deg_per_px, pixels);
}

std::optional<bool> barriers_solved_through_gap(const std::vector<BarrierRun>& runs) {
  if (runs.empty()) return std::nullopt;
  return std::all_of(runs.begin(), runs.end(), [](const BarrierRun& r) {
    return r.run.completed && r.run.reached && r.run.collisions == 0 && r.crossing == PassageCrossing::through_gap;
  });
}

std::optional<bool> one_intermediate_waypoint(const std::vector<DepthRun>& runs) {
  if (runs.empty()) return std::nullopt;
  return std::all_of(runs.begin(), runs.end(), [](const DepthRun& r) {
    return r.completed && r.reached && r.waypoints_planned == 1 && r.waypoints_reached == 1;
  });
}

std::optional<bool> about_count(const std::vector<DepthRun>& runs, int count) {
  std::vector<double> set;
  for (const DepthRun& r : runs) {
    if (r.completed && r.reached) set.push_back(r.waypoints_planned);
  }
  if (set.empty()) return std::nullopt;
  const double mean = sample_stats(set).mean;
  return mean >= count - 0.5 && mean < count + 0.5;
}

MeansCompared compare_means(const std::vector<double>& a, const std::vector<double>& b) {
  MeansCompared c;
  c.a = sample_stats(a);
  c.b = sample_stats(b);
  c.difference = c.b.mean - c.a.mean;
  if (c.a.n > 0 && c.b.n > 0) {
    c.standard_error = std::sqrt(c.a.sd * c.a.sd / c.a.n + c.b.sd * c.b.sd / c.b.n);
  }
  return c;
}

std::optional<bool> means_agree(const MeansCompared& c) {
  if (c.a.n < 2 || c.b.n < 2) return std::nullopt;
  return std::abs(c.difference) <= 1.96 * c.standard_error;
}

GroundFollowing measure_ground_following(std::span<const double> x_m, std::span<const double> y_m,
                                         std::span<const double> z_m, std::span<const double> height_above_ground_m,
                                         double end_margin_m) {
  GroundFollowing g;
  const std::size_t n = std::min({x_m.size(), y_m.size(), z_m.size(), height_above_ground_m.size()});
  if (n == 0) return g;
  const auto distance = [&](std::size_t i, std::size_t j) { return std::hypot(x_m[i] - x_m[j], y_m[i] - y_m[j]); };
  double ground_lo = std::numeric_limits<double>::infinity(), ground_hi = -ground_lo;
  double height_lo = ground_lo, height_hi = -ground_lo;
  for (std::size_t i = 0; i < n; ++i) {
    if (distance(i, 0) < end_margin_m || distance(i, n - 1) < end_margin_m) continue;
    if (!std::isfinite(height_above_ground_m[i]) || !std::isfinite(z_m[i])) continue;
    const double ground = z_m[i] - height_above_ground_m[i];
    ground_lo = std::min(ground_lo, ground);
    ground_hi = std::max(ground_hi, ground);
    height_lo = std::min(height_lo, height_above_ground_m[i]);
    height_hi = std::max(height_hi, height_above_ground_m[i]);
    ++g.samples;
  }
  if (g.samples == 0) return g;
  g.ground_min_m = ground_lo;
  g.ground_max_m = ground_hi;
  g.height_min_m = height_lo;
  g.height_max_m = height_hi;
  return g;
}

std::optional<bool> follows_terrain(const GroundFollowing& g, const DepthRun& run) {
  if (g.samples == 0 || !(g.relief_m() > 0.0)) return std::nullopt;
  return run.completed && run.reached && run.collisions == 0 && g.band_m() < 0.5 * g.relief_m();
}

std::optional<bool> all_hold(const std::vector<std::optional<bool>>& each) {
  if (each.empty()) return std::nullopt;
  bool all = true;
  for (const std::optional<bool>& e : each) {
    if (!e) return std::nullopt;
    all = all && *e;
  }
  return all;
}

std::optional<bool> every_run_reaches_cleanly(const std::vector<DepthRun>& runs) {
  if (runs.empty()) return std::nullopt;
  return std::all_of(runs.begin(), runs.end(),
                     [](const DepthRun& r) { return r.completed && r.reached && r.collisions == 0; });
}

}  // namespace campo
