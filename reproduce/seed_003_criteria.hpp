#pragma once
/// Seed 003's claims judged on the thesis's own criteria: each criterion a
/// pure function of measured data (runs' outcomes, tracks, routes, the gaps
/// follow-the-gap chose), tested directly in tests/reproduce/. A criterion is
/// empty (std::nullopt) when nothing was measured; campo's own tolerances are
/// shown beside the thesis's words in the report but are not arguments here
/// unless the thesis's words need a physical bound to be testable, which the
/// function's comment names.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace campo {

/// What the criteria need of one run.
struct RunOutcome {
  bool reached = false;      ///< outcome "reached"
  int collisions = 0;
  double avoiding_s = 0.0;   ///< time spent in local avoidance
  bool timed_out = false;    ///< outcome "timeout": still going at the time limit
};

/// Runs counted for a fraction (with its Wilson 95 % interval in the report).
struct OutcomeCounts {
  int runs = 0;
  int reached = 0;            ///< reached the goal
  int collision_free = 0;     ///< no collision
  int reached_clean = 0;      ///< both
  int avoided = 0;            ///< avoided at least once (avoiding_s > 0) and reached without collision
  int with_avoidance = 0;     ///< avoided at least once
};
OutcomeCounts count_outcomes(const std::vector<RunOutcome>& runs);

/// 003 §3.7 (Fig. 45): "the rover is able to go around them ... always
/// continuing toward the goal", read over random obstacle draws: every run
/// reaches the goal without a collision. Empty without runs.
std::optional<bool> every_run_reaches_without_collision(const std::vector<RunOutcome>& runs);

/// 003 §2.4.2: follow-the-gap "has no local-minimum problems": no run is
/// trapped, i.e. still short of the goal at the time limit (a collision is a
/// failure of another kind, judged by other claims). Empty without runs.
std::optional<bool> never_trapped(const std::vector<RunOutcome>& runs);

/// The longest interval (s) during which the speed stayed below
/// `still_mps`: how long a rover stood. Samples in time order, equal lengths.
double longest_standstill_s(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                            double still_mps);

/// The sides of the chosen gaps in time order, repeats merged: -1 right
/// (centre < 0, relative to the route), +1 left. Centres of exactly 0 are skipped.
std::vector<int> gap_sides(const std::vector<double>& chosen_centre_deg);

/// 003 §3.7, Fig. 46 (a)-(c): the first gap chosen is on the right, then the
/// rover inverts its turn toward a gap on the left.
bool switches_right_then_left(const std::vector<double>& chosen_centre_deg);

/// A run of the crossing walker: the chosen gaps and how it ended.
struct CrossingRun {
  std::vector<double> chosen_centre_deg;
  RunOutcome outcome;
};

/// Fig. 46 over walker start times and speeds: the thesis's criterion is that
/// the algorithm "is able to change its decision" as the walker cuts the
/// right-hand opening off (the switch right then left occurs) and "the rover
/// passes the obstacle safely (d) and continues along the original path"
/// (every run reaches without collision). Empty without runs.
std::optional<bool> fig46_holds(const std::vector<CrossingRun>& runs);
/// How many runs switch right then left.
int fig46_switches(const std::vector<CrossingRun>& runs);

/// Steering reversals: how often the heading steered for (relative to the
/// route) changes sign, ignoring values within `deadband_deg` of 0.
int steering_reversals(const std::vector<double>& heading_deg, double deadband_deg);

/// Flips of the chosen gap: its centre's values in time order are cut into
/// stretches where consecutive values differ by at most `jump_deg`; a flip is
/// a stretch that returns to within `jump_deg` of the stretch before the
/// previous one (A, B, A: the choice went back). Non-finite values are skipped.
int gap_flips(const std::vector<double>& chosen_centre_deg, double jump_deg);

/// 003 §3.6, Fig. 44: between two gaps of similar score the choice may flip
/// "continuously and suddenly" (a zig-zag), which the bonus for the previous
/// gap resolves. The criterion: without the bonus at least one run is
/// indecisive (`indecisive` or more flips, or reversals) and with it none is.
/// Empty when either list is empty.
std::optional<bool> hysteresis_holds(const std::vector<int>& flips_without_bonus,
                                     const std::vector<int>& flips_with_bonus, int indecisive);

