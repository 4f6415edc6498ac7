#pragma once
/// A planner's description of its own record (docs/extending.md, "Declaring
/// a planner's record"): the fields it adds to the generic decisions, each
/// declared once (campo/record_fields.hpp), and the overlays its figures and
/// video panels draw, computed by the planner's code from what it recorded and
/// drawn by the figures as generic primitives. Registered with the planner
/// (PlannerRegistration::record, campo/plugin.hpp), so a figure drawn from a
/// run directory finds it by the recorded planner name (planner_record()).
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "campo/planner.hpp"
#include "campo/record_fields.hpp"

namespace campo {

/// A grid of square cells in the horizontal plane with a value per cell (a
/// reconstructed height map), drawn over the scene's map.
struct CellsOverlay {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< world x, y of the south-west corner of cell (0, 0), m
  double cell_size_m = 1.0;                             ///< side of a cell, m
  int columns = 0;                                      ///< cells along x (east)
  int rows = 0;                                         ///< cells along y (north)
  /// Row-major from the south-west corner; NaN where nothing was recorded.
  std::vector<double> values;
  std::string unit;  ///< of the values, e.g. "m"
  bool empty() const { return values.empty(); }
};

/// A mark a planner leaves at one instant of the run: a heading it steered
/// for (an arrow on the sequence figure and the video's scan panel) with its
/// caption. Marks of different `side` ("left", "right") mark where the
/// planner's choice changed sides: the sequence figure's default instants.
struct HeadingMark {
  /// World heading of the route the other angles are relative to, degrees counter-clockwise from x (east).
  double reference_deg = 0.0;
  std::optional<double> nearest_m{};   ///< the nearest reading of the scan, m
  std::optional<double> heading_deg{};  ///< the heading steered for, relative to reference_deg, positive left
  std::string side{};                   ///< which side the choice was on ("left", "right"), "" for none
  std::string caption{};                ///< e.g. "gap on the left, heading +12 deg (arrow)"
  std::string status{};                 ///< the panel's status line while avoiding, e.g. "avoiding: gap on the left"
};

/// An image a planner's replanning step read (a depth map, values in [0, 1])
/// with the sensor's angular grid, as run.json recorded it.
struct RecordedImage {
  int cols = 0;
  int rows = 0;
  double fov_h_deg = 0.0;
  double fov_v_deg = 0.0;
  double max_range_m = 0.0;
  std::vector<float> values{};  ///< row-major, cols * rows
};

/// What a replanning step's figure draws over the image it read: images of
/// the same size (side by side with it), points, a polyline, an ellipse.
struct ImageOverlays {
  std::vector<float> processed;              ///< the image as the planner processed it (e.g. dilated); empty: none
  std::vector<std::uint8_t> mask;            ///< a 0/255 mask (e.g. thresholded); empty: none
  std::optional<double> mask_threshold{};    ///< the value behind `mask`, for its caption
  std::optional<Eigen::Vector2i> chosen_px{};  ///< a pixel chosen (ringed)
  std::vector<Eigen::Vector2i> polyline_px;  ///< pixels considered (a scan line)
  std::optional<Eigen::Vector2d> target_px{};  ///< a projected target (continuous; may lie outside the image)
  Eigen::Vector2d ellipse_px = Eigen::Vector2d::Zero();  ///< half-axes around target_px; 0: not drawn
  std::optional<Eigen::Vector2i> placed_px{};  ///< where something was placed (a diamond)
};

/// A planner's decisions with the time it took them (events.jsonl, run/event_log.hpp).
struct PlannerEvent {
  double time_s = 0.0;
  Decisions decisions;

  bool operator==(const PlannerEvent&) const = default;
};

/// What a run recorded that a planner's own metrics are measured on (PlannerRecord::measure).
struct PlannerRun {
  std::span<const PlannerEvent> events;  ///< every decision, in order (as events.jsonl holds them)
  double end_time_s = 0.0;               ///< simulated time when the run ended (run.json's sim_time_s), s
};

/// A planner's description of its record.
struct PlannerRecord {
  /// The fields it adds to Decisions::own; none when empty.
  RecordFields decisions;
  /// The fields of its replanning steps' details (ReplanDecision::details).
  RecordFields replan;
  /// Its own metrics, if any, written by `measure` into run.json's metrics
  /// beside the generic ones and the mission's; a name that is one of theirs
  /// refuses the run before it starts (InputError naming the planner).
  RecordFields metrics;
  /// Measures its metrics at the end of a run from what the run recorded,
  /// writing each through its `metrics` declaration into `out` (an empty
  /// object). A key it writes that is not declared there, or not of its
  /// declared type, is an InputError naming the planner. Called only when
  /// `metrics` declares a field.
  std::function<void(const PlannerRun& run, nlohmann::json& out)> measure;

  /// Overlays, each optional. `cells`: folds one event's decisions into the
  /// grid (its first call sees an empty one); InputError (file "", the
  /// pointer of the offending field under "/decisions") on a malformed record.
  std::function<void(const Decisions& decisions, CellsOverlay& cells)> cells;
  /// The heading mark of one event's decisions, if it left one.
  std::function<std::optional<HeadingMark>(const Decisions& decisions)> heading;
  /// What a replanning step did, a few words, e.g. "new waypoint".
  std::function<std::string(const ReplanDecision& step)> replan_action;
  /// One line of what a replanning step saw and did, e.g. "target invisible -> new waypoint".
  std::function<std::string(const ReplanDecision& step)> replan_caption;
  /// The overlays of replanning `step` over the image it read, recomputed from
  /// the planner's recorded parameters (run.json's parameters.planner.parameters,
  /// at `file` and `pointer`); InputError on a malformed record.
  std::function<ImageOverlays(const ReplanDecision& step, const RecordedImage& image,
                              const nlohmann::json& parameters, const std::string& file, const std::string& pointer)>
      replan_overlays;
};

/// The record description of the planner `name` (a built-in planner's or a
/// loaded plugin's); null when it has none or is not known.
const PlannerRecord* planner_record(std::string_view name);

}  // namespace campo
