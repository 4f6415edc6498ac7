// The planner decisions of a run are written to JSON and read back in one
// place, bounded as they are recorded, and events.jsonl reads back what was
// written.
#include "run/event_log.hpp"

#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/record_fields.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "planners/rover_route.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

nlohmann::json points(std::size_t n) {
  nlohmann::json p = nlohmann::json::array();
  for (std::size_t i = 0; i < n; ++i) p.push_back({static_cast<double>(i), 0.5, 1.0});
  return p;
}

// The same points, typed.
std::vector<Eigen::Vector3d> hits(std::size_t n) {
  std::vector<Eigen::Vector3d> p;
  for (std::size_t i = 0; i < n; ++i) p.emplace_back(static_cast<double>(i), 0.5, 1.0);
  return p;
}

// Every typed field decided, with planners' own decisions and details written through their declarations.
Decisions every_field() {
  Decisions d;
  d.reached_waypoints = {2, 3};
  d.planned_waypoint = Eigen::Vector3d(1.5, -2.0, 3.25);
  d.reached_intermediate = Eigen::Vector3d(0.0, 0.1, 0.2);
  d.discarded_waypoint = Eigen::Vector3d(-1e-3, 4.0, 7.0);
  d.planned_path = std::vector<Eigen::Vector3d>{{0, 0, 1}, {0.25, 0, 1}, {0.5, 0.125, 1}};
  d.avoiding = false;
  d.replan = ReplanDecision{.index = 7, .sensor = "cam", .time_ms = 12.5, .details = {{"action", "fly"}}};
  d.lidar_hits = {{1.0, 2.0, 3.0}, {-0.25, 0.5, 12.75}};
  const DStarLite3dRecord& dstar = dstar_lite_3d_record();
  dstar.height_map_grid.set(d.own, {.origin_m = {-30.0, 7.5}, .cell_size_m = 1.5, .columns = 100, .rows = 80});
  dstar.height_map_columns.set(d.own, {{2, 0, 14.0}, {99, 79, -7.0}});
  rover_route_record().gap.set(d.own, {.gaps = 3,
                                       .nearest_range_m = 1.25,
                                       .route_heading_deg = 90.0,
                                       .goal_deg = -2.5,
                                       .chosen = ChosenGap{.center_deg = -4.5, .heading_deg = -6.0, .width_m = 1.75}});
  depth_reactive_record().wall_following.set(d.own, {{"side", "left"}});
  return d;
}

TEST(Decisions, TypedToJsonAndBackIsTheSame) {
  const Decisions d = every_field();
  EXPECT_EQ(decisions_from_json(decisions_to_json(d), "f", ""), d);
  // A replanning step without a sensor, a cleared path, nothing else.
  const Decisions sparse{.planned_path = std::vector<Eigen::Vector3d>{},
                         .replan = ReplanDecision{.index = 0, .time_ms = 0.5}};
  const Decisions back = decisions_from_json(decisions_to_json(sparse), "f", "");
  EXPECT_EQ(back, sparse);
  EXPECT_TRUE(back.planned_path.has_value());
  EXPECT_FALSE(back.replan->sensor.has_value());
  EXPECT_TRUE(Decisions().empty());
  EXPECT_FALSE(sparse.empty());
  EXPECT_FALSE((Decisions{.own = {{"note", 1}}}.empty()));
  EXPECT_FALSE((Decisions{.lidar_hits = {{0, 0, 0}}}.empty()));
  // A scan without a chosen gap: the chosen gap's keys are absent, and stay so.
  const GapDecision gap{.gaps = 0, .nearest_range_m = 3.0, .route_heading_deg = -45.0};
  Decisions no_gap;
  rover_route_record().gap.set(no_gap.own, gap);
  EXPECT_EQ(decisions_to_json(no_gap),
            (nlohmann::json{{"gap", {{"gaps", 0}, {"nearest_range_m", 3.0}, {"route_heading_deg", -45.0},
                                     {"goal_deg", 0.0}}}}));
  const Decisions back_gap = decisions_from_json(decisions_to_json(no_gap), "f", "");
  EXPECT_EQ(back_gap, no_gap);
  EXPECT_EQ(rover_route_record().gap.get(back_gap.own), gap);
}