/// Signed distance from `point` to the polyline `route`: positive left of its
/// direction at the nearest segment. Infinity for an empty route.
double signed_cross_track(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& route);

/// Curvature of `route` (1/m) at each of its points: the turn between the
/// segments before and after it over their mean length (0 at the ends).
std::vector<double> route_curvature(const std::vector<Eigen::Vector2d>& route);

/// Mean speed of the samples whose nearest route point is on a straight
/// (|curvature| <= `straight_max`) against on a curve (>= `curve_min`).
struct SpeedByCurvature {
  int straight_samples = 0, curve_samples = 0;
  double straight_mps = 0.0, curve_mps = 0.0;
  double straight_cross_track_max_m = 0.0, curve_cross_track_max_m = 0.0;
};
SpeedByCurvature speed_by_curvature(const std::vector<Eigen::Vector2d>& track, const std::vector<double>& speed_mps,
                                    const std::vector<Eigen::Vector2d>& route, double straight_max, double curve_min);

/// 003 §3.7: "without obstacles the rover follows the desired trajectory
/// precisely ... slowing down when it drives a curve". Testable as: it never
/// leaves its inter-row (cross-track max below `free_half_width_m`, the
/// inter-row's free half width less the rover's half width: a physical bound
/// of the scene, not a tolerance) and its mean speed on curves is below that
/// on straights. Empty when no sample lies on a straight or on a curve.
std::optional<bool> tracking_holds(double cross_track_max_m, double free_half_width_m, const SpeedByCurvature& s);

/// The distance travelled along `track` until it first comes within
/// `within_m` of `route`; empty when it never does.
std::optional<double> distance_to_rejoin_m(const std::vector<Eigen::Vector2d>& track,
                                           const std::vector<Eigen::Vector2d>& route, double within_m);

/// 003 §3.7: pure pursuit lets the rover re-enter the path "if its initial
/// position does not match the start of the computed path": every run
/// rejoins (a distance) and reaches the goal. Empty without runs.
std::optional<bool> every_run_rejoins(const std::vector<std::optional<double>>& rejoin_m,
                                      const std::vector<RunOutcome>& runs);

/// Oscillations of a signed offset: how often it swings from beyond
/// +`band_m` to beyond -`band_m` or back.
int oscillations(const std::vector<double>& signed_offset_m, double band_m);

/// How far the track passes from the route's curves: the largest distance from
/// a route point of |curvature| >= `curve_min` to the nearest track sample
/// (a track that cuts a corner passes far from the arc's apex). 0 when the
/// route has no such point; infinity when the track is empty.
double curve_miss_m(const std::vector<Eigen::Vector2d>& route, const std::vector<Eigen::Vector2d>& track,
                    double curve_min);

/// One lookahead distance's tracking of the same route.
struct LookaheadRun {
  double lookahead_m = 0.0;
  int straight_oscillations = 0;        ///< oscillations on the straights
  double curve_miss_m = 0.0;            ///< curve_miss_m(): how far the track passes from the curves
};

/// 003 §3.4, Fig. 35: "very small values lead to tracking rich in oscillations
/// (instability), very large values create the problem of cutting corners":
/// the smallest lookahead oscillates more on the straights than the
/// `reference_m` one, and the largest leaves the curves by more than it.
/// Empty when the runs do not include the reference and a smaller and a larger value.
std::optional<bool> lookahead_holds(const std::vector<LookaheadRun>& runs, double reference_m);

/// A straight segment and a circular arc (as its whole circle) of a route's geometry.
struct Segment2 {
  Eigen::Vector2d a, b;
};
struct Circle2 {
  Eigen::Vector2d centre;
  double radius_m = 0.0;
};
/// The largest distance from any of `points` to the nearest of `segments` and
/// `circles` (how far the route departs from "straight stretches between two
/// rows, and arcs of circle for leaving one inter-row and entering the next").
double max_distance_to_geometry(const std::vector<Eigen::Vector2d>& points, const std::vector<Segment2>& segments,
                                const std::vector<Circle2>& circles);

}  // namespace campo
