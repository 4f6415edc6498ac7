// Seed 001's criteria on measured-like data and on small maps searched by
// campo's own A*: every verdict each can give, failure included, through
// judge() as the report uses them. Expected optima are counted by hand.
#include "reproduce/seed_001_criteria.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "reproduce/report.hpp"

namespace campo {
namespace {

Verdict verdict_of(const Judgement& j) { return judge(ClaimKind::thesis_result, j.holds, j.has_departures, j.cause_known); }

// A 10 x 10 map, 4 levels 7 m apart, the ground at level 0: a 7 m block blocks levels 0 and 1.
TrueMap small_map(std::vector<GridBlock> blocks) {
  TrueMap map;
  map.cols = map.rows = 10;
  map.levels = 4;
  map.ground_level = 0;
  map.blocks = std::move(blocks);
  return map;
}

TEST(Seed001Criteria, RowsMirroredAndBlocksBounded) {
  EXPECT_EQ(mirror_rows({49, 50, 46, 49, 35}, 100), (GridBlock{51, 52, 46, 49, 35}));
  EXPECT_EQ(mirror_rows(mirror_rows({20, 22, 1, 100, 30}, 100), 100), (GridBlock{20, 22, 1, 100, 30}));
  EXPECT_EQ(bounding_block({{24, 27, 16, 28, 35}, {39, 42, 6, 18, 35}, {69, 72, 6, 18, 30}}),
            (GridBlock{24, 72, 6, 28, 35}));
}

TEST(Seed001Criteria, ThesisLevelOfAHeight) {
  const TrueMap map;  // 7 m levels, take-off ground at level 2 (001 §4.2.4)
  EXPECT_EQ(level_of_height(map, 35.0), 7);  // above the 28 m lap (level 6), below 42 m (level 8)
  EXPECT_EQ(level_of_height(map, 30.0), 6);  // round(4.29) + 2: the wall blocks the 28 m lap
  EXPECT_EQ(level_of_height(map, 28.0), 6);
  EXPECT_EQ(level_of_height(map, 15.0), 4);
  EXPECT_EQ(level_of_height(map, 10.0), 3);  // below the 28 m lap: no obstacle to it
}

TEST(Seed001Criteria, PlaneAndVolumeOptima) {
  // A wall across row 5, columns 1-8, 7 m high; a gap at columns 9-10. From row 1 to row 10 along column 5 on level 1.
  const TrueMap map = small_map({{5, 5, 1, 8, 7.0}});
  const MapCell from{1, 5, 1}, to{10, 5, 1};
  // In the plane: 4 columns east to the gap, 9 rows, 4 back: 17 moves of 1.5 m.
  const RouteOptimum plane = route_optimum(map, grid::Connectivity::four, from, to, 1.0);
  ASSERT_TRUE(plane.found);
  EXPECT_EQ(plane.links, 17);
  EXPECT_NEAR(plane.cost_cells, 17.0, 1e-9);
  EXPECT_NEAR(plane.length_m, 25.5, 1e-9);
  EXPECT_FALSE(plane.leaves_level);
  // Every link the same cost (001): over the wall, up one level, 9 rows, down: 11 links, 9 x 1.5 + 2 x 7 m.
  const RouteOptimum equal = route_optimum(map, grid::Connectivity::six, from, to, 1.0);
  ASSERT_TRUE(equal.found);
  EXPECT_EQ(equal.links, 11);
  EXPECT_NEAR(equal.length_m, 27.5, 1e-9);
  EXPECT_TRUE(equal.leaves_level);
  // A climb costing its length (7 / 1.5 cells): 9 + 2 x 4.67 = 18.3 cells > 17, so round the wall.
  const RouteOptimum metric = route_optimum(map, grid::Connectivity::six, from, to, 7.0 / 1.5);
  ASSERT_TRUE(metric.found);
  EXPECT_NEAR(metric.length_m, 25.5, 1e-9);
  EXPECT_FALSE(metric.leaves_level);
  // Closing the gap in the plane leaves no route there.
  EXPECT_FALSE(route_optimum(map, grid::Connectivity::four, from, to, 1.0, {{5, 5, 9, 10, 0.0}}).found);
  // Diagonals: from (1, 1) to (4, 4) on an empty map, 3 diagonal moves.
  const RouteOptimum diagonal = route_optimum(small_map({}), grid::Connectivity::eight, {1, 1, 1}, {4, 4, 1}, 1.0);
  EXPECT_EQ(diagonal.links, 3);
  EXPECT_NEAR(diagonal.length_m, 3 * 1.5 * std::sqrt(2.0), 1e-9);
}

TEST(Seed001Criteria, RouteThroughAnArea) {
  const TrueMap map = small_map({});
  // From (1, 1) to (1, 5) through (3, 3): 2 + 2 moves there and 2 + 2 back, against 4 straight.
  const RouteOptimum through = route_through(map, grid::Connectivity::four, {1, 1, 1}, {1, 5, 1}, 1.0, {3, 3, 3, 3});
  ASSERT_TRUE(through.found);
  EXPECT_NEAR(through.cost_cells, 8.0, 1e-9);
  EXPECT_EQ(through.links, 8);
  EXPECT_EQ(through.path.size(), 9u);
  EXPECT_NEAR(route_optimum(map, grid::Connectivity::four, {1, 1, 1}, {1, 5, 1}, 1.0).cost_cells, 4.0, 1e-9);
}

// A leg south along column 3 meets a block at row 5; a slot at columns 5-6 between it and a block at columns 7-8.
SlotReading slot_reading(const std::string& name, int west_block_first_col) {
  const TrueMap map = small_map({{5, 5, west_block_first_col, 4, 7.0}, {5, 5, 7, 8, 7.0}});
  const MapCell from{10, 3, 1}, to{1, 3, 1};
  return {name, route_optimum(map, grid::Connectivity::four, from, to, 1.0),
          route_through(map, grid::Connectivity::four, from, to, 1.0, {5, 5, 5, 6})};
}

TEST(Seed001Criteria, SlotVerdicts) {
  // Block at columns 3-4: round it at column 2 costs 2 moves, through the slot 4: the slot is no shortest way.
  const SlotReading longer = slot_reading("rows from the south edge", 3);
  EXPECT_NEAR(longer.optimum.cost_cells, 11.0, 1e-9);
  EXPECT_NEAR(longer.through_slot.cost_cells, 13.0, 1e-9);
  EXPECT_FALSE(longer.slot_on_shortest_route());
  // Block at columns 1-4 (the map's west edge): the slot is the shortest way.
  const SlotReading shorter = slot_reading("rows from the north edge", 1);
  EXPECT_NEAR(shorter.optimum.cost_cells, 13.0, 1e-9);
  EXPECT_TRUE(shorter.slot_on_shortest_route());

  SlotMeasure m;
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::not_reproduced);  // nothing run
  m.passed_thesis_setting = true;
  m.passed_bundled = false;
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::reproduced);
  m.passed_thesis_setting = false;
  m.passed_bundled = true;
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::reproduced_with_departures);
  m.passed_bundled = false;
  m.passed_other_reading = true;
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::reproduced_with_departures);
  // No run passes: settled only when the slot is no shortest way under every reading computed.
  m.passed_other_reading = false;
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::not_reproduced);  // no reading computed
  m.readings = {longer, longer};
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::deviates);
  m.readings = {longer, shorter};
  EXPECT_EQ(verdict_of(judge_slot(m)), Verdict::not_reproduced);
}

