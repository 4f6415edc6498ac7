// Figures, videos and replays of a run of several vehicles (issue 33): a run of two quadrotors made by
// `campo run` is read back whole, its map has each vehicle's track in that vehicle's colour where the
// recorded trajectory files have it and each footprint where its track ends, the legends name both, a video
// frame and the replay show both, and --vehicle naming no vehicle of the run is refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "campo/json_reader.hpp"
#include "render/map_figure.hpp"
#include "render/replay.hpp"
#include "render/run_figures.hpp"
#include "render/run_files.hpp"
#include "render/side_view_figure.hpp"
#include "render/video_frame.hpp"
#include "tests/cli_support.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using figure::test::expect_vector_outputs;
using figure::test::nearest_colour;
using ::testing::HasSubstr;

// Two quadrotors 3 m apart flying opposite ways: alpha east along y = 0, bravo west along y = 3.
constexpr const char* kPairScene = R"j({"campo_scene": 1, "name": "tiny_pair",
 "world": {"time_limit_s": 20},
 "objects": [
  {"alias": "ground", "type": "plane"},
  {"alias": "alpha", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
   "mission": {"waypoints": [{"position_m": [4, 0, 1.5]}]}},
  {"alias": "bravo", "type": "quadrotor", "pose": {"position_m": [4, 3, 1.5], "rpy_deg": [0, 0, 180]},
   "mission": {"waypoints": [{"position_m": [0, 3, 1.5]}]}}
 ]})j";

cv::Vec3b bgr(const cv::Scalar& c) {
  return {static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2])};
}

class FleetFigures : public testing::CliTest {
 protected:
  // The pair's run directory, written by campo run with its figures.
  fs::path record() {
    const fs::path out = dir_ / "pair";
    const testing::Result r = campo("run " + write("pair.json", kPairScene) + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("map.png"));
    return out;
  }

  // Every vehicle's view as the run's figures draw it: with its footprint.
  static std::vector<RunView> views(const RecordedRun& run) {
    std::vector<RunView> out;
    for (const RecordedVehicle& v : run.vehicles) {
      out.push_back(v.view);
      out.back().footprint_m = vehicle_size_m(v).head<2>();
    }
    return out;
  }
};

TEST_F(FleetFigures, LoadsEveryVehicleInSceneOrder) {
  const fs::path out = record();
  const RecordedRun run = load_run_dir(out);
  ASSERT_EQ(run.vehicles.size(), 2u);
  EXPECT_TRUE(run.several());
  const std::vector<std::string> aliases{"alpha", "bravo"};
  const std::vector<Eigen::Vector3d> goals{{4, 0, 1.5}, {0, 3, 1.5}};
  for (std::size_t i = 0; i < 2; ++i) {
    const RecordedVehicle& v = run.vehicles[i];
    EXPECT_EQ(v.alias, aliases[i]);
    EXPECT_EQ(v.trajectory_file, "trajectory_" + aliases[i] + ".csv");
    const TrajectoryTable table = read_trajectory_table(out / v.trajectory_file);
    ASSERT_EQ(v.view.track.size(), table.column("time_s").size());
    EXPECT_EQ(v.view.track.back().position_m.x(), table.column("x_m").back());
    EXPECT_EQ(v.view.track.back().position_m.y(), table.column("y_m").back());
    EXPECT_EQ(v.view.label, aliases[i]);
    EXPECT_EQ(v.view.outcome, "reached");
    ASSERT_EQ(v.view.mission.size(), 1u);
    EXPECT_TRUE(v.view.mission.back().position_m.isApprox(goals[i]));
  }
  // The chosen vehicle's are the run's single-vehicle fields: the first by default, else the one named.
  EXPECT_EQ(run.chosen, 0u);
  EXPECT_EQ(run.view.track.size(), run.vehicles[0].view.track.size());
  EXPECT_EQ(run.view.label, "pair");
  const RecordedRun bravo = load_run_dir(out, "bravo");
  EXPECT_EQ(bravo.chosen, 1u);
  EXPECT_EQ(bravo.view.track.front().position_m, bravo.vehicles[1].view.track.front().position_m);
  EXPECT_EQ(recorded_vehicle(bravo).alias, "bravo");
  EXPECT_EQ(run_view_at(bravo, 1, 1.0).track.back().time_s, run_view_at(bravo, 1.0).track.back().time_s);
}

