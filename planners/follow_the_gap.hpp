#pragma once
/// Follow-the-gap obstacle avoidance on a planar scan (003 §3.6, SPEC §7.3)
/// as a pure function. Angles are in the robot frame (the scan's frame: x
/// forward, y left, counter-clockwise positive, 0 = straight ahead); the
/// caller adds the robot's heading to steer in the world.
#include <cmath>
#include <span>
#include <vector>

namespace campo {

/// One planar scan: beam i looks at first_angle_rad + i increment_rad. The
/// defaults are the planar180 sensor's layout (+90 deg .. -90 deg, 1 deg steps).
struct PlanarScanView {
  std::span<const float> ranges_m;  ///< per beam; >= max range (or not finite) = no return
  double first_angle_rad = M_PI / 2.0;
  double increment_rad = -M_PI / 180.0;

  double angle(int beam) const { return first_angle_rad + beam * increment_rad; }
};

struct FollowTheGapConfig {
  double activation_range_m = 3.5;  ///< avoid only when the nearest reading is below this, m (003 §3.6)
  double max_range_m = 20.0;        ///< the sensor's maximum; readings at or beyond it become max + 1 m
  double bubble_radius_m = 0.8;     ///< R: the rover's half-diagonal plus a margin, m, > 0
  double gap_jump_m = 1.0;          ///< 003 gaps only: a range step between neighbouring beams above this splits a gap, m
  /// > 0: campo's free-space gaps. Every reading nearer than this + R is
  /// grown by R (not only the nearest), each beam shortened to how far a disc
  /// of radius R drives along it, and a gap is a maximal run of beams longer
  /// than this; the heading stays inside its gap. 0: 003's gaps, every
  /// unblocked run between range steps. m, >= 0
  double free_range_m = 3.5;
  /// 003's gaps only (free_range_m = 0). true: 003 §2.4.2's point-robot
  /// approach applied to each gap's edges: the near side of every range step
  /// bounding a gap is grown by R (the gap loses asin(R / d) there), a gap
  /// left with no directions is dropped, and phi_gap is clamped to what
  /// remains. false: the gaps as §3.6 prints them, where only the nearest
  /// reading is grown, an opening only a point fits is a gap and phi_gap may
  /// leave its gap (the rover then heads for a box's edge and stands there).
  bool grow_gap_edges = true;
  double alpha_m = 1.0;             ///< a in phi_gap: weight of the gap centre against the goal, m, >= 0
  double k_width = 1.0;             ///< k1: score per metre of width times normalised depth
  double k_heading = 1.0;           ///< k2: score per radian of alignment with the goal
  double hysteresis_bonus = 0.5;    ///< added to the score of the gap overlapping the previous choice, >= 0
};

/// What follow-the-gap carries from one step to the next: the chosen gap, in
/// the world frame so a turning robot still recognises it.
struct FollowTheGapState {
  bool has_previous = false;
  double previous_center_world_rad = 0.0;  ///< centre angle of the chosen gap, world frame
  double previous_half_width_rad = 0.0;    ///< half its angular extent (beams x increment / 2)
};

/// A run of consecutive beams between discontinuities and blocked sectors
/// (with free_range_m: a run of free beams).
struct ScanGap {
  int first_beam = 0;        ///< inclusive, scan order
  int last_beam = 0;         ///< inclusive
  double center_rad = 0.0;   ///< phi_center: middle of the end beams' angles
  double heading_rad = 0.0;  ///< phi_gap, the heading this gap proposes
  double width_m = 0.0;      ///< L_gap: distance between the end readings (law of cosines)
  double mean_range = 0.0;   ///< d_gap: mean processed range over max_range_m
  double score = 0.0;        ///< U, including the hysteresis bonus when given
  bool previous = false;     ///< received the hysteresis bonus
};

struct FollowTheGapStep {
  bool active = false;           ///< an obstacle is nearer than activation_range_m
  double heading_rad = 0.0;      ///< robot frame: the chosen gap's heading; the goal bearing when inactive or no gap
  int nearest_beam = -1;         ///< beam of d_min (first of equals)
  double nearest_range_m = 0.0;  ///< d_min
  int bubble_half_width = 0;     ///< N: blocked sectors each side of the nearest beam (before clipping)
  int bubble_first_beam = 0;     ///< blocked sectors, inclusive, clipped to the scan (active only)
  int bubble_last_beam = -1;
  std::vector<float> ranges_m;  ///< processed: saturated, bubble set to 0, free distances with free_range_m (active only)
  std::vector<ScanGap> gaps;    ///< active only, scan order
  int chosen = -1;              ///< index into gaps; -1 when inactive or no gap is left
};

/// Number of sectors the safety bubble blocks each side of the nearest
/// reading: N = R / (d_min dalpha), rounded up so the bubble covers at least R.
int bubble_half_width(double radius_m, double nearest_range_m, double increment_rad);

/// How far a disc of radius `radius_m` starting at the sensor drives along
/// the direction `offset_rad` away from a point `range_m` away before it
/// touches the point; infinity when it never does (the point is more than the
/// radius off the line, or behind), 0 when it already touches.
double free_distance(double range_m, double offset_rad, double radius_m);

/// One follow-the-gap step (003 §3.6). `goal_bearing_rad`, in (-pi, pi], is
/// the direction of the pure-pursuit goal point in the robot frame;
/// `robot_heading_rad` (world) only keeps the hysteresis state in the world
/// frame. Readings at or beyond max_range_m saturate to max + 1 m; when the
/// nearest one (d_min) is below activation_range_m, N sectors each side of it
/// are set to 0 (the bubble; ties: the first beam), the rest splits into gaps
/// at zeroed sectors and at range steps above gap_jump_m (with free_range_m
/// > 0: readings are grown by R and gaps are the runs of free beams, see
/// there), and each gap gets
///   phi_gap = ((a / d_min) phi_center + phi_goal) / (a / d_min + 1),
///   U = k1 L_gap d_gap + k2 (pi - |phi_gap - phi_goal|),
/// (with free_range_m > 0, phi_gap clamped to the gap's beams; with 003's
/// gaps and grow_gap_edges, clamped to the gap less asin(R / d) at each
/// range-step edge of nearer range d, and gaps left empty dropped)
/// plus the bonus for the gap overlapping most the previous choice. The best
/// gap is chosen and remembered; an inactive step forgets the previous one.
FollowTheGapStep follow_the_gap_step(const FollowTheGapConfig& config, FollowTheGapState& state,
                                     const PlanarScanView& scan, double goal_bearing_rad, double robot_heading_rad);

}  // namespace campo