TEST(Decisions, RecordedAsDocumented) {
  // docs/running.md, "Planner decisions in the record": one key a field, a replanning step one object with the
  // planner's details beside its index, sensor and time; keys in order, as events.jsonl has them.
  EXPECT_EQ(event_line({2.5, every_field()}),
            R"({"decisions":{"avoiding":false,"discarded_waypoint":[-0.001,4.0,7.0],)"
            R"("gap":{"gap_center_deg":-4.5,"gap_heading_deg":-6.0,"gap_width_m":1.75,"gaps":3,"goal_deg":-2.5,)"
            R"("nearest_range_m":1.25,"route_heading_deg":90.0},)"
            R"("height_map_columns":[[2,0,14.0],[99,79,-7.0]],)"
            R"("height_map_grid":{"cell_size_m":1.5,"columns":100,"origin_m":[-30.0,7.5],"rows":80},)"
            R"("lidar_hits":[[1.0,2.0,3.0],[-0.25,0.5,12.75]],)"
            R"("planned_path":[[0.0,0.0,1.0],[0.25,0.0,1.0],[0.5,0.125,1.0]],)"
            R"("planned_waypoint":[1.5,-2.0,3.25],"reached_intermediate":[0.0,0.1,0.2],"reached_waypoints":[2,3],)"
            R"("replan":{"action":"fly","index":7,"sensor":"cam","time_ms":12.5},)"
            R"("wall_following":{"side":"left"}},"time_s":2.5})");
  EXPECT_EQ(event_line({0.0, Decisions{}}), R"({"decisions":{},"time_s":0.0})");
}

TEST(Decisions, OtherKeysLandInThePlannersOwnAsTheyAre) {
  const nlohmann::json record = {{"avoiding", true},
                                 {"wall_following", {{"offset_deg", 60.0}, {"side", "left"}}},
                                 {"occupied_voxels", 12},
                                 {"replan", {{"index", 1}, {"time_ms", 2.0}, {"visibility", "visible"}}}};
  const Decisions d = decisions_from_json(record, "f", "");
  EXPECT_EQ(d.avoiding, true);
  EXPECT_EQ(d.own, (nlohmann::json{{"wall_following", {{"offset_deg", 60.0}, {"side", "left"}}},
                                      {"occupied_voxels", 12}}));
  ASSERT_TRUE(d.replan.has_value());
  EXPECT_EQ(d.replan->details, (nlohmann::json{{"visibility", "visible"}}));
  EXPECT_EQ(decisions_to_json(d), record);
}

