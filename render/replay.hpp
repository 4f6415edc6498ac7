#pragma once
/// A shareable 3D replay of recorded runs (`campo render --kind replay`): one
/// self-contained HTML file holding the viewer (web/replay, with three.js from
/// the npm registry, embedded in campo when it is built) and the runs' data, so
/// it opens offline in any browser.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/run_files.hpp"

namespace campo {

/// Limits that keep a replay file small enough to share, and the memory and
/// time of making it bounded whatever the runs recorded (docs/limits.md).
struct ReplayLimits {
  std::size_t max_runs = 64;                    ///< runs in one replay; more are refused
  std::size_t max_track_samples = 20000;        ///< per run; longer tracks are thinned evenly
  std::size_t max_total_track_samples = 200000; ///< over all runs: each run keeps at most this / runs
  std::size_t max_scans = 400;                  ///< per run; more recorded scans are thinned evenly
  std::size_t max_scan_points = 1500;           ///< per scan; more returns are thinned evenly
  std::size_t max_total_scan_points = 1000000;  ///< over all runs: each run keeps at most this / runs
  double mover_sample_s = 0.1;                  ///< movers' positions every this many simulated seconds...
  std::size_t max_mover_samples = 20000;        ///< ...or fewer, farther apart, over a long run
  std::size_t max_total_mover_samples = 200000; ///< over all movers: each keeps at most this / movers
  std::size_t max_terrain_vertices = 1000000;   ///< over all terrains: finer ones are resampled coarser
  std::size_t max_mesh_triangles = 250000;      ///< over all distinct meshes: larger ones are clustered coarser
  std::size_t max_page_bytes = 128u << 20;      ///< the page; larger is refused (the limits above keep it far below)
};

/// InputError ("command line", "runs") when `runs` is more than a replay shows.
void check_replay_runs(std::size_t runs, const ReplayLimits& limits = {});

/// The replay's data (web/replay/README.md's format, "campo_replay": 1): the
/// first run's scene (its static solids, planes, terrains and movers), and per
/// run its track with attitude, vehicle type, size and colour, and the LIDAR
/// or depth-camera returns recorded with `campo run --record-depth N` in the
/// world frame. InputError when a run has no track.
nlohmann::json replay_data(const std::vector<RecordedRun>& runs, const ReplayLimits& limits = {});
/// The same from run directories, loaded one at a time (load_run_dir): the
/// memory of the first run (its scene) and one other, not of every run.
nlohmann::json replay_data(const std::vector<std::filesystem::path>& dirs, const ReplayLimits& limits = {});

/// The HTML page: the viewer's template with three.js, its orbit controls, the
/// viewer's script and `data` inlined. std::runtime_error when this campo
/// was built without the viewer (web/replay/node_modules missing at build time).
/// InputError ("command line", "runs") when the page would be larger than `limits.max_page_bytes`.
std::string replay_html(const nlohmann::json& data, const ReplayLimits& limits = {});

}  // namespace campo
