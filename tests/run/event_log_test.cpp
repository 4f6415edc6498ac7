// The planner decisions of a run are bounded as they are recorded, and
// events.jsonl reads back what was written.
#include "run/event_log.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

nlohmann::json points(std::size_t n) {
  nlohmann::json p = nlohmann::json::array();
  for (std::size_t i = 0; i < n; ++i) p.push_back({static_cast<double>(i), 0.5, 1.0});
  return p;
}

TEST(EventLog, ShortArraysAreKeptAsTheyAre) {
  nlohmann::json d = {{"lidar_hits", points(kEventArrayMaxEntries)}, {"reached_waypoints", {0}}};
  const nlohmann::json before = d;
  EXPECT_FALSE(bound_decisions(d));
  EXPECT_EQ(d, before);
}

TEST(EventLog, LongArraysKeepEvenlySpacedEntriesWithTheirEnds) {
  const std::size_t n = 10 * kEventArrayMaxEntries + 7;
  nlohmann::json d = {{"lidar_hits", points(n)}, {"replan", {{"index", 3}, {"path", points(n)}}}};
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
  EXPECT_EQ(d["replan"]["path"].size(), kEventArrayMaxEntries);
  EXPECT_EQ(d["replan"]["index"], 3);
  EXPECT_EQ(d["thinned"], (nlohmann::json{{"/lidar_hits", n}, {"/replan/path", n}}));
}

TEST(EventLog, AnOversizedEventDropsItsLargestKeysFirst) {
  // Strings are not thinned: 300 KiB of text leaves the line over its limit.
  nlohmann::json d = {{"note", std::string(300u << 10, 'x')}, {"avoiding", true}, {"reached_waypoints", {1}}};
  EXPECT_TRUE(bound_decisions(d));
  EXPECT_FALSE(d.contains("note"));
  EXPECT_EQ(d["avoiding"], true);
  EXPECT_EQ(d["reached_waypoints"], nlohmann::json({1}));
  EXPECT_EQ(d["omitted"]["note"], (300u << 10) + 2);  // its JSON text, quotes included
  EXPECT_LE(event_line({1.0, d}).size(), kEventLineMaxBytes);
}

TEST(EventLog, LinesAreBoundedWhateverThePlannerDecides) {
  // Wide rows of a nested array: each row is short enough, together they are not.
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 100; ++r) rows.push_back(points(kEventArrayMaxEntries));
  nlohmann::json d = {{"rows", rows}, {"index", 1}};
  bound_decisions(d);
  EXPECT_LE(event_line({123.25, d}).size(), kEventLineMaxBytes);
  EXPECT_EQ(d["index"], 1);
}

TEST(EventLog, JsonLinesReadBackAsWritten) {
  const auto file = std::filesystem::temp_directory_path() / "campo_event_log_test.jsonl";
  const std::vector<PlannerEvent> events{{0.5, {{"planned_waypoint", {1.0, 2.0, 3.0}}}},
                                         {1.0, {{"avoiding", true}, {"gap", {{"side", "left"}}}}}};
  std::ofstream(file, std::ios::binary) << events_jsonl(events);
  const nlohmann::json back = read_events_jsonl(file);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0]["time_s"], 0.5);
  EXPECT_EQ(back[1]["decisions"], events[1].decisions);
  // A line past the limit is refused, naming the file and line, before it is read whole.
  std::ofstream(file, std::ios::binary) << events_jsonl(events) << std::string(kEventLineMaxBytes + 1, ' ') << "\n";
  try {
    read_events_jsonl(file);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string() + ": line 3: expected at most 262144 bytes a line"));
  }
  std::ofstream(file, std::ios::binary) << "{\"decisions\": {}}\n";
  EXPECT_THROW(read_events_jsonl(file), InputError);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace campo