TEST(Decisions, AMalformedFieldIsAnErrorNamingItsKey) {
  // A planner's own field is checked by its declaration (as a run directory is read back for figures).
  const auto declared_error = [](const RecordFields& fields, const nlohmann::json& decisions) -> std::string {
    try {
      const PlannerEvent e = event_from_json({{"time_s", 1.0}, {"decisions", decisions}}, "run.json", "/events/4");
      fields.check(e.decisions.own, "run.json", "/events/4/decisions");
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "run.json");
      return e.pointer() + " | " + e.what();
    }
    return "no error";
  };
  const RecordFields& dstar = dstar_lite_3d_record().description.decisions;
  const RecordFields& rover = rover_route_record().description.decisions;
  const auto error = [](const nlohmann::json& decisions) -> std::string {
    try {
      event_from_json({{"time_s", 1.0}, {"decisions", decisions}}, "run.json", "/events/4");
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "run.json");
      return e.pointer() + " | " + e.what();
    }
    return "no error";
  };
  EXPECT_THAT(error({{"planned_waypoint", {1, 2}}}),
              HasSubstr("/events/4/decisions/planned_waypoint | run.json: /events/4/decisions/planned_waypoint: "
                        "expected a point [x, y, z] of numbers, m, got"));
  EXPECT_THAT(error({{"reached_intermediate", "here"}}), HasSubstr("/events/4/decisions/reached_intermediate |"));
  EXPECT_THAT(error({{"discarded_waypoint", {1, 2, "3"}}}), HasSubstr("/events/4/decisions/discarded_waypoint |"));
  EXPECT_THAT(error({{"planned_path", {{0, 0, 0}, {1, 1}}}}),
              HasSubstr("/events/4/decisions/planned_path/1 | run.json: /events/4/decisions/planned_path/1: expected"));
  EXPECT_THAT(error({{"planned_path", 3}}), HasSubstr("/events/4/decisions/planned_path |"));
  EXPECT_THAT(error({{"reached_waypoints", {0, -1}}}),
              HasSubstr("/events/4/decisions/reached_waypoints/1 | run.json: /events/4/decisions/reached_waypoints/1: "
                        "expected an integer in [0, 2147483647], got"));
  EXPECT_THAT(error({{"reached_waypoints", 0}}), HasSubstr("/events/4/decisions/reached_waypoints |"));
  EXPECT_THAT(error({{"avoiding", 1}}), HasSubstr("/events/4/decisions/avoiding | run.json: "
                                                  "/events/4/decisions/avoiding: expected true or false, got"));
  EXPECT_THAT(error({{"replan", {{"time_ms", 1.0}}}}), HasSubstr("/events/4/decisions/replan | run.json: "
                                                                 "/events/4/decisions/replan: expected a replanning "
                                                                 "step with its \"index\""));
  EXPECT_THAT(error({{"replan", {{"index", 0}}}}), HasSubstr("with its \"time_ms\""));
  EXPECT_THAT(error({{"replan", {{"index", 1.5}, {"time_ms", 1.0}}}}), HasSubstr("/events/4/decisions/replan/index |"));
  EXPECT_THAT(error({{"replan", {{"index", 0}, {"time_ms", "1"}}}}), HasSubstr("/events/4/decisions/replan/time_ms |"));
  EXPECT_THAT(error({{"replan", {{"index", 0}, {"time_ms", 1}, {"sensor", 2}}}}),
              HasSubstr("/events/4/decisions/replan/sensor |"));
  EXPECT_THAT(error({{"replan", true}}), HasSubstr("/events/4/decisions/replan |"));
  EXPECT_THAT(error(nlohmann::json::array()), HasSubstr("/events/4/decisions | run.json: /events/4/decisions: "
                                                        "expected an object of planner decisions"));
  EXPECT_THAT(error({{"lidar_hits", {{0, 0, 0}, {1, 2}}}}),
              HasSubstr("/events/4/decisions/lidar_hits/1 | run.json: /events/4/decisions/lidar_hits/1: expected a "
                        "point [x, y, z] of numbers, m, got"));
  EXPECT_THAT(error({{"lidar_hits", "many"}}), HasSubstr("/events/4/decisions/lidar_hits |"));
  const nlohmann::json grid = {{"origin_m", {0.0, 0.0}}, {"cell_size_m", 1.5}, {"columns", 10}, {"rows", 10}};
  const auto with = [](nlohmann::json j, const char* key, nlohmann::json value) {
    j[key] = std::move(value);
    return j;
  };
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", with(grid, "cell_size_m", 0.0)}}),
              HasSubstr("/events/4/decisions/height_map_grid/cell_size_m | run.json: "
                        "/events/4/decisions/height_map_grid/cell_size_m: expected a number > 0, got"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", with(grid, "rows", 0)}}), HasSubstr("/decisions/height_map_grid/rows |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", with(grid, "columns", 2.5)}}),
              HasSubstr("/decisions/height_map_grid/columns |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", with(grid, "origin_m", nlohmann::json::array({1.0}))}}),
              HasSubstr("/decisions/height_map_grid/origin_m |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", with(grid, "levels", 3)}}),
              HasSubstr("/decisions/height_map_grid/levels | run.json: /events/4/decisions/height_map_grid/levels: "
                        "unknown key \"levels\""));
  nlohmann::json no_rows = grid;
  no_rows.erase("rows");
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", no_rows}}),
              HasSubstr("/events/4/decisions/height_map_grid | run.json: /events/4/decisions/height_map_grid: "
                        "missing required key \"rows\""));
  EXPECT_THAT(declared_error(dstar, {{"height_map_grid", 1.5}}), HasSubstr("/events/4/decisions/height_map_grid |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_columns", {{1, 2, 3.0}, {1, -2, 3.0}}}}),
              HasSubstr("/events/4/decisions/height_map_columns/1 | run.json: "
                        "/events/4/decisions/height_map_columns/1: expected a height-map column "
                        "[column, row, top z]: indices from 0, m, got"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_columns", {{1.5, 2, 3.0}}}}), HasSubstr("/decisions/height_map_columns/0 |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_columns", {{1, 2, "3"}}}}), HasSubstr("/decisions/height_map_columns/0 |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_columns", {{1, 2}}}}), HasSubstr("/decisions/height_map_columns/0 |"));
  EXPECT_THAT(declared_error(dstar, {{"height_map_columns", 5}}), HasSubstr("/decisions/height_map_columns |"));
  const nlohmann::json gap = {{"gaps", 2}, {"nearest_range_m", 1.0}, {"route_heading_deg", 0.0}, {"goal_deg", 0.0}};
  EXPECT_THAT(declared_error(rover, {{"gap", with(gap, "gaps", -1)}}),
              HasSubstr("/events/4/decisions/gap/gaps | run.json: /events/4/decisions/gap/gaps: expected an integer "
                        "in [0, 2147483647], got"));
  EXPECT_THAT(declared_error(rover, {{"gap", with(gap, "route_heading_deg", "north")}}),
              HasSubstr("/decisions/gap/route_heading_deg |"));
  EXPECT_THAT(declared_error(rover, {{"gap", with(gap, "nearest_range_m", -1.0)}}), HasSubstr("/decisions/gap/nearest_range_m |"));
  // A chosen gap has its centre, heading and width together.
  EXPECT_THAT(declared_error(rover, {{"gap", with(gap, "gap_center_deg", 5.0)}}),
              HasSubstr("/events/4/decisions/gap | run.json: /events/4/decisions/gap: missing required key "
                        "\"gap_heading_deg\""));
  EXPECT_THAT(declared_error(rover, {{"gap", with(gap, "side", "left")}}), HasSubstr("/decisions/gap/side |"));
  nlohmann::json no_heading = gap;
  no_heading.erase("route_heading_deg");
  EXPECT_THAT(declared_error(rover, {{"gap", no_heading}}), HasSubstr("missing required key \"route_heading_deg\""));
  // Not an event at all.
  EXPECT_THROW(event_from_json({{"decisions", nlohmann::json::object()}}, "run.json", "/events/0"), InputError);
  EXPECT_THROW(events_from_json(nlohmann::json::object(), "run.json", "/events"), InputError);
}

