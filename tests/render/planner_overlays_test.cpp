// A recorded run's figures find its planner's description by the planner name run.json records and
// draw the overlays the planner computes from its own decisions, written through its declarations:
// dstar_lite_3d's height map, rover_route's gap marks (the sequence figure's instants); a key the
// planner does not declare, or a value not of its type, refuses the run.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/planner_record.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "planners/rover_route.hpp"
#include "render/run_figures.hpp"
#include "render/run_files.hpp"
#include "run/event_log.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class PlannerOverlays : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_planner_overlays_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "scene.json") << R"j({"objects": []})j";
    std::ofstream csv(dir_ / "trajectory.csv");
    csv << "time_s,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps\n";
    for (int i = 0; i <= 20; ++i) csv << i << "," << i << ",0,0,1,0,0\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A run directory of `planner` with these events (run.json's events, as events.jsonl has them).
  RecordedRun recorded(const std::string& planner, const std::vector<PlannerEvent>& events) {
    nlohmann::json list = nlohmann::json::array();
    for (const PlannerEvent& e : events) list.push_back(nlohmann::json::parse(event_line(e)));
    const nlohmann::json record = {
        {"metrics", {{"outcome", "reached"}}},
        {"parameters",
         {{"mission", nlohmann::json::array({{{"position_m", {20, 0, 0}}}})}, {"planner", {{"name", planner}}}}},
        {"events", list}};
    std::ofstream(dir_ / "run.json") << record.dump();
    return load_run_dir(dir_);
  }

  std::string load_error(const std::string& planner, const std::vector<PlannerEvent>& events) {
    try {
      recorded(planner, events);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(PlannerOverlays, TheDescriptionIsFoundByTheRecordedPlannerName) {
  EXPECT_EQ(planner_record("dstar_lite_3d"), &dstar_lite_3d_record().description);
  EXPECT_EQ(planner_record("rover_route"), &rover_route_record().description);
  EXPECT_NE(planner_record("depth_reactive"), nullptr);
  EXPECT_EQ(planner_record("straight"), nullptr);  // records nothing of its own
  EXPECT_EQ(planner_record("no_such_planner"), nullptr);
  EXPECT_EQ(recorded("rover_route", {}).planner, &rover_route_record().description);
}

TEST_F(PlannerOverlays, DStarLite3dsHeightMapIsItsCellsOverlay) {
  const DStarLite3dRecord& r = dstar_lite_3d_record();
  Decisions first, second;
  r.height_map_grid.set(first.own, {.origin_m = {-1.0, 2.0}, .cell_size_m = 0.5, .columns = 4, .rows = 3});
  r.height_map_columns.set(second.own, {{1, 2, 7.5}, {3, 0, 2.0}});
  Decisions later;
  r.height_map_columns.set(later.own, {{1, 2, 9.0}});  // the column's top rose again
  const RecordedRun run = recorded("dstar_lite_3d", {{0.0, first}, {1.0, second}, {2.0, later}});
  const HeightMapView& h = run.view.height_map;
  EXPECT_EQ(h.origin_m, Eigen::Vector2d(-1.0, 2.0));
  EXPECT_EQ(h.cell_size_m, 0.5);
  ASSERT_EQ(h.columns, 4);
  ASSERT_EQ(h.rows, 3);
  ASSERT_EQ(h.top_m.size(), 12u);
  // Row-major from the south-west corner: (column 1, row 2) is 2 * 4 + 1.
  EXPECT_EQ(h.top_m[9], 9.0);
  EXPECT_EQ(h.top_m[3], 2.0);
  int unmapped = 0;
  for (const double v : h.top_m) unmapped += std::isnan(v) ? 1 : 0;
  EXPECT_EQ(unmapped, 10);
  // As it was at 1.5 s: the first top of the column.
  EXPECT_EQ(run_view_at(run, 1.5).height_map.top_m[9], 7.5);
  // The same decisions recorded by a planner without that overlay draw no height map.
  EXPECT_TRUE(recorded("straight", {{0.0, first}, {1.0, second}}).view.height_map.empty());
}

TEST_F(PlannerOverlays, AColumnOutsideTheGridIsRefused) {
  const DStarLite3dRecord& r = dstar_lite_3d_record();
  Decisions grid, outside;
  r.height_map_grid.set(grid.own, {.columns = 2, .rows = 2});
  r.height_map_columns.set(outside.own, {{2, 0, 1.0}});
  EXPECT_THAT(load_error("dstar_lite_3d", {{0.0, grid}, {1.0, outside}}),
              HasSubstr("run.json: /events/1/decisions/height_map_columns: columns inside the height_map_grid"));
}

TEST_F(PlannerOverlays, AnUndeclaredKeyOrAWrongTypeRefusesTheRun) {
  const Decisions undeclared{.own = {{"blocked", nlohmann::json::array()}}};
  EXPECT_THAT(load_error("dstar_lite_3d", {{0.0, {}}, {1.0, undeclared}}),
              HasSubstr("run.json: /events/1/decisions/blocked: expected a declared field (height_map_grid, "
                        "height_map_columns, blocked_cells, cleared_cells, occupied_voxels), got \"blocked\""));
  const Decisions wrong{.own = {{"occupied_voxels", "many"}}};
  EXPECT_THAT(load_error("dstar_lite_3d", {{0.0, wrong}}),
              HasSubstr("run.json: /events/0/decisions/occupied_voxels: expected integer"));
  // A replanning step's details are checked by the planner's replan fields.
  const Decisions step{.replan = ReplanDecision{.index = 0, .time_ms = 1.0, .details = {{"route_point", 3}}}};
  EXPECT_THAT(load_error("rover_route", {{0.0, step}}), HasSubstr("/events/0/decisions/replan/route_point"));
  // The bound's notes are not the planner's; a planner without a description records what it likes.
  const Decisions noted{.own = {{"thinned", {{"/planned_path", 3000}}}}};
  EXPECT_EQ(load_error("dstar_lite_3d", {{0.0, noted}}), "");
  EXPECT_EQ(load_error("straight", {{0.0, undeclared}}), "");
}

TEST_F(PlannerOverlays, RoverRoutesGapsMarkTheSequencesInstants) {
  const RoverRouteRecord& r = rover_route_record();
  const auto gap = [&](double center_deg) {
    Decisions d;
    r.gap.set(d.own, {.gaps = 2,
                      .nearest_range_m = 1.0,
                      .route_heading_deg = 90.0,
                      .chosen = ChosenGap{.center_deg = center_deg, .heading_deg = center_deg / 2, .width_m = 1.0}});
    return d;
  };
  Decisions none;
  r.gap.set(none.own, {.gaps = 0, .nearest_range_m = 1.0});
  // Avoiding from 2 s to 9 s; a gap on the left at 3 s, still left at 4 s, on the right at 7 s.
  const RecordedRun run = recorded("rover_route", {{1.0, none},
                                                   {2.0, {.avoiding = true}},
                                                   {3.0, gap(20.0)},
                                                   {4.0, gap(10.0)},
                                                   {7.0, gap(-15.0)},
                                                   {9.0, {.avoiding = false}}});
  // First chosen gap, half-way to the first on the other side, that one, 2 s after the avoidance ended.
  EXPECT_EQ(gap_switch_instants(run), (std::vector<double>{3.0, 5.0, 7.0, 11.0}));
  const HeadingMark mark = rover_route_record().description.heading(gap(-15.0)).value();
  EXPECT_EQ(mark.reference_deg, 90.0);
  EXPECT_EQ(mark.heading_deg, -7.5);
  EXPECT_EQ(mark.side, "right");
  EXPECT_EQ(mark.caption, "gap on the right, heading -8 deg (arrow)");
  EXPECT_EQ(mark.status, "gap on the right");
  // A scan without a chosen gap marks the route's direction only.
  const HeadingMark plain = rover_route_record().description.heading(none).value();
  EXPECT_FALSE(plain.heading_deg.has_value());
  EXPECT_TRUE(plain.side.empty());
  EXPECT_FALSE(rover_route_record().description.heading(Decisions{}).has_value());
}

TEST_F(PlannerOverlays, AGapThatNeverChangesSidesGivesNoInstants) {
  Decisions left;
  rover_route_record().gap.set(left.own, {.gaps = 1, .chosen = ChosenGap{.center_deg = 5.0}});
  EXPECT_THROW(gap_switch_instants(recorded("rover_route", {{1.0, left}, {2.0, left}})), InputError);
  EXPECT_THROW(gap_switch_instants(recorded("straight", {{1.0, left}})), InputError);
}

}  // namespace
}  // namespace campo
