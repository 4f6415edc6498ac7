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

#include "campo/lidar_config.hpp"

namespace campo {

/// The angular grid of a depth map: pixel centres equiangular in azimuth and
/// elevation (LidarConfig's convention), ranges up to max_range_m.
struct DepthGrid {
  int cols = 0;
  int rows = 0;
  double fov_h_deg = 90.0;
  double fov_v_deg = 90.0;
  double max_range_m = 10.0;

  static DepthGrid of(const LidarConfig& config);
  double deg_per_col() const { return fov_h_deg / cols; }
  double deg_per_row() const { return fov_v_deg / rows; }
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
/// Layers that grow every obstacle pixel by the angle `margin_m` spans at
/// that pixel's own depth d, atan(margin / d), rounded up to whole pixels
/// (at most the image's size): one layer per depth interval over which the
/// rounded radius (across or down) is constant, so there are as many layers
/// as distinct radii and none dilates more than its nearest pixel needs.
/// The edge of an obstacle lies between the last pixel centre that hit it and
/// the next, so a free pixel centre is at least the margin from it.
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
/// ellipse of angular radius asin(r / rho_W)), clipped to the image; m is its
/// smallest value times d_max. Visible when m = d_max or the obstacle lies
/// beyond W by more than r (m - rho_W > r: Algorithm 2 prints rho_W - m,
/// which would call every occluded waypoint visible); Unreachable when
/// |rho_W - m| < r; else Invisible. A waypoint within r of the sensor is
/// Visible; one whose neighbourhood lies wholly outside the image is Invisible.
/// `extra_px` widens the neighbourhood by that many pixels (0: Algorithm 2;
/// negative narrows it, down to the pixel holding W').
VisibilityCheck check_visibility(const cv::Mat& dilated, const DepthGrid& grid,
                                 const Eigen::Vector3d& waypoint_sensor, double safety_radius_m,
                                 double extra_px = 0.0);

// ------------------------------------------------------------------ TrovaWP

struct FindWaypointParams {
  double altitude_penalty = 1.0;    ///< k in c(P) = ||W' - P|| + k |y_W' - y_P|, >= 0
  double threshold_cap = 0.9;       ///< t = min((d_W + d_B) / 2, cap)
  double vehicle_radius_m = 0.45;   ///< added to the obstacle-edge distance
  double safety_radius_m = 0.5;     ///< kept free around the new waypoint
  double min_distance_m = 0.5;      ///< nearer waypoints are not worth flying to
  int max_candidates = 64;          ///< candidates tried, cheapest first, before giving up
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
WaypointSearch find_waypoint(const cv::Mat& dilated, const DepthGrid& grid,
                             const Eigen::Vector2d& target_pixel, double target_range_norm,
                             double obstacle_range_norm, const FindWaypointParams& params,
                             std::span<const Eigen::Vector3d> avoid_sensor = {});

/// Pixels of the segment from `from` to `to` (both clipped to the image), in order.
std::vector<Eigen::Vector2i> pixel_segment(const cv::Size& size, const Eigen::Vector2i& from,
                                           const Eigen::Vector2d& to);

// ---------------------------------------------------------- Wall following

/// The farthest range, at most max_range_m and at least min_range_m, at which
/// a waypoint in the direction of `pixel` passes ControllaVisibilita on
/// `dilated` (nothing nearer than the range plus the safety radius in its
/// sphere's projection, widened by extra_px pixels); nullopt when there is none.
std::optional<double> clear_range(const cv::Mat& dilated, const DepthGrid& grid, const Eigen::Vector2d& pixel,
                                  double max_range_m, double safety_radius_m, double min_range_m,
                                  double extra_px = 0.0);

/// Fraction of the pixels of `region` (clipped to the image) whose dilated
/// value is above `free_value`: the wall-following measure of free space.
double free_fraction(const cv::Mat& dilated, const cv::Rect& region, double free_value);

/// The band wall following looks at: columns within +-sector_deg/2 of the
/// centre, rows within +-band_deg of the horizon row of the sensor.
cv::Rect navigable_region(const DepthGrid& grid, double sector_deg, double band_deg);

}  // namespace campo