TEST(Decisions, OwnMayNotTakeATypedFieldsName) {
  Decisions d;
  d.own = {{"avoiding", "maybe"}};
  EXPECT_THROW(decisions_to_json(d), std::invalid_argument);
  d.own = nlohmann::json::array();
  EXPECT_THROW(decisions_to_json(d), std::invalid_argument);
  d.own = nullptr;  // none
  EXPECT_EQ(decisions_to_json(d), nlohmann::json::object());
  d.own = {{"lidar_hits", nlohmann::json::array()}};
  EXPECT_THROW(decisions_to_json(d), std::invalid_argument);
  d.own = nullptr;
  d.replan = ReplanDecision{.details = {{"time_ms", 3.0}}};
  EXPECT_THROW(decisions_to_json(d), std::invalid_argument);
}

TEST(Decisions, RunRecordsWithInlineEventsReadBack) {
  // run.json of runs recorded before events.jsonl: an "events" array of the same events.
  const std::vector<PlannerEvent> events{{0.5, every_field()}, {1.0, {.avoiding = true}}};
  nlohmann::json inline_events = nlohmann::json::array();
  for (const PlannerEvent& e : events) inline_events.push_back(nlohmann::json::parse(event_line(e)));
  EXPECT_EQ(events_from_json(inline_events, "run.json", "/events"), events);
  // Integers where the writer has decimals, as a hand-written or older record may have them.
  const std::vector<PlannerEvent> read = events_from_json(
      nlohmann::json::parse(R"([{"time_s": 3, "decisions": {"planned_path": [[0, 0, 1], [2, 0, 1]]}}])"), "run.json",
      "/events");
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].time_s, 3.0);
  EXPECT_EQ(read[0].decisions.planned_path, (std::vector<Eigen::Vector3d>{{0, 0, 1}, {2, 0, 1}}));
  const Decisions grid = decisions_from_json(
      nlohmann::json::parse(R"({"height_map_grid": {"origin_m": [1, 2], "cell_size_m": 2, "columns": 3, "rows": 4}})"),
      "run.json", "/events/0/decisions");
  EXPECT_EQ(dstar_lite_3d_record().height_map_grid.get(grid.own),
            (HeightMapGrid{.origin_m = {1.0, 2.0}, .cell_size_m = 2.0, .columns = 3, .rows = 4}));
}

