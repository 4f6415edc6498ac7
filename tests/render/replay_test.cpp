// The 3D replay (campo render --kind replay): its data against the recorded files and the
// scene's geometry, the page's self-containment, and the page itself in headless Chromium
// (Debian's chromium, tools/setup.sh --tests): it loads without console messages, its time slider
// moves the vehicle to where trajectory.csv has it, and its view of the scene from a known
// camera matches campo's own OSMesa render of the same view.
#include "render/replay.hpp"

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "render/run_files.hpp"
#include "render/snapshot.hpp"
#include "scene/scene_mesh.hpp"
#include "tests/cli_support.hpp"
#include "tests/render/silhouette_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::Result;
using testing::slurp;

class Replay : public testing::CliTest {
 protected:
  // A recorded run of `scene` (every fifth scan's depth map kept) in the test directory.
  fs::path record(const std::string& scene, const std::string& name, const std::string& extra = "") {
    const fs::path out = dir_ / name;
    const Result r = campo("run " + scene + " --out " + out.string() + " --no-figures --record-depth 5 " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }

  // Headless Chromium on `url`, console messages on stderr; `args` adds --dump-dom or --screenshot.
  Result chromium(const std::string& url, const std::string& args) const {
    const std::string command =
        "chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
        "--enable-logging=stderr --v=0 --virtual-time-budget=5000 --window-size=640,480 " +
        args + " '" + url + "' >" + (dir_ / "chromium.out").string() + " 2>" + (dir_ / "chromium.err").string();
    const int status = std::system(command.c_str());
    return {WEXITSTATUS(status), slurp(dir_ / "chromium.out"), slurp(dir_ / "chromium.err")};
  }
};

// The console lines of Chromium's log: any message or uncaught error of the page.
std::vector<std::string> console_lines(const std::string& log) {
  std::vector<std::string> out;
  for (const std::string& line : testing::lines_of(log)) {
    if (line.find("CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos) out.push_back(line);
  }
  return out;
}

// The value of data-NAME on the dumped page's <body>.
std::string body_data(const std::string& dom, const std::string& name) {
  const std::string key = "data-" + name + "=\"";
  const std::size_t at = dom.find(key);
  if (at == std::string::npos) return "";
  const std::size_t from = at + key.size();
  return dom.substr(from, dom.find('"', from) - from);
}

// trajectory.csv's position at time t, linearly between its samples.
Eigen::Vector3d position_at(const TrajectoryTable& table, double t) {
  const auto& time = table.column("time_s");
  const auto& x = table.column("x_m");
  const auto& y = table.column("y_m");
  const auto& z = table.column("z_m");
  std::size_t i = 1;
  while (i + 1 < time.size() && time[i] < t) ++i;
  const double f = std::clamp((t - time[i - 1]) / (time[i] - time[i - 1]), 0.0, 1.0);
  return Eigen::Vector3d(x[i - 1], y[i - 1], z[i - 1]) + f * Eigen::Vector3d(x[i] - x[i - 1], y[i] - y[i - 1], z[i] - z[i - 1]);
}

TEST_F(Replay, DataFollowsTheRecordedFilesAndScansLieOnTheScene) {
  const fs::path run_dir = record(std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json", "run");
  const RecordedRun run = load_run_dir(run_dir);
  const nlohmann::json data = replay_data({run});
  EXPECT_EQ(data["campo_replay"], 1);
  // The track: every recorded sample (fewer than the limit), to the millimetre.
  const TrajectoryTable table = read_trajectory_table(run_dir / "trajectory.csv");
  const nlohmann::json& r = data["runs"][0];
  ASSERT_EQ(r["times_s"].size(), table.column("time_s").size());
  for (std::size_t i = 0; i < r["times_s"].size(); i += 37) {
    EXPECT_NEAR(r["positions_m"][i][0].get<double>(), table.column("x_m")[i], 6e-4);
    EXPECT_NEAR(r["positions_m"][i][2].get<double>(), table.column("z_m")[i], 6e-4);
    EXPECT_NEAR(r["rpy_deg"][i][2].get<double>(), table.column("yaw_deg")[i], 6e-4);
  }
  EXPECT_EQ(r["vehicle"], "quadrotor");
  EXPECT_DOUBLE_EQ(data["duration_s"].get<double>(), r["times_s"].back().get<double>());
  // Two barriers as cuboids, the ground as a plane.
  ASSERT_EQ(data["scene"]["shapes"].size(), 2u);
  EXPECT_EQ(data["scene"]["planes"].size(), 1u);
  // Every return, turned into the world frame from the recorded pose, lies on the ground or
  // on a barrier's surface: the pose, the mount and the beam directions compose correctly.
  ASSERT_FALSE(r["scans"].empty());
  std::size_t points = 0;
  for (const auto& scan : r["scans"]) {
    for (const auto& p : scan["points_m"]) {
      const Eigen::Vector3d w(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      bool on_surface = std::abs(w.z()) < 0.01;
      for (const Shape& s : run.scene.shapes) {
        if (s.type != ShapeType::cuboid) continue;
        const Eigen::Vector3d local = (s.pose.inverse() * w).cwiseAbs() - 0.5 * s.size_m;
        on_surface = on_surface || (local.maxCoeff() < 0.01 && local.maxCoeff() > -0.01);
      }
      EXPECT_TRUE(on_surface) << w.transpose() << " at " << scan["time_s"];
      ++points;
    }
  }
  EXPECT_GT(points, 1000u);
}

TEST_F(Replay, PageIsSelfContainedAndRefusesMixedScenes) {
  const fs::path a = record(std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json", "a");
  const Result r = campo("render " + a.string() + " --kind replay");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = slurp(a / "replay.html");
  // No fetching at view time: no external scripts, styles or images.
  for (const char* remote : {"src=\"http", "href=\"http", "<script src", "<link ", "url(http", "<img "}) {
    EXPECT_EQ(page.find(remote), std::string::npos) << remote;
  }
  // The data inside is exactly replay_data's.
  const std::string open = "<script id=\"campo-data\" type=\"application/json\">";
  const std::size_t from = page.find(open);
  ASSERT_NE(from, std::string::npos);
  const std::size_t to = page.find("</script>", from);
  EXPECT_EQ(nlohmann::json::parse(page.substr(from + open.size(), to - from - open.size())),
            replay_data({load_run_dir(a)}));
  // One replay shows one scene.
  const fs::path b = record(std::string(CAMPO_SOURCE_DIR) + "/scenes/vineyard_gap.json", "b");
  const Result mixed = campo("render " + a.string() + " " + b.string() + " --kind replay --out " + (dir_ / "x.html").string());
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_THAT(mixed.err, HasSubstr("one replay shows one scene"));
  EXPECT_FALSE(fs::exists(dir_ / "x.html"));
  const Result wrong = campo("render " + a.string() + " --kind map --kind replay --out " + (dir_ / "y.html").string());
  EXPECT_EQ(wrong.exit_code, 2);
  // Movers are sampled where the scene puts them, and never more often than the limit allows.
  const RecordedRun walker_run = load_run_dir(b);
  ASSERT_EQ(walker_run.scene.movers.size(), 1u);
  ReplayLimits few;
  few.max_mover_samples = 50;
  const nlohmann::json movers = replay_data({walker_run}, few)["scene"]["movers"];
  ASSERT_EQ(movers.size(), 1u);
  const nlohmann::json& times = movers[0]["times_s"];
  EXPECT_LE(times.size(), 51u);
  EXPECT_GE(times.size(), 50u);
  for (std::size_t k = 0; k < times.size(); k += 7) {
    const Eigen::Vector3d want = walker_run.scene.movers[0].position_at(times[k].get<double>());
    EXPECT_NEAR(movers[0]["positions_m"][k][1].get<double>(), want.y(), 3e-3) << k;  // both rounded to 1 ms, 1 mm
  }
}

TEST_F(Replay, BoundedInRunsSamplesAndPageWhateverIsGiven) {
  // More run directories than a replay shows are refused before any is read (they are not runs).
  std::string many;
  for (int i = 0; i < 65; ++i) {
    fs::create_directories(dir_ / ("r" + std::to_string(i)));
    many += " " + (dir_ / ("r" + std::to_string(i))).string();
  }
  const Result refused = campo("render" + many + " --kind replay --out " + (dir_ / "many.html").string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr("error: command line: runs: at most 64 run directories in one replay, got 65"));
  EXPECT_FALSE(fs::exists(dir_ / "many.html"));
  const Result videos = campo("render" + many + " --kind video --out " + (dir_ / "videos").string());
  EXPECT_EQ(videos.exit_code, 2);
  EXPECT_THAT(videos.err, HasSubstr("at most 16 run directories for --kind video, got 65"));
  // The runs share the totals: each keeps its part of the track samples and scan points.
  const fs::path a = record(std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json", "a");
  const RecordedRun run = load_run_dir(a);
  ReplayLimits small;
  small.max_total_track_samples = 400;
  small.max_total_scan_points = 2000;
  const nlohmann::json data = replay_data({run, run, run, run}, small);
  ASSERT_EQ(data["runs"].size(), 4u);
  for (const auto& r : data["runs"]) {
    EXPECT_LE(r["times_s"].size(), 101u);  // 400 / 4, and the last sample
    EXPECT_GT(r["times_s"].size(), 50u);  // thinned by a whole stride: more than half the share
    std::size_t points = 0;
    for (const auto& scan : r["scans"]) points += scan["points_m"].size();
    EXPECT_GT(points, 0u);
    EXPECT_LE(points, 6u * 101u);  // 2000 / 4 = 500: 5 scans of 100 points (thinning keeps the last of each)
  }
  // Read from the directories one at a time, the data are the same.
  EXPECT_EQ(replay_data(std::vector<fs::path>{a, a, a, a}, small), data);
  // A GIF longer than its limit is refused before a frame is drawn.
  const Result gif = campo("render " + a.string() + " --kind video --speed 0.05 --out " + (dir_ / "slow.gif").string());
  EXPECT_EQ(gif.exit_code, 2);
  EXPECT_THAT(gif.err, HasSubstr("--out: a GIF of at most 3000 frames, got "));
  EXPECT_FALSE(fs::exists(dir_ / "slow.gif"));
}

TEST_F(Replay, LoadsCleanlyAndTheSliderMovesTheVehicle) {
  const fs::path run_dir = record(std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json", "run");
  ASSERT_EQ(campo("render " + run_dir.string() + " --kind replay").exit_code, 0);
  const std::string url = "file://" + (run_dir / "replay.html").string();
  const TrajectoryTable table = read_trajectory_table(run_dir / "trajectory.csv");
  std::vector<Eigen::Vector3d> seen;
  for (const double t : {3.25, 9.5}) {
    const Result page = chromium(url + "#t=" + std::to_string(t), "--dump-dom");
    ASSERT_EQ(page.exit_code, 0) << page.err;
    EXPECT_TRUE(console_lines(page.err).empty()) << testing::lines_of(page.err).size() << " log lines; first console line: "
                                                 << (console_lines(page.err).empty() ? "" : console_lines(page.err)[0]);
    ASSERT_EQ(body_data(page.out, "ready"), "1");
    EXPECT_DOUBLE_EQ(std::stod(body_data(page.out, "time")), t);
    std::istringstream xyz(body_data(page.out, "vehicles"));
    Eigen::Vector3d p;
    char comma;
    xyz >> p.x() >> comma >> p.y() >> comma >> p.z();
    ASSERT_TRUE(xyz) << body_data(page.out, "vehicles");
    // Where trajectory.csv has the vehicle then (the page interpolates its millimetre-rounded samples).
    EXPECT_LT((p - position_at(table, t)).norm(), 2e-3) << t;
    EXPECT_GT(std::stoi(body_data(page.out, "scan-points")), 0);
    seen.push_back(p);
  }
  EXPECT_GT((seen[0] - seen[1]).norm(), 1.0);
}

// Terrain and one solid of each kind, no ground plane, all within the snapshot's fog-free range.
constexpr const char* kViewScene = R"j({
  "campo_scene": 1, "name": "view_check",
  "objects": [
    {"alias": "hill", "type": "heightfield", "expression": "0.8*sin(x/3) + 0.5*cos(y/4)",
     "size_m": [16, 12], "spacing_m": 0.5, "color": [0.5, 0.6, 0.35]},
    {"alias": "box", "type": "cuboid", "size_m": [2, 1, 3],
     "pose": {"position_m": [2, 2, 2], "rpy_deg": [0, 0, 30]}, "color": [0.8, 0.2, 0.2]},
    {"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 4,
     "pose": {"position_m": [-4, -2.5, 2], "rpy_deg": [20, 0, 0]}, "color": [0.2, 0.3, 0.8]},
    {"alias": "cone", "type": "cone", "radius_m": 1, "height_m": 2.5, "pose": {"position_m": [-3, 3, 2]}},
    {"alias": "ball", "type": "sphere", "radius_m": 0.8, "pose": {"position_m": [4, -3, 2.5]}},
    {"alias": "goal", "type": "dummy", "pose": {"position_m": [3, 0, 4]}},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 4]},
     "planner": {"name": "straight"}, "mission": {"waypoints": [{"frame": "goal"}]}}
  ]})j";

TEST_F(Replay, ScreenshotMatchesCamposOwnRenderOfTheSameView) {
  const std::string scene_file = write("view_check.json", kViewScene);
  const fs::path run_dir = record(scene_file, "run", "--planner straight");
  ASSERT_EQ(campo("render " + run_dir.string() + " --kind replay").exit_code, 0);
  SnapshotCamera camera;
  camera.eye_m = {-14.0, -16.0, 14.0};
  camera.target_m = {0.0, 0.0, 1.0};
  camera.fov_deg = 50.0;
  camera.width_px = 640;
  camera.height_px = 480;
  const std::string hash = "#view=silhouette&fov=50&camera=-14,-16,14,0,0,1";
  const fs::path shot = dir_ / "shot.png";
  const Result r = chromium("file://" + (run_dir / "replay.html").string() + hash, "--screenshot=" + shot.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(console_lines(r.err).empty());
  const cv::Mat page = cv::imread(shot.string(), cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(page.size(), cv::Size(640, 480));
  // campo's render of the same scene from the same camera, without track or vehicle: solid
  // wherever it is not the sky colour.
  const Scene scene = load_scene(scene_file);
  const cv::Mat own = render_snapshot(scene, build_scene_mesh(scene), camera, {}, std::nullopt, VehicleType::quadrotor);
  const test::SilhouetteComparison c = test::compare_silhouettes(own, page);
  // The scene fills a good part of the view, and the two silhouettes agree but for edge pixels.
  EXPECT_GT(c.solid, 640 * 480 / 10);
  const double overlap = c.overlap();
  EXPECT_GT(overlap, 0.988) << c.both << " / " << c.either;  // 0.993 here; a camera 0.5 m off gives 0.986
  RecordProperty("silhouette_overlap", std::to_string(overlap));
}

}  // namespace
}  // namespace campo
