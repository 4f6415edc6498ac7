#pragma once
/// Seed 000's claims judged on the thesis's own criteria: each criterion a
/// pure function of measured data (runs' outcomes and counts, trajectories),
/// tested directly in tests/reproduce/. A criterion is empty (std::nullopt)
/// when nothing was measured. Where the thesis's words need a bound to be
/// testable, the function's comment names the bound and why; campo's own
/// tolerances are shown beside the thesis's numbers in the report but are
/// never arguments here.
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace campo {

/// One row of 000 Tabella 5.1 (the second scenario, trees on rolling terrain), as printed.
struct ThesisTable51Row {
  int resolution = 0;
  int reached = 0;    ///< intermediate waypoints reached ("Raggiunti")
  int discarded = 0;  ///< waypoints chosen and later discarded ("Scartati")
  double length_m = 0.0;
  double ratio = 0.0;  ///< normalised by the 23.27 m straight line
  double time_s = 0.0;
};

/// The twelve rows of Tabella 5.1, in the thesis's order.
std::span<const ThesisTable51Row> thesis_table_5_1();

/// 000 §5.5.1: "the ratio to the straight-line distance never exceeds the threshold of 1.10".
inline constexpr double kThesisRatioCeiling = 1.10;

/// What the criteria need of one run of the depth planner.
struct DepthRun {
  bool completed = false;  ///< the run produced its record
  bool reached = false;    ///< outcome "reached"
  int collisions = 0;
  double path_ratio = 0.0;
  int waypoints_planned = 0;    ///< intermediate waypoints set (TrovaWP)
  int waypoints_reached = 0;    ///< intermediate waypoints reached
  int waypoints_discarded = 0;  ///< intermediate waypoints found invisible or unreachable and dropped
};

/// Mean and sample standard deviation of values (sd 0 for fewer than two); empty values: n 0.
struct SampleStats {
  int n = 0;
  double mean = 0.0, sd = 0.0;
};
SampleStats sample_stats(const std::vector<double>& values);

/// 000 §5.5.1 on Tabella 5.1: "the algorithm completes the path ... the ratio
/// to the straight-line distance never exceeds the threshold of 1.10". Holds
/// when every run reached the goal and no run's normalised length exceeds
/// `ceiling` (the thesis's 1.10). Empty without runs.
std::optional<bool> ratio_never_exceeds(const std::vector<DepthRun>& runs, double ceiling);

/// How a flight crossed the line of two barriers (000 §5.4, first scenario).
enum class PassageCrossing {
  through_gap,   ///< between the barriers' inner ends, below their tops: "flying in the space between one obstacle and the other"
  over,          ///< at or above the barriers' tops
  around,        ///< below the tops, past a barrier's outer end
  into_barrier,  ///< below the tops, within a barrier's span (a collision, or through it)
  never,         ///< the track never crossed the barriers' line
};
const char* passage_crossing_name(PassageCrossing c);

/// The barriers along the line x = `line_x_m`: one spans y from `outer_lo_m`
/// to `gap_lo_m`, the other from `gap_hi_m` to `outer_hi_m`, their tops at
/// `top_m`.
struct BarrierLine {
  double line_x_m = 0.0;
  double outer_lo_m = 0.0, gap_lo_m = 0.0, gap_hi_m = 0.0, outer_hi_m = 0.0;
  double top_m = 0.0;
};

/// How the track (equal-length x, y, z samples in time order) first crossed
/// the barriers' line, its y and z interpolated at the crossing.
PassageCrossing first_passage_crossing(std::span<const double> x_m, std::span<const double> y_m,
                                       std::span<const double> z_m, const BarrierLine& barriers);

/// How many pixel columns of a gap the depth planner's dilation leaves free,
/// seen from the sensor: the gap's angular width between its edges (bearings
/// `edge_a_deg` and `edge_b_deg`, at ranges `range_a_m` and `range_b_m`) in
/// pixels of `fov_deg` / `pixels`, less the dilation each edge gets
/// (margin_radius_px: asin(margin / range) plus half a pixel, rounded up).
/// Below 1 the dilated map shows no free column: the planner cannot set a
/// waypoint through the gap from there. Evidence for why a run climbed over
/// the barriers instead.
double free_gap_columns(double edge_a_deg, double range_a_m, double edge_b_deg, double range_b_m, double margin_m,
                        double fov_deg, int pixels);

/// A run of the barriers: its outcome and how it crossed.
struct BarrierRun {
  DepthRun run;
  PassageCrossing crossing = PassageCrossing::never;
};

/// 000 §5.5: "The first scenario was solved in the same way as already
/// described, even after an extreme reduction of the LIDAR's resolution
/// (16x16)"; §5.4 describes it: "we expect the drone to reach the goal flying
/// in the space between one obstacle and the other". Holds when every run
/// reached the goal without a collision through the gap. Empty without runs.
std::optional<bool> barriers_solved_through_gap(const std::vector<BarrierRun>& runs);

/// 000 §5.4 (first scenario, 256 x 256): "the drone manages to set an
/// intermediate waypoint" and completes the mission. Holds when every run
/// reached the goal having set exactly one intermediate waypoint and reached
/// it. Empty without runs.
std::optional<bool> one_intermediate_waypoint(const std::vector<DepthRun>& runs);

/// 000 §5.4 (second scenario, 256 x 256): "our algorithm generates four
/// intermediate waypoints before reaching the goal" (one run). Read as four
/// to the nearest whole waypoint: holds when the mean number set per run over
/// the runs that reached the goal lies in [count - 0.5, count + 0.5). Empty
/// when no run reached the goal.
std::optional<bool> about_count(const std::vector<DepthRun>& runs, int count);

/// Two samples' means compared: holds when they differ by at most 1.96 times
/// the standard error of their difference (Welch), i.e. the thesis's mean is
/// inside the 95 % interval of the difference being zero. This is how "about
/// 1.4 per run" is judged: the thesis's 1.4 is the mean of its twelve runs,
/// with their spread, so campo's mean is "about" it when the two are not
/// distinguishable at the 5 % level. Empty when either sample has fewer than
/// two values.
struct MeansCompared {
  SampleStats a, b;
  double difference = 0.0;      ///< b.mean - a.mean
  double standard_error = 0.0;  ///< sqrt(sd_a^2 / n_a + sd_b^2 / n_b)
};
MeansCompared compare_means(const std::vector<double>& a, const std::vector<double>& b);
std::optional<bool> means_agree(const MeansCompared& c);

/// The height of a flight above the ground while it crosses the relief (000
/// §5.4 and Fig. 5.5: "it follows the inclination of the terrain
/// automatically"): over the cruise samples (horizontal distance at least
/// `end_margin_m` from the first and the last sample), the ground under the
/// drone (z - height above ground) and its height above it.
struct GroundFollowing {
  int samples = 0;
  double ground_min_m = 0.0, ground_max_m = 0.0;  ///< the ground under the path
  double height_min_m = 0.0, height_max_m = 0.0;  ///< above that ground
  double relief_m() const { return ground_max_m - ground_min_m; }
  double band_m() const { return height_max_m - height_min_m; }
};
GroundFollowing measure_ground_following(std::span<const double> x_m, std::span<const double> y_m,
                                         std::span<const double> z_m, std::span<const double> height_above_ground_m,
                                         double end_margin_m);

/// One run holds "a steady height above the ground whatever the hill" when
/// its height above the ground varied by less than half the ground's rise and
/// fall under its path. The bound is physical, not a tolerance: a flight at
/// one altitude that ignored the terrain would see its height above the
/// ground vary by the whole relief under its path, a flight that followed it
/// perfectly by nothing; following means the altitude takes up most (more
/// than half) of the relief. Also required: it reached the goal without a
/// collision. Empty when no cruise sample was measured or the path crossed no
/// relief at all (nothing to follow).
std::optional<bool> follows_terrain(const GroundFollowing& g, const DepthRun& run);

/// Every run holds: empty when the list is empty or any run's criterion is empty.
std::optional<bool> all_hold(const std::vector<std::optional<bool>>& each);

/// 000 Fig. 5.6, "the solutions of some of the tests": every run drawn reached
/// the goal without a collision. Empty without runs.
std::optional<bool> every_run_reaches_cleanly(const std::vector<DepthRun>& runs);

}  // namespace campo