TEST(Decisions, BoundedAsRecorded) {
  // A path of 3 k points keeps 2048 of them, its ends included, and says so; the metrics read this.
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i < 3000; ++i) path.emplace_back(i, 0.0, 1.0);
  const Decisions bounded = bounded_decisions({.planned_path = path, .avoiding = true});
  ASSERT_TRUE(bounded.planned_path.has_value());
  ASSERT_EQ(bounded.planned_path->size(), kEventArrayMaxEntries);
  EXPECT_EQ(bounded.planned_path->front(), path.front());
  EXPECT_EQ(bounded.planned_path->back(), path.back());
  EXPECT_EQ(bounded.avoiding, true);
  EXPECT_EQ(bounded.own, (nlohmann::json{{"thinned", {{"/planned_path", 3000}}}}));
  EXPECT_TRUE(was_bounded(bounded));
  // So are a scan's hits and a height map's columns, typed as they were.
  std::vector<HeightMapColumn> columns;
  for (int i = 0; i < 5000; ++i) columns.push_back({i, 2 * i, 0.5 * i});
  Decisions many{.lidar_hits = hits(2049)};
  dstar_lite_3d_record().height_map_columns.set(many.own, columns);
  const Decisions mapped = bounded_decisions(many);
  ASSERT_EQ(mapped.lidar_hits.size(), kEventArrayMaxEntries);
  EXPECT_EQ(mapped.lidar_hits.front(), Eigen::Vector3d(0.0, 0.5, 1.0));
  EXPECT_EQ(mapped.lidar_hits.back(), Eigen::Vector3d(2048.0, 0.5, 1.0));
  const std::vector<HeightMapColumn> kept = dstar_lite_3d_record().height_map_columns.get(mapped.own).value();
  ASSERT_EQ(kept.size(), kEventArrayMaxEntries);
  EXPECT_EQ(kept.front(), columns.front());
  EXPECT_EQ(kept.back(), columns.back());
  EXPECT_EQ(mapped.own["thinned"], (nlohmann::json{{"/height_map_columns", 5000}, {"/lidar_hits", 2049}}));
  // Short ones are recorded as they are.
  const Decisions small = every_field();
  EXPECT_EQ(bounded_decisions(small), small);
  EXPECT_FALSE(was_bounded(small));
}

TEST(EventLog, ShortArraysAreKeptAsTheyAre) {
  nlohmann::json d = decisions_to_json({.reached_waypoints = {0}, .lidar_hits = hits(kEventArrayMaxEntries)});
  const nlohmann::json before = d;
  EXPECT_FALSE(bound_decisions(d));
  EXPECT_EQ(d, before);
}

TEST(EventLog, LongArraysKeepEvenlySpacedEntriesWithTheirEnds) {
  const std::size_t n = 10 * kEventArrayMaxEntries + 7;
  nlohmann::json d = decisions_to_json(
      {.replan = ReplanDecision{.index = 3, .details = {{"path", points(n)}}}, .lidar_hits = hits(n)});
  EXPECT_TRUE(bound_decisions(d));
  ASSERT_EQ(d["lidar_hits"].size(), kEventArrayMaxEntries);
  EXPECT_EQ(d["lidar_hits"].front()[0], 0.0);
  EXPECT_EQ(d["lidar_hits"].back()[0], static_cast<double>(n - 1));
  // Strictly increasing, spaced by about (n - 1) / (k - 1) = 10.0 entries.
  for (std::size_t i = 1; i < kEventArrayMaxEntries; ++i) {
    const double step = d["lidar_hits"][i][0].get<double>() - d["lidar_hits"][i - 1][0].get<double>();
    EXPECT_GE(step, 10.0);
    EXPECT_LE(step, 11.0);
  }
  const Decisions back = decisions_from_json(d, "f", "");
  EXPECT_EQ(back.replan.value().details["path"].size(), kEventArrayMaxEntries);
  EXPECT_EQ(back.lidar_hits.size(), kEventArrayMaxEntries);
  EXPECT_EQ(back.replan.value().index, 3);
  EXPECT_EQ(d["thinned"], (nlohmann::json{{"/lidar_hits", n}, {"/replan/path", n}}));
}

