#pragma once
/// The steps of seed 000's reactive depth-map navigation (000 §4, SPEC §7.1)
/// as pure functions on depth maps (CV_32F, SPEC §6: value = range / d_max in
/// [0, 1], 1 = no return, 0 = nearer than d_min; pixel (0,0) top-left, x
/// right, y down). The planner (depth_reactive.cpp) strings them together.
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/range_scan.hpp"
#include "campo/range_sensor_config.hpp"

namespace campo {

/// The angular grid of a depth map: pixel centres equiangular in azimuth and
/// elevation (RangeSensorConfig's convention), ranges up to max_range_m.
struct DepthGrid {
  int cols = 0;
  int rows = 0;
  double fov_h_deg = 90.0;
  double fov_v_deg = 90.0;
  double max_range_m = 10.0;

  /// The grid of `scan`'s depth map: its rows and columns, as the scan was
  /// laid out; the angles and the range from its sensor's `config`.
  static DepthGrid of(const RangeScan& scan, const RangeSensorConfig& config);
  double deg_per_col() const { return fov_h_deg / cols; }
  double deg_per_row() const { return fov_v_deg / rows; }
  /// The coarser of the two pitches, radians: one pixel spans range * pixel_rad() metres.
  double pixel_rad() const;
  /// Continuous pixel coordinates (integers at pixel centres) of a direction
  /// in the sensor frame (x forward, y left, z up); it may lie outside the image.
  Eigen::Vector2d project(const Eigen::Vector3d& direction_sensor) const;
  /// Unit direction, sensor frame, through continuous pixel coordinates.
  Eigen::Vector3d direction(const Eigen::Vector2d& pixel) const;
};

// ---------------------------------------------------------------- DilataMappa

enum class StructuringShape { square, disc };

/// DilataMappa parameters (000 Algorithm 1).
struct DilationParams {
  StructuringShape shape = StructuringShape::square;
  /// Radius in pixels (across, down) of the structuring element of layer s
  /// at index s - 1; n = size() layers.
  std::vector<cv::Size> layer_radius_px;
  /// Upper bounds of the layers' values, increasing, the last 1: layer s holds
  /// the values in (upper[s - 2], upper[s - 1]]. Empty: n equal layers, s / n.
  std::vector<double> layer_upper;
};

/// Layer radii of Algorithm 1 as printed: layer s of n gets r s / n (rounded),
/// so the farthest layer is dilated most.
std::vector<cv::Size> printed_layer_radii(int layers, double max_radius_x_px, double max_radius_y_px);
/// Layer radii that keep at least `margin_m` around every obstacle: layer s
/// spans the angle of the margin seen from the layer's nearest depth
/// (s - 1) / n d_max, rounded up to whole pixels (at most the image's size),
/// so near layers are dilated most, as 000 §4.2.1 asks.
std::vector<cv::Size> margin_layer_radii(int layers, double margin_m, const DepthGrid& grid);
/// Radius in pixels that keeps `margin_m` around an obstacle pixel at depth
/// `depth_m`, errors of a coarse pixel included: ceil(asin(margin / d) /
/// deg_per_px + 1/2), at most `size` (the whole image once d <= margin).
/// asin, not atan: a ray at angle a from a point at range d passes d sin a
/// from it. The edge of an obstacle lies anywhere between the last pixel
/// centre that hit it and the next one (up to a pixel), and a direction
/// read from a free pixel anywhere in that pixel's footprint (up to half a
/// pixel from its centre): k pixels of dilation leave every direction of the
/// first free pixel's footprint at least k - 1/2 pixels from the edge.
int margin_radius_px(double margin_m, double depth_m, double deg_per_px, int size);
/// Layers that grow every obstacle pixel by margin_radius_px at that pixel's
/// own depth: one layer per depth interval over which the radius (across or
/// down) is constant, so there are as many layers as distinct radii and none
/// dilates more than its nearest pixel needs. Every direction within the
/// footprint of a free pixel then passes at least `margin_m` from every
/// obstacle the scan hit (to first order in the pixel's angle: the edge's own
/// depth is taken as that of the pixel that hit it).
DilationParams margin_layers(double margin_m, const DepthGrid& grid, StructuringShape shape = StructuringShape::square);

/// DilataMappa: layer s holds the pixels with value in ((s-1)/n, s/n], or
/// between its params.layer_upper bounds (layer 1 also those at 0, nearer
/// than d_min); each layer is dilated with its
/// structuring element (a square of side 2r+1 or a disc of radius r) and
/// nearer layers overwrite farther ones. No-return pixels (1) are free space,
/// not obstacles. Inside a layer the nearest value wins where dilated pixels
/// overlap, so the result never reports an obstacle farther than it is.
/// Equivalently: each pixel takes the smallest value among the obstacle
/// pixels whose element covers it, or 1 when none does.
cv::Mat dilate_depth_map(const cv::Mat& depth, const DilationParams& params);

/// Minimum filter, in place, of a row-major `rows` x `cols` float image with
/// a (2 rx + 1) x (2 ry + 1) rectangle, nothing beyond the border (as
/// cv::erode with a constant border above every value). Vector minima, in
/// passes over whole rows: the step of DilataMappa's chain of layers.
void erode_rect(std::vector<float>& image, int rows, int cols, int rx, int ry);
/// The same on the pixels that can change when those outside `box` are all
/// above every value (empty): only `box` grown by the radii is computed, and
/// returned; `scratch` (the image's size, empty outside `box` too; or no
/// size at all, filled with empty pixels here when a step needs it) may be
/// swapped with `image`, and both stay empty outside the returned box.
cv::Rect erode_rect(std::vector<float>& image, std::vector<float>& scratch, int rows, int cols, cv::Rect box, int rx,
                    int ry);

// ------------------------------------------------------- ControllaVisibilita

enum class Visibility { visible, invisible, unreachable };
std::string_view to_string(Visibility visibility);

struct VisibilityCheck {
  Visibility visibility = Visibility::invisible;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  ///< W', continuous (may be outside the image)
  double radius_x_px = 0.0;      ///< projected safety sphere, pixels across
  double radius_y_px = 0.0;      ///< and down
  double waypoint_range_m = 0.0; ///< rho_W
  double obstacle_range_m = 0.0; ///< m: the nearest value in the neighbourhood, metres (d_max when empty)
  bool in_view = true;           ///< the neighbourhood overlaps the image
};

/// ControllaVisibilita (000 Algorithm 2) on a dilated map, for a waypoint at
/// `waypoint_sensor` in the sensor frame with safety radius r: the
/// neighbourhood is the projection of the sphere of radius r around W (an
/// ellipse of angular radius asin(r / rho_W)), clipped to the image: every
/// pixel whose footprint (the square of one pixel around its centre) meets
/// it, so a direction anywhere in the ellipse is read; m is its smallest
/// value times d_max. Visible when m = d_max or the obstacle lies beyond W by
/// more than r (m - rho_W > r: Algorithm 2 prints rho_W - m, which would call
/// every occluded waypoint visible); Unreachable when |rho_W - m| < r; else
/// Invisible. The dilation grows obstacles across the line of sight only;
/// with `depth_margin_m` (the dilation's margin) W must also keep R = r +
/// depth_margin_m from what lies behind it: m - rho_W > R, else Unreachable;
/// when `depth` (the map before dilation) is given, m within r in front of W
/// to R beyond it is judged on what the scan hit instead: Visible when
/// nearest_hit_m(depth, W, R) >= R, else Unreachable (a dilated obstacle
/// there may lie beside W, not behind it). depth_margin_m 0: Algorithm 2.
/// A waypoint within r of the sensor is
/// Visible; one whose neighbourhood lies wholly outside the image is Invisible.
/// `extra_px` widens the neighbourhood by that many pixels (0: Algorithm 2;
/// negative narrows it, down to the pixels whose footprint holds W').
VisibilityCheck check_visibility(const cv::Mat& dilated, const DepthGrid& grid,
                                 const Eigen::Vector3d& waypoint_sensor, double safety_radius_m,
                                 double extra_px = 0.0, double depth_margin_m = 0.0, const cv::Mat* depth = nullptr);

/// Distance from `point` (sensor frame) to the nearest point the scan hit
/// within `radius_m` of it, less half a pixel's diagonal at the hit's range
/// (the surface a pixel stands for spans its footprint): the pixels of
/// `depth` (before dilation) whose footprint meets the cone of angular radius
/// asin(radius / |point|) around it, one pixel wider for the edges between
/// rays. +infinity when none is nearer than radius_m.
double nearest_hit_m(const cv::Mat& depth, const DepthGrid& grid, const Eigen::Vector3d& point, double radius_m);

/// The smallest value of `image` over the pixels whose footprint holds the
/// projection of direction `d` (sensor frame; grid.project, two pixels or
/// four on a boundary), none when it lies outside the image. Mostly without
/// project's double atan2: in float, unless the float angles lie within
/// 1e-5 rad of a pixel boundary (their error is under 1e-6 rad).
std::optional<float> value_at_direction(const cv::Mat& image, const DepthGrid& grid, const Eigen::Vector3d& d);

/// Whether the straight segment from `from_sensor` to `to_sensor` (sensor
/// frame) keeps `depth_margin_m` from everything on the dilated map: every
/// point P of it at least `min_range_m` from the sensor is in view and the
/// pixels whose footprint holds P' read nothing nearer than |P| +
/// depth_margin_m, or nothing nearer than |P| and, when `depth` (the map
/// before dilation) is given, no hit within depth_margin_m of P
/// (nearest_hit_m). The dilation keeps its margin across the line of sight,
/// this toward the sensor, so the segment's points keep the margin from every
/// obstacle the scan hit (the whole swept corridor, not only its end). Points
/// nearer than min_range_m are not judged (the image cannot: the caller
/// vouches for them); a segment wholly nearer is clear. Points are taken at
/// most half a pixel apart as seen from the sensor.
bool segment_clear(const cv::Mat& dilated, const DepthGrid& grid, const Eigen::Vector3d& from_sensor,
                   const Eigen::Vector3d& to_sensor, double depth_margin_m, double min_range_m,
                   const cv::Mat* depth = nullptr);

/// Where ControllaAltitudine takes a vehicle at `from` before it turns
/// toward `to` (any frame; `up` the unit vertical in it): the least vertical
/// move that brings `to` within max_elevation_deg of the horizontal, none
/// when it is within that plus tolerance_m already.
Eigen::Vector3d after_altitude_check(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& up,
                                     double max_elevation_deg, double tolerance_m);

/// Length of the start of a leg that, once the vehicle faces along it, may
/// pass within `margin_m` of something the sensor cannot see: an obstacle out
/// of a field of view of half-angle `half_fov_deg` (the narrower of the two)
/// from a sensor `mount_ahead_m` ahead of the vehicle's centre is within
/// margin_m of the leg only along its first mount_ahead_m + margin_m /
/// sin(half_fov) metres.
double blind_leg_m(double margin_m, double half_fov_deg, double mount_ahead_m);

// ------------------------------------------------------------------ TrovaWP

struct FindWaypointParams {
  double altitude_penalty = 1.0;    ///< k in c(P) = ||W' - P|| + k |y_W' - y_P|, >= 0
  double threshold_cap = 0.9;       ///< t = min((d_W + d_B) / 2, cap)
  double vehicle_radius_m = 0.45;   ///< added to the obstacle-edge distance
  double safety_radius_m = 0.5;     ///< kept free around the new waypoint
  double min_distance_m = 0.5;      ///< nearer waypoints are not worth flying to
  int max_candidates = 64;          ///< candidates tried, cheapest first, before giving up
  /// Kept toward the sensor as well as across (check_visibility's
  /// depth_margin_m): a new waypoint lies at least r + this in front of
  /// anything behind it, and its corridor this far from everything (0: off).
  double depth_margin_m = 0.0;
  /// Length of the start of the next leg, from the new waypoint toward the
  /// target, that must be clear on this map (segment_clear): what the vehicle
  /// will not see once it turns there (blind_leg_m). 0: not checked.
  double next_leg_check_m = 0.0;
  /// ControllaAltitudine's limit (after_altitude_check): the vertical moves
  /// it makes before the flight to the new waypoint and before the next leg
  /// are part of the corridor checked. 0: not modelled.
  double max_elevation_deg = 0.0;
  double altitude_tolerance_m = 0.1;
};

struct FoundWaypoint {
  Eigen::Vector2i pixel;            ///< P-bar, the chosen pixel
  Eigen::Vector2i edge_pixel;       ///< first pixel below t from P-bar toward W'
  Eigen::Vector2i waypoint_pixel;   ///< where the waypoint is: P-bar moved away from the edge until its sphere is clear
  double edge_range_m = 0.0;        ///< d_dB: range of the obstacle edge
  double range_m = 0.0;             ///< distance of the new waypoint from the sensor
  Eigen::Vector3d direction_sensor; ///< unit, sensor frame
  int tried = 0;                    ///< candidates examined before this one succeeded
};

struct WaypointSearch {
  double threshold = 0.0;           ///< t
  int candidates = 0;               ///< pixels at distance 1 from the obstacle
  std::optional<FoundWaypoint> found;
};

/// The binary map of TrovaWP: 255 where the dilated map is above t (free), 0 elsewhere.
cv::Mat threshold_free(const cv::Mat& dilated, double threshold);

/// The free pixels (non-zero) of a binary map (CV_8U) that share a side
/// with an obstacle pixel (0) of the map, row by row: those at distance 1
/// in its L1 distance transform (cv::distanceTransform, DIST_L1), without
/// the transform (outside the image is not an obstacle).
std::vector<Eigen::Vector2i> obstacle_border(const cv::Mat& free);

/// TrovaWP (000 §4.4): threshold the dilated map at t; L1 distance transform;
/// among the free pixels next to the obstacle (distance 1) take the one
/// minimising c(P); its distance is the first value below t scanning from P
/// toward W' (the obstacle edge; d_B when the scan meets none) plus the
/// vehicle radius. Reachability, from the neighbourhood of P: the waypoint's
/// direction moves from P away from the edge until the projection of its
/// safety sphere holds nothing nearer than the waypoint plus the safety
/// radius (else the distance shrinks until it does, clear_range), so it
/// passes ControllaVisibilita on this map. A candidate that cannot beyond
/// min_distance_m is skipped for the next cheapest.
/// `target_range_norm` is d_W (may exceed 1), `obstacle_range_norm` d_B.
/// Candidates whose waypoint would lie within the safety radius of a point of
/// `avoid_sensor` (sensor frame: waypoints already discarded) are skipped, so
/// a deterministic world cannot make the planner propose the same one forever.
/// With params.depth_margin_m, a waypoint is taken only when the segment
/// from `origin_sensor` (the vehicle's centre, sensor frame) to it is clear
/// (segment_clear, judged from depth_margin_m of the sensor on) and, with
/// params.next_leg_check_m, so is the start of the leg from it toward the
/// target (the target at target_range_norm d_max through target_pixel); with
/// `depth` (the map before dilation) refines the margin's checks (check_visibility).
/// With params.max_elevation_deg, the vertical moves of ControllaAltitudine at
/// either end (`up_sensor`: the vertical in the sensor frame) are checked as
/// segments too, and a move the sensor cannot see is not taken.
WaypointSearch find_waypoint(const cv::Mat& dilated, const DepthGrid& grid,
                             const Eigen::Vector2d& target_pixel, double target_range_norm,
                             double obstacle_range_norm, const FindWaypointParams& params,
                             std::span<const Eigen::Vector3d> avoid_sensor = {},
                             const Eigen::Vector3d& origin_sensor = Eigen::Vector3d::Zero(),
                             const Eigen::Vector3d& up_sensor = Eigen::Vector3d::UnitZ(),
                             const cv::Mat* depth = nullptr);

/// Pixels of the segment from `from` to `to` (both clipped to the image), in order.
std::vector<Eigen::Vector2i> pixel_segment(const cv::Size& size, const Eigen::Vector2i& from,
                                           const Eigen::Vector2d& to);

// ---------------------------------------------------------- Wall following

/// The farthest range, at most max_range_m and at least min_range_m, at which
/// a waypoint in the direction of `pixel` passes ControllaVisibilita on
/// `dilated` (nothing nearer than the range plus the safety radius plus
/// depth_margin_m in its sphere's projection, widened by extra_px pixels);
/// nullopt when there is none.
std::optional<double> clear_range(const cv::Mat& dilated, const DepthGrid& grid, const Eigen::Vector2d& pixel,
                                  double max_range_m, double safety_radius_m, double min_range_m,
                                  double extra_px = 0.0, double depth_margin_m = 0.0, const cv::Mat* depth = nullptr);

/// Distance from `point` (sensor frame) to the nearest point the scan hit
/// within `radius_m` of it, less half a pixel's diagonal at the hit's range
/// (the surface a pixel stands for spans its footprint): the pixels of
/// `depth` (before dilation) whose footprint meets the cone of angular radius
/// asin(radius / |point|) around it, one pixel wider for the edges between
/// rays. +infinity when none is nearer than radius_m.
double nearest_hit_m(const cv::Mat& depth, const DepthGrid& grid, const Eigen::Vector3d& point, double radius_m);

/// Fraction of the pixels of `region` (clipped to the image) whose dilated
/// value is above `free_value`: the wall-following measure of free space.
double free_fraction(const cv::Mat& dilated, const cv::Rect& region, double free_value);

/// The band wall following looks at: columns within +-sector_deg/2 of the
/// centre, rows within +-band_deg of the horizon row of the sensor.
cv::Rect navigable_region(const DepthGrid& grid, double sector_deg, double band_deg);

}  // namespace campo
