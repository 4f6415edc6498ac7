// Videos: the encoder (ffmpeg fed raw frames) against ffprobe and decoded frames, and
// `campo render --kind video` end to end on recorded runs.
#include "render/video_encoder.hpp"

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "render/run_files.hpp"
#include "render/video_frame.hpp"
#include "tests/cli_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::Result;
using testing::slurp;

class Video : public testing::CliTest {
 protected:
  // ffprobe's count of decoded frames, width and height: "N,W,H".
  std::string probe(const fs::path& file) const {
    const std::string command = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                "stream=nb_read_frames,width,height -of csv=p=0 '" +
                                file.string() + "' > " + (dir_ / "probe").string();
    EXPECT_EQ(std::system(command.c_str()), 0);
    std::string text = slurp(dir_ / "probe");
    while (!text.empty() && (text.back() == '\n' || text.back() == ',')) text.pop_back();
    return text;
  }
  // Frame `index` of a video, decoded by ffmpeg.
  cv::Mat frame(const fs::path& file, int index) const {
    const fs::path png = dir_ / "frame.png";
    const std::string command = "ffmpeg -v error -y -i '" + file.string() + "' -vf 'select=eq(n\\," +
                                std::to_string(index) + ")' -frames:v 1 '" + png.string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0);
    return cv::imread(png.string(), cv::IMREAD_COLOR);
  }
};

// Frame k: a solid colour of its own, a white square moving right.
cv::Mat synthetic(int k) {
  cv::Mat f(360, 640, CV_8UC3, cv::Scalar(40 + 20 * k, 120, 200 - 15 * k));
  f(cv::Rect(20 + 40 * k, 100, 80, 80)).setTo(cv::Scalar(255, 255, 255));
  return f;
}

TEST_F(Video, EncodesEveryFrameAndTheSameFramesGiveTheSameBytes) {
  for (const char* name : {"a.mp4", "b.mp4", "c.gif"}) {
    const fs::path file = dir_ / name;
    VideoEncoder encoder(file, *video_format_of(file), {640, 360}, 10.0);
    for (int k = 0; k < 10; ++k) encoder.add(synthetic(k));
    EXPECT_FALSE(fs::exists(file));  // nothing half-written in place
    encoder.finish();
    EXPECT_EQ(probe(file), "640,360,10") << name;
  }
  EXPECT_EQ(slurp(dir_ / "a.mp4"), slurp(dir_ / "b.mp4"));
  // Decoded frames are the frames given (H.264 is lossy: compare averages and the square).
  for (const int k : {0, 6, 9}) {
    const cv::Mat decoded = frame(dir_ / "a.mp4", k);
    ASSERT_EQ(decoded.size(), cv::Size(640, 360));
    const cv::Mat given = synthetic(k);
    // yuv420p halves the chroma resolution: a few levels off on average, far less than a neighbour frame is.
    EXPECT_LT(cv::norm(decoded, given, cv::NORM_L1) / (640.0 * 360 * 3), 6.0) << k;
    EXPECT_GT(cv::norm(decoded, synthetic(k == 9 ? 8 : k + 1), cv::NORM_L1) / (640.0 * 360 * 3), 12.0) << k;
    EXPECT_GT(decoded.at<cv::Vec3b>(140, 60 + 40 * k)[1], 240) << k;  // inside the white square
  }
  EXPECT_EQ(video_format_of("x.GIF"), VideoFormat::gif);
  EXPECT_FALSE(video_format_of("x.avi"));
}

TEST_F(Video, FailuresNameFfmpegAndLeaveNoFile) {
  // An ffmpeg that fails: its message comes back, and no partial file is left.
  const std::string path = std::getenv("PATH");
  fs::create_directories(dir_ / "bin");
  write("bin/ffmpeg", "#!/bin/sh\ncat >/dev/null\necho 'boom: cannot encode' >&2\nexit 1\n");
  fs::permissions(dir_ / "bin" / "ffmpeg", fs::perms::owner_all);
  ::setenv("PATH", (dir_ / "bin").c_str(), 1);
  try {
    VideoEncoder encoder(dir_ / "x.mp4", VideoFormat::mp4, {640, 360}, 10.0);
    for (int k = 0; k < 10; ++k) encoder.add(synthetic(k));
    encoder.finish();
    ADD_FAILURE() << "a failing ffmpeg went unnoticed";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("boom: cannot encode"));
  }
  ::setenv("PATH", path.c_str(), 1);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find("x.mp4"), std::string::npos) << entry.path();
  }
  // Without ffmpeg on the PATH: the error names the package to install.
  ::setenv("PATH", (dir_ / "empty").c_str(), 1);
  try {
    VideoEncoder encoder(dir_ / "y.mp4", VideoFormat::mp4, {640, 360}, 10.0);
    ADD_FAILURE() << "started without ffmpeg";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("Debian package ffmpeg"));
  }
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_FALSE(fs::exists(dir_ / "y.mp4"));
  EXPECT_THROW(VideoEncoder(dir_ / "z.mp4", VideoFormat::mp4, {641, 360}, 10.0), std::invalid_argument);
}