TEST(Seed001Criteria, WithTheThesisSettingOrOnlyWithDepartures) {
  EXPECT_EQ(verdict_of(judge_with_thesis_setting(true, false, false)), Verdict::reproduced);
  EXPECT_EQ(verdict_of(judge_with_thesis_setting(false, true, false)), Verdict::reproduced_with_departures);
  EXPECT_EQ(verdict_of(judge_with_thesis_setting(std::nullopt, true, false)), Verdict::reproduced_with_departures);
  EXPECT_EQ(verdict_of(judge_with_thesis_setting(false, false, true)), Verdict::deviates);
  EXPECT_EQ(verdict_of(judge_with_thesis_setting(false, false, false)), Verdict::not_reproduced);
  EXPECT_EQ(verdict_of(judge_with_thesis_setting(std::nullopt, std::nullopt, true)), Verdict::not_reproduced);
}

TEST(Seed001Criteria, PassingSides) {
  const std::vector<Rect> buildings{{0.0, 10.0, 0.0, 5.0}, {5.0, 15.0, 10.0, 15.0}, {0.0, 10.0, 30.0, 35.0}};
  // West of the first (mean x 2 < 5), east of the second (mean x 12 > 10), never in the third's span.
  const std::vector<Eigen::Vector2d> track{{2.0, 1.0}, {2.0, 4.0}, {8.0, 7.0}, {12.0, 11.0}, {12.0, 14.0}, {6.0, 20.0}};
  const std::vector<Side> sides = passing_sides(track, buildings);
  ASSERT_EQ(sides.size(), 3u);
  EXPECT_EQ(sides[0], Side::west);
  EXPECT_EQ(sides[1], Side::east);
  EXPECT_EQ(sides[2], Side::none);
  const Rect f = footprint({24, 27, 16, 28, 35}, 1.5);
  EXPECT_DOUBLE_EQ(f.x_min, 22.5);
  EXPECT_DOUBLE_EQ(f.x_max, 42.0);
  EXPECT_DOUBLE_EQ(f.y_min, 34.5);
  EXPECT_DOUBLE_EQ(f.y_max, 40.5);
}

