#pragma once
/// Writing the figures of recorded runs (shared by `campo run` and `campo render`).
#include <filesystem>
#include <string>
#include <vector>

#include "render/run_files.hpp"

namespace campo::cli {

/// Figure kinds of one run.
inline const std::vector<std::string> kRunFigureKinds{"map", "side", "depth", "snapshot"};

/// Draws figure `kind` ("map", "side", "depth", "snapshot") of a run into
/// out_dir; returns the files written.
std::vector<std::filesystem::path> write_figure(const RecordedRun& run, const std::string& kind,
                                                const std::filesystem::path& out_dir);

/// Several runs on one map, written to out_dir/overlay.png.
std::filesystem::path write_overlay(const std::vector<RecordedRun>& runs, const std::filesystem::path& out_dir);

}  // namespace campo::cli
