#include "render/video_encoder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/output_dir.hpp"

extern char** environ;

namespace campo {

namespace {

// The last lines of ffmpeg's stderr (the last 16 KiB of the in-memory log), for an error message.
std::string tail_of(int log_fd) {
  if (log_fd < 0) return "";
  const off_t size = ::lseek(log_fd, 0, SEEK_END);
  const off_t from = std::max<off_t>(0, size - (16 << 10));
  std::string text(static_cast<std::size_t>(std::max<off_t>(0, size - from)), '\0');
  const ssize_t n = ::pread(log_fd, text.data(), text.size(), from);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  std::string out;
  for (std::size_t i = lines.size() > 4 ? lines.size() - 4 : 0; i < lines.size(); ++i) out += "\n  " + lines[i];
  return out;
}

// ffmpeg's arguments: raw BGR frames on stdin, bit-exact output without metadata.
std::vector<std::string> ffmpeg_arguments(VideoFormat format, cv::Size size, double fps,
                                          const std::filesystem::path& partial) {
  std::ostringstream rate, frame;
  rate.precision(17);
  rate << fps;
  frame << size.width << "x" << size.height;
  std::vector<std::string> args{"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
                                "-f", "rawvideo", "-pix_fmt", "bgr24", "-s", frame.str(), "-r", rate.str(),
                                "-i", "pipe:0"};
  if (format == VideoFormat::mp4) {
    // yuv420p and faststart: plays in browsers, presentation software and phones.
    for (const char* a : {"-c:v", "libx264", "-preset", "veryfast", "-crf", "20", "-pix_fmt", "yuv420p", "-movflags",
                          "+faststart", "-f", "mp4"}) {
      args.emplace_back(a);
    }
  } else {
    // One palette for the whole animation, from what changes between frames.
    for (const char* a : {"-vf", "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer:bayer_scale=4",
                          "-f", "gif"}) {
      args.emplace_back(a);
    }
  }
  for (const char* a : {"-fflags", "+bitexact", "-flags:v", "+bitexact", "-map_metadata", "-1"}) args.emplace_back(a);
  args.push_back(partial.string());
  return args;
}

}  // namespace

std::optional<VideoFormat> video_format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".mp4") return VideoFormat::mp4;
  if (ext == ".gif") return VideoFormat::gif;
  return std::nullopt;
}

VideoEncoder::VideoEncoder(const std::filesystem::path& out, VideoFormat format, cv::Size frame_px, double fps)
    : out_(output_file_target(out)), frame_px_(frame_px) {
  if (frame_px.width <= 0 || frame_px.height <= 0 || frame_px.width % 2 || frame_px.height % 2) {
    throw std::invalid_argument("VideoEncoder: frame size must be even and positive");
  }
  if (!(fps > 0.0)) throw std::invalid_argument("VideoEncoder: fps must be positive");
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + string.
  std::string stem(".");
  stem += out_.filename().string();
  stem += '.';
  stem += std::to_string(::getpid());
  const std::filesystem::path dir = out_.has_parent_path() ? out_.parent_path() : std::filesystem::path(".");
  partial_ = dir / (stem + ".partial");
  // ffmpeg's stderr goes to memory, not beside the video: on a full disk its message is the one thing to keep.
  log_fd_ = ::memfd_create("campo-ffmpeg-log", MFD_CLOEXEC);
  if (log_fd_ < 0) throw std::runtime_error(std::string("cannot create ffmpeg's log: ") + std::strerror(errno));

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    const int errnum = errno;
    ::close(log_fd_);
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errnum));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log_fd_, STDERR_FILENO);
  const std::vector<std::string> args = ffmpeg_arguments(format, frame_px, fps, partial_);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  if (spawned != 0) {
    ::close(fds[1]);
    ::close(log_fd_);
    throw std::runtime_error("cannot start ffmpeg (" + std::string(std::strerror(spawned)) +
                             "); videos are encoded by the ffmpeg program: install the Debian package ffmpeg");
  }
  pid_ = pid;
  pipe_ = fds[1];
}

VideoEncoder::~VideoEncoder() {
  if (log_fd_ >= 0) ::close(log_fd_);
  if (done_) return;
  stop();
  std::error_code ignored;
  std::filesystem::remove(partial_, ignored);
}

void VideoEncoder::stop() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
  pid_ = -1;
}

void VideoEncoder::fail(const std::string& what) {
  const std::string tail = tail_of(log_fd_);
  stop();
  // What stops ffmpeg is almost always the place to write (a full disk, a folder gone): exit 2.
  throw OutputError(out_, "cannot write: ffmpeg " + what + tail);
}

void VideoEncoder::add(const cv::Mat& frame) {
  if (frame.type() != CV_8UC3 || frame.size() != frame_px_) {
    throw std::invalid_argument("VideoEncoder::add: expected a BGR frame of the encoder's size");
  }
  if (pipe_ < 0) throw std::logic_error("VideoEncoder::add after finish");
  const cv::Mat packed = frame.isContinuous() ? frame : frame.clone();
  const auto* data = packed.data;
  std::size_t left = packed.total() * packed.elemSize();
  // A stopped ffmpeg would raise SIGPIPE, which ends the process; ignore it while writing so the error is reported.
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  while (left > 0) {
    const ssize_t n = ::write(pipe_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::sigaction(SIGPIPE, &previous, nullptr);
      fail("stopped reading frames");
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  ::sigaction(SIGPIPE, &previous, nullptr);
}

void VideoEncoder::finish() {
  if (pipe_ < 0) throw std::logic_error("VideoEncoder::finish twice");
  ::close(pipe_);
  pipe_ = -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("exited with an error");
  // ffmpeg exits 0 after "Error writing trailer ...: No space left on device", leaving a cut
  // file; at -loglevel error it prints nothing else, so anything it printed is a failure.
  if (!tail_of(log_fd_).empty()) fail("reported an error");
  if (::rename(partial_.c_str(), out_.c_str()) != 0) throw OutputError(out_, system_reason("cannot move into place", errno));
  done_ = true;
}

}  // namespace campo