TEST(Seed001Criteria, WeaveVerdicts) {
  const std::vector<Side> between{Side::east, Side::west, Side::east, Side::west};
  const std::vector<Side> outside(4, Side::west);
  const double round_outside_m = 145.5;  // 97 moves of 1.5 m round the west of four staggered buildings
  // Between the buildings, at altitude, 137 m: shorter than round the outside.
  EXPECT_EQ(verdict_of({weave_holds({false, between, 137.0}, round_outside_m), false, false}), Verdict::reproduced);
  EXPECT_EQ(verdict_of({weave_holds({false, between, 137.0}, round_outside_m), true, false}),
            Verdict::reproduced_with_departures);
  // Round the outside (even when shorter than the bound, as an 8-connected flight may be), over them, or too long.
  EXPECT_EQ(weave_holds({false, outside, 133.0}, round_outside_m), false);
  EXPECT_EQ(weave_holds({true, between, 137.0}, round_outside_m), false);
  EXPECT_EQ(weave_holds({false, between, 150.0}, round_outside_m), false);
  EXPECT_EQ(verdict_of({weave_holds({true, between, 137.0}, round_outside_m), false, true}), Verdict::deviates);
  EXPECT_EQ(verdict_of({weave_holds({true, between, 137.0}, round_outside_m), false, false}), Verdict::not_reproduced);
  // Nothing flown past the buildings, or no outside route: not measured.
  EXPECT_EQ(weave_holds({false, std::vector<Side>(4, Side::none), 137.0}, round_outside_m), std::nullopt);
  EXPECT_EQ(weave_holds({false, between, 137.0}, std::nullopt), std::nullopt);
}

TEST(Seed001Criteria, WallVerdicts) {
  EXPECT_EQ(wall_holds(true, 0.46, 1.5), true);
  EXPECT_EQ(verdict_of({wall_holds(true, 0.46, 1.5), false, false}), Verdict::reproduced);
  EXPECT_EQ(wall_holds(true, 19.0, 1.5), false);       // along the wall first
  EXPECT_EQ(wall_holds(true, std::nullopt, 1.5), false);  // never climbed
  EXPECT_EQ(wall_holds(false, 0.4, 1.5), false);        // collided or stopped short
  EXPECT_EQ(verdict_of({wall_holds(true, 19.0, 1.5), false, false}), Verdict::not_reproduced);
  EXPECT_EQ(wall_holds(std::nullopt, 0.4, 1.5), std::nullopt);
}

