#pragma once
/// The sweep chart (SPEC §9): how a planner degrades along one numeric
/// parameter. Two panels, normalized path length (mean with ± sd error bars)
/// and success rate (%), one coloured series per scene.
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "sweep/results.hpp"

namespace campo {

/// Whether the table can be charted: exactly one axis, all its values numbers.
bool chartable(const SweepTable& table);

/// The chart of a chartable table (BGR). The x axis is log2 when every value
/// is a positive power of two (resolutions), else linear; it is ticked at the
/// swept values. The same table gives the same pixels.
cv::Mat draw_sweep_chart(const SweepTable& table);

/// Draws the chart and writes it as PNG.
void write_sweep_chart(const SweepTable& table, const std::filesystem::path& png);

}  // namespace campo
