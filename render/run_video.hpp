#pragma once
/// Videos of recorded runs (`campo render --kind video`): the frames of
/// render/video_frame.hpp filled from a run's files, encoded with ffmpeg.
#include <cstddef>
#include <filesystem>
#include <functional>

#include <opencv2/core.hpp>

#include "render/run_files.hpp"

namespace campo {

struct VideoOptions {
  double fps = 25.0;               ///< frames per second of the video, [1, 60]
  double speed = 1.0;              ///< simulated seconds per second of video, [0.05, 100]
  cv::Size frame_px{1600, 900};    ///< even sides, at least 480 x 270
  std::size_t max_frames = 60000;  ///< longer videos are refused (raise --speed)
  std::size_t max_gif_frames = 3000;       ///< a GIF's frames (2 min at 25 fps): longer ones are refused
  std::size_t max_track_samples = 20000;   ///< a longer track is thinned evenly for drawing (each frame draws it)
  std::size_t max_runs = 16;               ///< runs made into videos by one command; more are refused
};

/// InputError ("command line", "runs") when `runs` is more than one command makes videos of.
void check_video_runs(std::size_t runs, const VideoOptions& options);

/// Writes the video of `run` to `out` (.mp4: H.264; .gif), from the recorded
/// files alone: frame k shows the run at k * speed / fps simulated seconds,
/// the last frame its end, held for a second. The sensor panel is the depth
/// map of the latest replanning with the planner's overlays
/// (depth_reactive), else the latest depth map or planar scan recorded with
/// `campo run --record-depth N` (a planar scan drawn around the vehicle with
/// follow-the-gap's choice), else the planner's gap decisions alone.
/// `progress(done, total)` is called after each frame. InputError for a bad
/// run directory or options; std::runtime_error when ffmpeg fails.
void write_video(const RecordedRun& run, const VideoOptions& options, const std::filesystem::path& out,
                 const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace campo
