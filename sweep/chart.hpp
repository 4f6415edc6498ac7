#pragma once
/// Charts of sweep results (SPEC §9), drawn on a figure::Canvas (PNG, PDF or
/// SVG from one drawing), the same bytes for the same results. The summary chart of `campo table`: two panels,
/// normalized path length (mean and its 95 % confidence interval, the one
/// `campo plot` and the tables give: mean_interval95, on the log scale as the
/// ratio is >= 0) and success rate (%, with its Wilson interval) against one
/// numeric axis, one coloured series per scene (the path length over the runs
/// that reached their goal only); the legend names both intervals. The plots of
/// `campo plot`: any metric against any field, as lines or box plots.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/figure_canvas.hpp"
#include "sweep/results.hpp"

namespace campo {

/// Whether the table can be charted: exactly one axis, all its values numbers.
bool chartable(const SweepTable& table);

/// The chart of a chartable table. The x axis is log2 when every value
/// is a positive power of two (resolutions), else linear; it is ticked at the
/// swept values. The same table gives the same drawing.
figure::Canvas draw_sweep_chart(const SweepTable& table);

enum class PlotKind {
  automatic,  ///< line when every x value is a number, else box
  line,       ///< x numeric (log2 when all are powers of two): mean and 95 % interval per x (mean_interval95 with
              ///< metric_support, named in the legend), lines through the means
  box,        ///< x as categories: median, quartiles, whiskers at 1.5 IQR, outliers (rates: the rate and its interval)
};

/// What `campo plot` draws: metric `y` against field `x`.
struct PlotRequest {
  std::string x;       ///< a field (check_field): "scene", "planner", "seed" or an axis
  std::string y;       ///< a metric (check_metric), "success" for the success rate, "path_ratio@reached" over successes
  std::string group;   ///< a field other than x: one coloured series per value; empty: one series
  PlotKind kind = PlotKind::automatic;
  std::string title;    ///< empty: "<sweep>: <metric heading> vs <x>"
  std::string x_label;  ///< empty: field_heading(x), with its unit, and ", log2 scale" when it is
  std::string y_label;  ///< empty: metric_heading(y), with its unit
};

/// Size of a plot; the fonts suit it (a figure for a paper).
struct PlotConfig {
  int width_px = 1600;   ///< >= 800
  int height_px = 1000;  ///< >= 500
};

/// A plot built a run at a time: memory per point or box, not per run
/// (RunningStats; a QuantileSketch per box, exact up to its kExactValues values).
class PlotBuilder {
 public:
  /// `layout` must outlive this (with axes_from_runs its axes may grow until
  /// draw()). Checks the request's fields when the axes are known (InputError).
  PlotBuilder(const TableLayout& layout, PlotRequest request);
  ~PlotBuilder();
  PlotBuilder(PlotBuilder&&) noexcept;
  PlotBuilder& operator=(PlotBuilder&&) noexcept;
  /// `index`: the run's place in order of first appearance (for_each_result).
  void add(const RunResult& run, std::size_t index);
  /// The plot of the runs added. Checks the request first: InputError
  /// naming the option (--x, --y, --group, --kind) and what was expected.
  figure::Canvas draw(const PlotConfig& config = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The plot of `runs` (PlotBuilder).
figure::Canvas draw_sweep_plot(const std::vector<RunResult>& runs, const TableLayout& layout, const PlotRequest& request,
                              const PlotConfig& config = {});

}  // namespace campo
