#pragma once
/// Encoding frames into a video file with the ffmpeg program (Debian package
/// ffmpeg): H.264 MP4 or GIF, chosen by the file's extension. ffmpeg is a
/// separate process fed raw frames through a pipe, so campo links no codec
/// library and loads none until a video is asked for.
#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace campo {

enum class VideoFormat { mp4, gif };

/// The format a file name asks for (".mp4", ".gif", any case); nullopt otherwise.
std::optional<VideoFormat> video_format_of(const std::filesystem::path& file);

/// Streams frames to ffmpeg, which writes a temporary file beside `out` (the
/// target of `out` when it is a symbolic link; anything but a regular file is
/// refused); finish() moves it into place, so `out` is never half-written. The same
/// frames give the same bytes (bit-exact flags, no metadata, no timestamps).
class VideoEncoder {
 public:
  /// Starts ffmpeg for frames of `frame_px` (even width and height) at `fps`
  /// frames per second. std::runtime_error when ffmpeg cannot be started
  /// (naming the Debian package to install).
  VideoEncoder(const std::filesystem::path& out, VideoFormat format, cv::Size frame_px, double fps);
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;
  /// Stops ffmpeg and removes the temporary file unless finish() succeeded.
  ~VideoEncoder();

  /// Appends one frame (CV_8UC3 BGR of frame_px); OutputError naming the
  /// file with ffmpeg's last lines when it stopped (a full disk).
  void add(const cv::Mat& frame);
  /// Ends the stream, waits for ffmpeg and moves the file into place;
  /// OutputError naming the file with ffmpeg's last lines when it failed.
  void finish();

 private:
  [[noreturn]] void fail(const std::string& what);
  void stop();

  std::filesystem::path out_;
  std::filesystem::path partial_;  // ffmpeg's output until finish()
  int log_fd_ = -1;                 // ffmpeg's stderr, a file in memory (memfd)
  cv::Size frame_px_;
  int pipe_ = -1;                  // ffmpeg's stdin
  int pid_ = -1;
  bool done_ = false;
};

}  // namespace campo