TEST_F(FleetFigures, AnUnknownVehicleIsAnInputErrorNamingVehicle) {
  const fs::path out = record();
  try {
    load_run_dir(out, "charlie");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "command line");
    EXPECT_EQ(e.pointer(), "--vehicle");
    EXPECT_THAT(e.message(), HasSubstr("\"charlie\""));
    EXPECT_THAT(e.message(), HasSubstr("\"alpha\", \"bravo\""));
  }
  const testing::Result r = campo("render " + out.string() + " --kind map --vehicle charlie --out " + (dir_ / "f").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--vehicle"));
  EXPECT_FALSE(fs::exists(dir_ / "f" / "pair" / "map.png"));
  // A replay alone reads its runs later: refused all the same, before anything is written.
  const testing::Result replay = campo("render " + out.string() + " --kind replay --vehicle charlie --out " +
                                       (dir_ / "r.html").string());
  EXPECT_EQ(replay.exit_code, 2);
  EXPECT_THAT(replay.err, HasSubstr("--vehicle"));
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

// The map campo run wrote: each vehicle's colour along its recorded track (and not the other's), each
// footprint's pale fill inside the footprint at the track's end, at the recorded heading.
TEST_F(FleetFigures, MapDrawsEveryTrackInItsColourAndEveryFootprint) {
  const fs::path out = record();
  const RecordedRun run = load_run_dir(out);
  const FigureLayout layout = fleet_map_layout(run.scene, views(run), FigureStyle{});
  const cv::Mat image = cv::imread((out / "map.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(image.size(), layout.image_px);
  ASSERT_GT(cv::norm(vehicle_color(0) - vehicle_color(1)), 100.0);
  for (std::size_t i = 0; i < 2; ++i) {
    const TrajectoryTable table = read_trajectory_table(out / run.vehicles[i].trajectory_file);
    const auto& x = table.column("x_m");
    const auto& y = table.column("y_m");
    const cv::Vec3b own = bgr(vehicle_color(i)), other = bgr(vehicle_color(1 - i));
    int checked = 0;
    for (std::size_t k = 0; k < x.size(); k += 5) {
      if (x[k] < 1.0 || x[k] > 3.0) continue;  // clear of the start, goal and footprint markers
      const cv::Point2d p = layout.to_px({x[k], y[k]});
      EXPECT_LT(nearest_colour(image, p, own, 1), 30) << run.vehicles[i].alias << " at " << x[k] << ", " << y[k];
      EXPECT_GT(nearest_colour(image, p, other, 1), 150) << run.vehicles[i].alias << " at " << x[k] << ", " << y[k];
      ++checked;
    }
    EXPECT_GT(checked, 5);
    // Inside the footprint (0.6 m square for a quadrotor), towards its rear left corner, clear of the goal star.
    const double yaw = table.column("yaw_deg").back() * M_PI / 180.0;
    const Eigen::Vector2d ahead(std::cos(yaw), std::sin(yaw)), left(-ahead.y(), ahead.x());
    const Eigen::Vector2d centre(x.back(), y.back());
    const Eigen::Vector2d inside = centre + 0.8 * (-0.3 * ahead + 0.3 * left);
    const cv::Point2d p = layout.to_px(inside);
    ASSERT_GT(cv::norm(p - layout.to_px(centre)), 20.0);  // beyond the goal star's tips and ring
    EXPECT_LT(nearest_colour(image, p, bgr(figure::lighten(vehicle_color(i), 0.55)), 1), 20) << run.vehicles[i].alias;
  }
}

// Read back from the PDF by another program (pdftotext): the legends name each vehicle and its outcome.
TEST_F(FleetFigures, LegendsNameEveryVehicle) {
  const RecordedRun run = load_run_dir(record());
  FigureStyle style;
  style.max_size_px = 600;
  style.title = "Fleet";
  expect_vector_outputs(draw_fleet_map(run.scene, views(run), style),
                        {"alpha (reached)", "bravo (reached)", "vehicle, at its end", "goal"});
  expect_vector_outputs(draw_fleet_side_view(run.scene, views(run), style), {"alpha (reached)", "bravo (reached)"});
}

// A video frame half way: each vehicle's track so far in its colour, where the recorded files have it.
TEST_F(FleetFigures, VideoFramesShowEveryVehicle) {
  const RecordedRun run = load_run_dir(record());
  const std::vector<RunView> whole = views(run);
  VideoFrames frames(run.scene, whole, {960, 540});
  const double t = 0.5 * run.vehicles[0].view.track.back().time_s;
  std::vector<RunView> now;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    now.push_back(run_view_at(run, i, t));
    now.back().footprint_m = whole[i].footprint_m;
  }
  const cv::Mat frame = frames.draw(now, t, cv::Mat(), "caption", VideoStrip{});
  for (std::size_t i = 0; i < now.size(); ++i) {
    // Half way along what it has flown by then.
    const TrackPoint& mid = now[i].track[now[i].track.size() / 2];
    ASSERT_GT((mid.position_m - now[i].track.front().position_m).norm(), 0.5);
    EXPECT_LT(nearest_colour(frame, frames.to_frame_px(mid.position_m.head<2>()), bgr(vehicle_color(i)), 1), 40)
        << run.vehicles[i].alias;
    // Its footprint where it is then.
    EXPECT_LT(nearest_colour(frame, frames.to_frame_px(now[i].track.back().position_m.head<2>()),
                             bgr(figure::lighten(vehicle_color(i), 0.55)), 3),
              20)
        << run.vehicles[i].alias;
  }
  // A video of the run, with bravo's sensor panel.
  const testing::Result r = campo("render " + run.dir.string() + " --kind video --vehicle bravo --speed 4 --size 480x270 --out " +
                                  (dir_ / "pair.gif").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "pair.gif"));
}

// The replanning depth maps (replans/) are one vehicle's: run.json's recorded_vehicle, else the first.
TEST_F(FleetFigures, ReplanningStepsAreTheRecordedVehiclesOnly) {
  const fs::path out = record();
  nlohmann::json record = read_json_file(out / "run.json");
  record["vehicles"][1]["parameters"]["planner"]["name"] = "depth_reactive";  // a planner that draws its steps
  std::ofstream(out / "run.json") << record.dump();
  EXPECT_EQ(sensor_records_vehicle(load_run_dir(out)), "alpha");
  try {
    find_replan_steps(load_run_dir(out, "bravo"), std::nullopt);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.pointer(), "--vehicle");
    EXPECT_THAT(e.message(), HasSubstr("of vehicle \"alpha\", not of \"bravo\""));
  }
  record["recorded_vehicle"] = "bravo";
  std::ofstream(out / "run.json") << record.dump();
  EXPECT_EQ(sensor_records_vehicle(load_run_dir(out)), "bravo");
  try {
    find_replan_steps(load_run_dir(out, "bravo"), std::nullopt);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {  // bravo's own: it recorded none
    EXPECT_EQ(e.message(), "no replanning steps recorded");
  }
}

TEST_F(FleetFigures, ReplayShowsEveryVehicle) {
  const RecordedRun run = load_run_dir(record());
  const nlohmann::json data = replay_data(std::vector<RecordedRun>{run});
  ASSERT_EQ(data["runs"].size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const nlohmann::json& entry = data["runs"][i];
    EXPECT_EQ(entry["label"], run.vehicles[i].alias);
    EXPECT_EQ(entry["outcome"], "reached");
    EXPECT_EQ(entry["vehicle"], "quadrotor");
    const cv::Scalar c = vehicle_color(i);
    EXPECT_NEAR(entry["color"][0].get<double>(), c[2] / 255.0, 1e-3);
    EXPECT_NEAR(entry["color"][2].get<double>(), c[0] / 255.0, 1e-3);
    const TrajectoryTable table = read_trajectory_table(run.dir / run.vehicles[i].trajectory_file);
    EXPECT_NEAR(entry["times_s"].back().get<double>(), table.column("time_s").back(), 1e-4);
    EXPECT_NEAR(entry["positions_m"].back()[0].get<double>(), table.column("x_m").back(), 1e-3);
    EXPECT_NEAR(entry["positions_m"].back()[1].get<double>(), table.column("y_m").back(), 1e-3);
  }
  EXPECT_THAT(data["title"].get<std::string>(), HasSubstr("2 vehicles"));
}

}  // namespace
}  // namespace campo