TEST(Seed001Criteria, SweepCountsAndVerdicts) {
  std::vector<SettingBehaviours> settings{
      {"six", 1.0, 45.0, false, false, true},
      {"twenty_six", 2.5, 35.0, false, true, true},
      {"twenty_six", 1.0, 45.0, std::nullopt, std::nullopt, std::nullopt},  // failed runs
      {"six", 4.67, 45.0, true, true, true},
  };
  const BehaviourCounts c = count_behaviours(settings);
  EXPECT_EQ(c.settings, 4);
  EXPECT_EQ(c.slot, 1);
  EXPECT_EQ(c.slot_n, 3);
  EXPECT_EQ(c.weave, 2);
  EXPECT_EQ(c.wall, 3);
  EXPECT_EQ(c.all, 1);
  const SettingBehaviours* thesis = find_setting(settings, "six", 1.0, 45.0);
  ASSERT_NE(thesis, nullptr);
  EXPECT_EQ(find_setting(settings, "six", 1.0, 35.0), nullptr);
  // The thesis's setting misses the slot and the weave: settled when both causes are computed.
  EXPECT_EQ(verdict_of(judge_sweep(thesis, true, true)), Verdict::deviates);
  EXPECT_EQ(verdict_of(judge_sweep(thesis, true, false)), Verdict::not_reproduced);
  EXPECT_EQ(verdict_of(judge_sweep(find_setting(settings, "six", 4.67, 45.0), false, false)), Verdict::reproduced);
  EXPECT_EQ(verdict_of(judge_sweep(nullptr, true, true)), Verdict::not_reproduced);
  EXPECT_EQ(verdict_of(judge_sweep(find_setting(settings, "twenty_six", 1.0, 45.0), true, true)),
            Verdict::not_reproduced);
  // A missed wall has no computed cause.
  settings[0].wall = false;
  EXPECT_EQ(verdict_of(judge_sweep(&settings[0], true, true)), Verdict::not_reproduced);
}

TEST(Seed001Criteria, LapsCoincideWithTheNominalRoute) {
  const std::vector<Eigen::Vector2d> nominal{{0.0, 0.0}, {0.0, 100.0}, {50.0, 100.0}};
  EXPECT_NEAR(max_offset_m({{0.3, 10.0}, {-0.2, 50.0}, {20.0, 100.9}}, nominal), 0.9, 1e-12);
  EXPECT_DOUBLE_EQ(max_offset_m({}, nominal), 0.0);
  EXPECT_EQ(verdict_of({laps_coincide({0.9, 0.4, 0.5}, 1.5), false, false}), Verdict::reproduced);
  EXPECT_EQ(laps_coincide({0.9, 3.0}, 1.5), false);
  EXPECT_EQ(laps_coincide({}, 1.5), std::nullopt);
}

TEST(Seed001Criteria, LowBlocksIgnored) {
  // The 10 m block crossed at altitude; the 15 m block off the route.
  EXPECT_EQ(low_blocks_ignored({{120, 130, 0.3}, {0, 0, 0.0}}, 2.0), true);
  EXPECT_EQ(low_blocks_ignored({{120, 130, 7.0}, {0, 0, 0.0}}, 2.0), false);  // climbed over it
  EXPECT_EQ(low_blocks_ignored({{0, 130, 0.0}}, 2.0), false);                 // went round it
  EXPECT_EQ(low_blocks_ignored({{0, 0, 0.0}}, 2.0), std::nullopt);            // the route crosses none
}

TEST(Seed001Criteria, MoversNotAvoided) {
  std::vector<MoverRun> runs{{false, 0.3}, {true, 0.2}, {false, 0.4}};
  EXPECT_EQ(verdict_of({movers_not_avoided(runs, 1.5), false, false}), Verdict::reproduced);
  runs[0].max_offset_m = 4.0;  // one run turned away from its route
  EXPECT_EQ(movers_not_avoided(runs, 1.5), false);
  EXPECT_EQ(verdict_of({movers_not_avoided(runs, 1.5), false, true}), Verdict::deviates);
  EXPECT_EQ(movers_not_avoided({{false, 0.3}}, 1.5), false);  // nothing ever hit it
  EXPECT_EQ(movers_not_avoided({}, 1.5), std::nullopt);
}

TEST(Seed001Criteria, BridgeFlownOver) {
  EXPECT_EQ(bridge_flown_over(true, 27.0, 28.0, 22.0), true);
  EXPECT_EQ(bridge_flown_over(true, 13.0, 14.0, 22.0), false);  // under the deck
  EXPECT_EQ(bridge_flown_over(false, 27.0, 28.0, 22.0), false);
  EXPECT_EQ(bridge_flown_over(true, 1.0, 0.0, 22.0), std::nullopt);  // never crossed its span
}

}  // namespace
}  // namespace campo