TEST_F(Video, RenderWritesOneFramePerStepOfPlaybackAndHoldsTheEnd) {
  const fs::path run = dir_ / "run";
  ASSERT_EQ(campo("run " + std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json --out " + run.string() +
                  " --no-figures")
                .exit_code,
            0);
  const fs::path out = dir_ / "run.mp4";
  const Result r = campo("render " + run.string() + " --kind video --out " + out.string() +
                         " --fps 10 --speed 4 --size 640x360");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote " + out.string()));
  // Frames at 0, 0.4, 0.8 ... s up to the end (the last at the end itself), then 10 more: a second held.
  const double duration = load_run_dir(run).view.track.back().time_s;
  int moving = static_cast<int>(std::floor(duration / 0.4 + 1e-9)) + 1;
  if ((moving - 1) * 0.4 < duration) ++moving;
  EXPECT_EQ(probe(out), "640,360," + std::to_string(moving + 10));
  // The end is held: the last two frames decode alike; the first differs from the last.
  const cv::Mat last = frame(out, moving + 9), held = frame(out, moving + 1), first = frame(out, 0);
  EXPECT_LT(cv::norm(last, held, cv::NORM_L1) / last.total(), 1.0);
  EXPECT_GT(cv::norm(first, last, cv::NORM_L1) / last.total(), 1.0);
  // The sensor panel (right of the map, above the strip) holds the replanning's depth figure of
  // this depth_reactive run, not a blank: a good part of it is coloured.
  const cv::Rect panel = video_layout({640, 360}).sensor_px;
  cv::Mat grey;
  cv::cvtColor(first(panel), grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey < 200), panel.area() / 10);
  // Reproducible: the same run renders to the same bytes.
  const fs::path again = dir_ / "again.mp4";
  ASSERT_EQ(campo("render " + run.string() + " --kind video --out " + again.string() + " --fps 10 --speed 4 --size 640x360")
                .exit_code,
            0);
  EXPECT_EQ(slurp(out), slurp(again));
  // Bad requests: exit 2 with what was expected, nothing written.
  for (const std::string& args : {std::string("--kind video --out ") + (dir_ / "x.mp4").string() + " --size 641x360",
                                  std::string("--kind video --out ") + (dir_ / "x.mp4").string() + " --fps 0",
                                  std::string("--kind map --kind video --out ") + (dir_ / "x.mp4").string()}) {
    const Result bad = campo("render " + run.string() + " " + args);
    EXPECT_EQ(bad.exit_code, 2) << args << "\n" << bad.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.mp4"));
}

TEST_F(Video, RoverRunShowsItsRecordedScans) {
  // The same rover run recorded with every scan and without: only the first shows returns (red
  // dots) around the rover in its sensor panel; both show follow-the-gap's view.
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/vineyard_gap.json";
  const fs::path scanned = dir_ / "scanned", bare = dir_ / "bare";
  ASSERT_EQ(campo("run " + scene + " --out " + scanned.string() + " --no-figures --record-depth 1").exit_code, 0);
  ASSERT_EQ(campo("run " + scene + " --out " + bare.string() + " --no-figures").exit_code, 0);
  const auto red_in_panel = [&](const fs::path& run, const std::string& name) {
    const fs::path video = dir_ / name;
    const Result r = campo("render " + run.string() + " --kind video --out " + video.string() +
                           " --fps 5 --speed 4 --size 640x360");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    int red = 0;
    for (const int k : {5, 10, 15, 20, 25}) {  // 4 s to 20 s: the rows' posts, then the walker, pass by
      const cv::Mat panel = frame(video, k)(video_layout({640, 360}).sensor_px);
      for (int y = 0; y < panel.rows; ++y) {
        for (int x = 0; x < panel.cols; ++x) {
          const cv::Vec3b p = panel.at<cv::Vec3b>(y, x);
          red += p[2] > 150 && p[1] < 110 && p[0] < 110;
        }
      }
    }
    return red;
  };
  const int with_scans = red_in_panel(scanned, "scanned.mp4");
  const int without = red_in_panel(bare, "bare.mp4");
  // 99 vs 30 (the legend's dot) when written.
  EXPECT_GT(with_scans, without + 40) << with_scans << " vs " << without;
  const Result gif = campo("render " + scanned.string() + " --kind video --out " + (dir_ / "rover.gif").string() +
                           " --fps 5 --speed 4 --size 640x360");
  ASSERT_EQ(gif.exit_code, 0) << gif.err;
  EXPECT_THAT(probe(dir_ / "rover.gif"), ::testing::StartsWith("640,360,"));
}

}  // namespace
}  // namespace campo
