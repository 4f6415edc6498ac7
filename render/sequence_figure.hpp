#pragma once
/// The map of one run at several instants, panel by panel.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"

namespace campo {

/// One panel of a sequence figure: the run as it was at `time_s`.
struct SequencePanel {
  double time_s = 0.0;
  std::string caption;                    ///< the panel's title, e.g. "(a) 6.0 s: gap on the right"
  std::optional<double> heading_deg;      ///< world heading to draw as an arrow from the vehicle (a chosen gap)
};

/// The map of one run at several instants (seed 003 Fig. 46), two panels a
/// row, all on one frame (the track between the first and the last instant,
/// the movers there then, plus style.margin_m): in each, the track up to that
/// instant, every mover where it was then (its path dashed), the vehicle's
/// footprint (`footprint_m`, length x width, about its track point) at its
/// recorded heading and, when given, an arrow along heading_deg.
/// std::invalid_argument when `panels` is empty or the run has no track.
figure::Canvas draw_sequence(const Scene& scene, const RunView& run, const std::vector<SequencePanel>& panels,
                             const Eigen::Vector2d& footprint_m, const FigureStyle& style = {});

}  // namespace campo