TEST(EventLog, AnOversizedEventDropsItsLargestKeysFirst) {
  // Strings are not thinned: 300 KiB of text leaves the line over its limit.
  nlohmann::json d = decisions_to_json(
      {.reached_waypoints = {1}, .avoiding = true, .own = {{"note", std::string(300u << 10, 'x')}}});
  EXPECT_TRUE(bound_decisions(d));
  EXPECT_FALSE(d.contains("note"));
  EXPECT_EQ(d["omitted"]["note"], (300u << 10) + 2);  // its JSON text, quotes included
  const Decisions back = decisions_from_json(d, "f", "");
  EXPECT_EQ(back.avoiding, true);
  EXPECT_EQ(back.reached_waypoints, std::vector<int>{1});
  EXPECT_LE(event_line({1.0, back}).size(), kEventLineMaxBytes);
}

TEST(EventLog, LinesAreBoundedWhateverThePlannerDecides) {
  // Wide rows of a nested array: each row is short enough, together they are not.
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 100; ++r) rows.push_back(points(kEventArrayMaxEntries));
  nlohmann::json d = {{"rows", rows}, {"index", 1}};
  bound_decisions(d);
  EXPECT_LE(event_line({123.25, decisions_from_json(d, "f", "")}).size(), kEventLineMaxBytes);
  EXPECT_EQ(d["index"], 1);
}

TEST(EventLog, JsonLinesReadBackAsWritten) {
  const auto file = std::filesystem::temp_directory_path() / "campo_event_log_test.jsonl";
  const std::vector<PlannerEvent> events{{0.5, {.planned_waypoint = Eigen::Vector3d(1.0, 2.0, 3.0)}},
                                         {1.0, {.avoiding = true, .own = {{"wall_following", {{"side", "left"}}}}}},
                                         {1.5, every_field()}};
  std::ofstream(file, std::ios::binary) << events_jsonl(events);
  const std::vector<PlannerEvent> back = read_events_jsonl(file);
  EXPECT_EQ(back, events);
  // The planners' own fields read back through their declarations as they were written.
  EXPECT_EQ(rover_route_record().gap.get(back[2].decisions.own)->chosen->width_m, 1.75);
  EXPECT_EQ(dstar_lite_3d_record().height_map_columns.get(back[2].decisions.own),
            (std::vector<HeightMapColumn>{{2, 0, 14.0}, {99, 79, -7.0}}));
  EXPECT_NO_THROW(dstar_lite_3d_record().description.decisions.check(
      nlohmann::json{{"height_map_grid", back[2].decisions.own["height_map_grid"]}}, file.string(), ""));
  // A line past the limit is refused, naming the file and line, before it is read whole.
  std::ofstream(file, std::ios::binary) << events_jsonl(events) << std::string(kEventLineMaxBytes + 1, ' ') << "\n";
  try {
    read_events_jsonl(file);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string() + ": line 4: expected at most 262144 bytes a line"));
  }
  std::ofstream(file, std::ios::binary) << "{\"decisions\": {}}\n";
  EXPECT_THROW(read_events_jsonl(file), InputError);
  // A malformed decision names its line and key.
  std::ofstream(file, std::ios::binary) << events_jsonl(events) << R"({"time_s": 2, "decisions": {"avoiding": "yes"}})"
                                        << "\n";
  try {
    read_events_jsonl(file);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string() + " line 4");
    EXPECT_EQ(e.pointer(), "/decisions/avoiding");
  }
  std::ofstream(file, std::ios::binary) << events_jsonl(events)
                                        << R"({"time_s": 2, "decisions": {"height_map_columns": [[1, 2, 3.5], [4, 5]]}})"
                                        << "\n";
  // Read back as recorded; its declaration refuses it, naming the key.
  const std::vector<PlannerEvent> malformed = read_events_jsonl(file);
  try {
    (void)dstar_lite_3d_record().height_map_columns.get(malformed.back().decisions.own, file.string() + " line 4",
                                                        "/decisions");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string() + " line 4");
    EXPECT_EQ(e.pointer(), "/decisions/height_map_columns/1");
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace campo
