#pragma once
/// Writing the figures of recorded runs (shared by `campo run` and `campo render`).
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "render/figure_canvas.hpp"
#include "render/run_files.hpp"

namespace campo {

/// The formats a command writes its figures in (--figure-format); PNG alone by default.
using FigureFormats = std::vector<figure::FigureFormat>;
inline const FigureFormats kPngOnly{figure::FigureFormat::png};

/// What `campo render --kind` draws, named on the command line as to_string
/// gives (one name table, in run_figures.cpp, for both directions).
enum class FigureKind { map, side, heightmap, depth, snapshot, overlay, sequence, video, replay };

/// Every figure kind, in the order --kind's help lists them.
inline constexpr std::array kFigureKinds{FigureKind::map,      FigureKind::side,    FigureKind::heightmap,
                                         FigureKind::depth,    FigureKind::snapshot, FigureKind::overlay,
                                         FigureKind::sequence, FigureKind::video,   FigureKind::replay};

/// The figure kinds of one run that write_figure draws.
inline constexpr std::array kRunFigureKinds{FigureKind::map, FigureKind::side, FigureKind::heightmap,
                                            FigureKind::depth, FigureKind::snapshot};

std::string_view to_string(FigureKind kind);
std::optional<FigureKind> figure_kind_from_string(std::string_view name);
/// The names of kFigureKinds, in its order (--kind's choices).
std::vector<std::string> figure_kind_names();

/// The figures a run directory gets when it is written (`campo run`, a sweep's
/// kept runs): the map and the side view, and what its planner's record adds.
std::vector<FigureKind> run_directory_figures(const RecordedRun& run);

/// Draws figure `kind` of a run (one of kRunFigureKinds) into out_dir, once
/// per format (map.png, map.pdf ...); returns the files written. A snapshot is
/// a rendered raster: its PDF and SVG embed the image. std::invalid_argument
/// for a kind that is not a figure of one run.
std::vector<std::filesystem::path> write_figure(const RecordedRun& run, FigureKind kind,
                                                const std::filesystem::path& out_dir,
                                                const FigureFormats& formats = kPngOnly);
/// One replanning step of a run (Decisions::replan, docs/planners.md) whose planner draws its steps
/// (PlannerRecord::replan_overlays: depth_reactive).
struct ReplanStep {
  double time_s = 0.0;                  ///< when the planner decided, simulated seconds
  ReplanDecision decision;              ///< the step as recorded (its index, sensor and the planner's details)
  std::filesystem::path depth_file;     ///< the depth map it read, replans/replan_KKKK.png
};

/// The replanning steps `indices` of a run, in the order given (every
/// recorded step when nullopt), checked before anything is drawn: the
/// recorded planner's description must draw replanning steps (depth_reactive)
/// and each step and its depth map must have been recorded; InputError naming
/// the file and what was expected otherwise.
std::vector<ReplanStep> find_replan_steps(const RecordedRun& run, const std::optional<std::vector<int>>& indices);

/// For each step, the depth map it read with the planner's overlays,
/// recomputed by the planner's code (PlannerRecord::replan_overlays) from the
/// recorded files alone (depth_reactive: DilataMappa with the recorded planner
/// parameters and sensor grid, TrovaWP's thresholded map, W' with its safety
/// ellipse, chosen pixel, scan line to the obstacle edge, new waypoint),
/// written to out_dir/depth_figures/replan_KKKK_grey.png and _colour.png;
/// returns the files written.
std::vector<std::filesystem::path> write_replan_figures(const RecordedRun& run, const std::vector<ReplanStep>& steps,
                                                        const std::filesystem::path& out_dir,
                                                        const FigureFormats& formats = kPngOnly);

/// The figure of one replanning step as write_replan_figures draws it (grey
/// or colour-mapped), for a video's sensor panel.
cv::Mat draw_replan_figure(const RecordedRun& run, const ReplanStep& step, bool colour);

/// The instants of a sequence figure picked from the planner's heading marks
/// (PlannerRecord::heading: rover_route's follow-the-gap decisions): (a) the
/// first mark on a side, (c) the first one on the other side of the route,
/// (b) half way between, (d) 2 s after that avoidance ended (or the last
/// mark); InputError when the choice never changed sides.
std::vector<double> gap_switch_instants(const RecordedRun& run);

/// The map of a run at `times_s` (2 x 2 for four; gap_switch_instants when
/// empty), each panel captioned with its letter, time and the planner's mark
/// then (the gap chosen, its heading an arrow), written to out_dir/sequence.png
/// (and .pdf, .svg as asked).
std::vector<std::filesystem::path> write_sequence(const RecordedRun& run, std::vector<double> times_s,
                                                  const std::filesystem::path& out_dir,
                                                  const FigureFormats& formats = kPngOnly);

/// Several runs on one map, written to out_dir/overlay.png (and .pdf, .svg as asked).
std::vector<std::filesystem::path> write_overlay(const std::vector<RecordedRun>& runs,
                                                 const std::filesystem::path& out_dir,
                                                 const FigureFormats& formats = kPngOnly);

}  // namespace campo
