#pragma once
/// `depth_reactive`: seed 000's mapless reactive navigation for the
/// quadrotor (000 §4, SPEC §7.1). NavigazioneLocale keeps a stack of the
/// target and at most one temporary waypoint; before each decision the
/// drone adjusts its altitude (ControllaAltitudine), turns toward the
/// waypoint (ControllaRotazione) and hovers still; then it dilates the latest
/// depth map (DilataMappa) and classifies the waypoint (ControllaVisibilita):
/// Visible -> fly to it, stopping if it becomes occluded; Invisible target ->
/// a temporary waypoint beside the obstacle (TrovaWP), or wall following when
/// there is none; Invisible or Unreachable temporary waypoint -> discarded;
/// Unreachable target -> the run ends with a reason. The steps are the pure
/// functions of depth_reactive_steps.hpp.
#include <cstdint>
#include <memory>
#include <string>

#include "campo/config_fields.hpp"
#include "campo/planner.hpp"
#include "campo/planner_record.hpp"
#include "campo/record_fields.hpp"
#include "planners/depth_reactive_steps.hpp"

namespace campo {

/// How DilataMappa's structuring element shrinks over the layers
/// (depth_reactive_steps.hpp): keeping a metric margin (the default), or
/// Algorithm 1 as printed (r s / n), which dilates the nearest obstacles least.
enum class LayerRadii { margin, as_printed };

struct DepthReactiveConfig {
  std::string sensor;                 ///< alias of the depth source; empty: the vehicle's first grid sensor
  double speed_mps = 0.6;             ///< cruise speed (seed 000 flew at 0.6 m/s)
  double tolerance_m = 0.3;           ///< a waypoint counts as reached within this distance
  double safety_radius_m = 0.25;      ///< r of ControllaVisibilita: kept free around every waypoint, beyond the dilation margin
  double vehicle_radius_m = 0.45;     ///< added to the obstacle-edge distance in TrovaWP
  int layers = 18;                    ///< n of DilataMappa (0.56 m deep each over 10 m)
  StructuringShape structuring_element = StructuringShape::square;
  LayerRadii layer_radii = LayerRadii::margin;
  /// Margin kept around obstacles (layer_radii margin), so that the drone
  /// flies as a point: the bounding radius of the quadrotor's collision box
  /// (0.6 x 0.6 x 0.12 m: half-diagonal 0.43 m) plus 0.07 m for tracking
  /// error; rounding the dilation up to whole pixels adds up to a pixel more.
  double dilation_margin_m = 0.5;
  /// Keep the margin toward the sensor too, not only across the line of
  /// sight (docs/planners.md, "Safety at coarse resolutions"): an obstacle
  /// must lie beyond a waypoint by r + dilation_margin_m for it to be
  /// visible, TrovaWP's waypoints keep that distance, their corridor from the
  /// vehicle and the start of the next leg (what the vehicle will not see
  /// once it turns there) keep the margin. false: Algorithm 2 and TrovaWP as
  /// printed (obstacles beyond a waypoint by r suffice).
  bool margin_in_depth = true;
  double dilation_radius_deg = 17.2;  ///< r as an angle (layer_radii as_printed; seed 000: 49 px at 256 px over 90 deg)
  double altitude_penalty = 1.0;      ///< k of TrovaWP's cost, per pixel of altitude change
  double threshold_cap = 0.9;         ///< cap of TrovaWP's threshold t
  double min_waypoint_distance_m = 0.5;  ///< TrovaWP skips nearer waypoints
  int max_candidates = 64;            ///< TrovaWP candidates tried before wall following
  double yaw_tolerance_deg = 3.0;     ///< ControllaRotazione: aligned within this
  double max_elevation_deg = 20.0;    ///< ControllaAltitudine: change altitude until the waypoint is within this elevation
  double monitor_min_range_m = 1.0;   ///< VaiVerso stops checking occlusion this close to the waypoint
  /// Hysteresis of ControllaVisibilita: the target is flown to only when also
  /// visible with its neighbourhood this many pixels wider, and VaiVerso's
  /// check on the way uses a neighbourhood this many pixels narrower, so a
  /// flight does not stop as soon as the drone pitches forward and the image shifts.
  double visible_margin_px = 1.5;
  double wall_scan_deg = 60.0;        ///< wall following: look this far either side of the goal (000 §4.4.3)
  double wall_turn_step_deg = 20.0;   ///< then turn toward the freer side in these steps
  double wall_sector_deg = 60.0;      ///< width of the navigable sector that must be free
  double wall_band_deg = 10.0;        ///< rows within this elevation of the horizon are looked at
  double wall_free_fraction = 0.8;    ///< fraction of the sector that must be free
  double wall_step_m = 3.0;           ///< distance of a wall-following waypoint
  int max_replans = 1000;             ///< give up after this many replanning steps
};

std::unique_ptr<Planner> make_depth_reactive_planner(const ParamsBlock& params, const PlannerContext& context);

/// The fields of `params` (keys as DepthReactiveConfig's members); parameters() writes them back.
const ConfigFields<DepthReactiveConfig>& depth_reactive_config_fields();

/// The configuration of `params` (keys as DepthReactiveConfig's fields;
/// structuring_element "square" | "disc", layer_radii "margin" |
/// "as_printed"); InputError naming the file and JSON pointer otherwise.
DepthReactiveConfig parse_depth_reactive_config(const ParamsBlock& params);

/// DilataMappa's parameters for a sensor grid.
DilationParams dilation_params(const DepthReactiveConfig& config, const DepthGrid& grid);
/// TrovaWP's parameters.
FindWaypointParams find_waypoint_params(const DepthReactiveConfig& config);

/// What depth_reactive records beyond the generic decisions (docs/planners.md),
/// declared once: the description registered with it (with the overlays of
/// its replanning figures) and its typed fields.
struct DepthReactiveRecord {
  PlannerRecord description;
  /// A wall-following step: {offset_deg, free_fraction, side, waypoint}.
  RecordField<nlohmann::json> wall_following;
  // A replanning step's details.
  RecordField<double> scan_time_s;
  RecordField<nlohmann::json> waypoint;
  RecordField<std::string> role;
  RecordField<std::string> visibility;
  RecordField<nlohmann::json> pixel;
  RecordField<nlohmann::json> radius_px;
  RecordField<double> waypoint_range_m;
  RecordField<double> obstacle_range_m;
  RecordField<bool> marginal;
  RecordField<double> search_ms;
  RecordField<double> threshold;
  RecordField<std::int64_t> candidates;
  RecordField<nlohmann::json> chosen_pixel;
  RecordField<nlohmann::json> edge_pixel;
  RecordField<nlohmann::json> waypoint_pixel;
  RecordField<double> edge_range_m;
  RecordField<double> new_waypoint_range_m;
  RecordField<std::int64_t> tried;
  RecordField<std::string> action;
  RecordField<double> dilation_ms;

  DepthReactiveRecord();
};
const DepthReactiveRecord& depth_reactive_record();

}  // namespace campo
