// Runs `campo plan` as a user would: the one-line result, the scenario CSV,
// and exit code 2 with a precise message on bad input; for the grid
// searches, RRT* and Dubins paths.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using campo::testing::Result;
using campo::testing::lines_of;
using campo::testing::slurp;

const std::string kData = std::string(CAMPO_SOURCE_DIR) + "/tests/data/movingai/";

// Runs `campo plan ARGS`.
class PlanCli : public campo::testing::CliTest {
 protected:
  Result plan(const std::string& args) const { return campo("plan " + args); }
  // A 5 x 3 map whose middle column is a wall: no path from left to right.
  std::string walled_map() const { return write("walled.map", "type octile\nheight 3\nwidth 5\nmap\n..@..\n..@..\n..@..\n"); }
};

TEST_F(PlanCli, OneProblemPrintsOneLine) {
  // arena.map.scen line 4: (1,13) -> (4,12), optimal 3.41421.
  for (const char* planner : {"astar", "dstar_lite"}) {
    const Result r = plan(std::string("--planner ") + planner + " --map " + kData + "arena.map --start 1,13 --goal 4,12");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::regex_match(r.out, std::regex("cost=3\\.41421356 steps=3 expansions=[0-9]+ time_ms=[0-9]+\\.[0-9]{3}\n")))
        << r.out;
  }
}

TEST_F(PlanCli, NoPathPrintsCostMinusOne) {
  const std::string map = walled_map();
  const Result r = plan("--map " + map + " --start 0,0 --goal 4,2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::StartsWith("cost=-1 steps=0 expansions=6 "));
}

TEST_F(PlanCli, ScenarioPrintsCsvWithEveryProblemMatching) {
  for (const char* planner : {"astar", "dstar_lite"}) {
    const Result r = plan(std::string("--planner ") + planner + " --map " + kData + "arena.map --scen " + kData +
                           "arena.map.scen");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto rows = lines_of(r.out);
    ASSERT_EQ(rows.size(), 161u);
    EXPECT_EQ(rows[0], "index,start_x,start_y,goal_x,goal_y,optimal,cost,match");
    EXPECT_EQ(rows[3], "2,1,13,4,12,3.41421000,3.41421356,1");
    for (std::size_t i = 1; i < rows.size(); ++i) EXPECT_THAT(rows[i], ::testing::EndsWith(",1")) << rows[i];
    EXPECT_THAT(r.err, HasSubstr("160 of 160 problems at the optimal length"));
  }
}

TEST_F(PlanCli, AWrongOptimalLengthIsAMismatch) {
  const std::string scen = write("wrong.scen", "version 1\n0\tarena.map\t49\t49\t1\t13\t4\t12\t3.5\n");
  const Result r = plan("--map " + kData + "arena.map --scen " + scen);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lines_of(r.out).at(1), "0,1,13,4,12,3.50000000,3.41421356,0");
  EXPECT_THAT(r.err, HasSubstr("0 of 1 problems"));
}

TEST_F(PlanCli, BadInputExitsTwoNamingTheProblem) {
  const std::string arena = " --map " + kData + "arena.map";
  struct Case {
    std::string args;
    std::string message;
  };
  const std::string bad_map = write("bad.map", "type octile\nheight 2\nwidth 2\nmap\n..\n.?\n");
  const std::string bad_scen = write("bad.scen", "version 1\n0\tarena.map\t49\t49\t1\t13\t4\n");
  for (const Case& c : {
           Case{arena + " --start 1x13 --goal 4,12", "--start: expected X,Y with 0 <= X < 49 and 0 <= Y < 49"},
           Case{arena + " --start 1,13 --goal 49,12", "--goal: expected X,Y"},
           Case{arena + " --start 0,0 --goal 4,12", "--start: expected a passable cell, got 0,0, which the map blocks"},
           Case{arena + " --start 1,13", "--goal: expected both --start X,Y and --goal X,Y"},
           Case{arena, "expected either --start X,Y and --goal X,Y, or --scen FILE.scen"},
           Case{" --map " + bad_map + " --start 0,0 --goal 1,0", "bad.map: line 6: column 1: expected one of"},
           Case{arena + " --scen " + bad_scen, "bad.scen: line 2: expected 9 fields"},
           Case{" --map " + kData + "missing.map --start 0,0 --goal 1,0", "missing.map: cannot read the file"},
           Case{arena + " --planner rrt --start 1,13 --goal 4,12", "--planner"},
       }) {
    const Result r = plan(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(r.out, "") << c.args;
  }
}

TEST_F(PlanCli, HelpExplainsFormatAndOutput) {
  const Result r = plan("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text : {"type octile", "cost=C steps=S expansions=E time_ms=T", "-1 when no path",
                           "index,start_x,start_y,goal_x,goal_y,optimal,cost,match", "no corner cutting", "dstar_lite",
                           "--planner rrt_star --map FILE.map", "cost=C steps=S iterations=I first_solution=K time_ms=T",
                           "at most 10 % longer", "--planner dubins --from X,Y,HEADING --to X,Y,HEADING --radius R",
                           "word=LSL length=L segments=A,B,C", "counter-clockwise from +x",
                           "Options that do not apply to the planner are errors", "--time-limit S",
                           "at most 10000000 iterations", "bar with ETA"}) {
    EXPECT_THAT(r.out, HasSubstr(text));
  }
}

// ---- dubins ----

TEST_F(PlanCli, DubinsUTurnIsOneRightHalfCircle) {
  // Heading north (90 degrees) at the origin, turning right (clockwise) about
  // (2, 0) with radius 2 reaches (4, 0) heading south after half a circle:
  // 2 pi m of R, no straight, no second arc.
  const Result r = plan("--planner dubins --from 0,0,90 --to 4,0,-90 --radius 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "word=RSR length=6.283185 segments=6.283185,0.000000,0.000000\n");
}

// Issue 16: the extremes of the accepted ranges plan (exit 0): a straight
// run of 2e7 m along x, east to east, radius 1e-6 m: word LSL with zero arcs.
TEST_F(PlanCli, DubinsAtTheLimitsOfItsRanges) {
  const Result r = plan("--planner dubins --from -1e7,0,0 --to 1e7,0,0 --radius 1e-6");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "word=LSL length=20000000.000000 segments=0.000000,20000000.000000,0.000000\n");
  EXPECT_EQ(plan("--planner dubins --from 0,0,1e6 --to 4,0,-1e6 --radius 1e7").exit_code, 0);
}

TEST_F(PlanCli, DubinsRowSwitchIsArcStraightArc) {
  // North at the origin to south at (10, 0), radius 2: a quarter turn right
  // about (2, 0) to (2, 2) heading east, 6 m straight to (8, 2), a quarter
  // turn right about (8, 0): pi + 6 + pi.
  const Result r = plan("--planner dubins --from 0,0,90 --to 10,0,-90 --radius 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "word=RSR length=12.283185 segments=3.141593,6.000000,3.141593\n");
  // Heading east to (6, 4) heading west: 6 m straight under the left circle
  // about (6, 2), then half of it.
  EXPECT_EQ(plan("--planner dubins --from 0,0,0 --to 6,4,180 --radius 2").out,
            "word=LSL length=12.283185 segments=0.000000,6.000000,6.283185\n");
}

TEST_F(PlanCli, DubinsStraightRunIsLslWithZeroArcs) {
  const Result r = plan("--planner dubins --from 1.5,-2,0 --to 11.5,-2,0 --radius 1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "word=LSL length=10.000000 segments=0.000000,10.000000,0.000000\n");
}

// ---- rrt_star ----

// "cost=C steps=S iterations=I first_solution=K time_ms=T" -> C, or NaN.
double rrt_cost(const std::string& line) {
  std::smatch m;
  if (!std::regex_match(line, m,
                        std::regex("cost=(-1|[0-9]+\\.[0-9]{8}) steps=[0-9]+ iterations=[0-9]+ "
                                   "first_solution=(-1|[0-9]+) time_ms=[0-9]+\\.[0-9]{3}\n"))) {
    return std::nan("");
  }
  return std::stod(m[1]);
}

std::string without_time(const std::string& line) { return line.substr(0, line.find(" time_ms=")); }

TEST_F(PlanCli, RrtStarSolvesAnArenaProblemNearTheOptimum) {
  // The longest arena problem (the one bench/rover_global_bench.cpp runs).
  const std::string problem = " --map " + kData + "arena.map --start 1,7 --goal 47,46";
  const Result astar = plan("--planner astar" + problem);
  ASSERT_EQ(astar.exit_code, 0) << astar.err;
  const double optimum = std::stod(astar.out.substr(5));
  EXPECT_NEAR(optimum, 62.15432893, 1e-8);

  const Result r = plan("--planner rrt_star" + problem);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::StartsWith("cost=")) << r.out;
  EXPECT_THAT(r.out, HasSubstr(" iterations=20000 "));
  const double cost = rrt_cost(r.out);
  ASSERT_FALSE(std::isnan(cost)) << r.out;
  // Any-angle paths may cut below the 8-connected optimum, never below the
  // straight line between the two cell centres.
  EXPECT_GE(cost, std::hypot(46.0, 39.0));
  EXPECT_LE(cost, 1.15 * optimum);

  // Deterministic for a seed: the same line but for the time.
  const Result again = plan("--planner rrt_star" + problem);
  EXPECT_EQ(without_time(again.out), without_time(r.out));
  const Result seeded = plan("--planner rrt_star --seed 0 --iterations 20000 --step 5" + problem);
  EXPECT_EQ(without_time(seeded.out), without_time(r.out));
  // Another seed, another tree (its line may differ), still a good path.
  const Result other = plan("--planner rrt_star --seed 7" + problem);
  EXPECT_EQ(other.exit_code, 0) << other.err;
  const double other_cost = rrt_cost(other.out);
  ASSERT_FALSE(std::isnan(other_cost)) << other.out;
  EXPECT_GE(other_cost, std::hypot(46.0, 39.0));
  EXPECT_LE(other_cost, 1.15 * optimum);
}

TEST_F(PlanCli, RrtStarWithoutAPathPrintsCostMinusOne) {
  const std::string map = walled_map();
  const Result r = plan("--planner rrt_star --map " + map + " --start 0,0 --goal 4,2 --iterations 100");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::StartsWith("cost=-1 steps=0 iterations=100 first_solution=-1 time_ms="));
}

TEST_F(PlanCli, RrtStarScenarioMatchesWithinTenPercent) {
  // Arena problems 0 to 3; in problem 3 the no-corner-cutting rule makes the
  // grid path 3.41421 long while RRT* passes two blocked cells at their
  // corners (2.83): shorter is a match. A file optimum of 2.5 makes the
  // same path more than 10 % too long.
  const std::string scen = write("four.scen",
                                 "version 1\n"
                                 "0\tarena.map\t49\t49\t1\t11\t1\t12\t1\n"
                                 "0\tarena.map\t49\t49\t1\t12\t1\t10\t2\n"
                                 "0\tarena.map\t49\t49\t1\t13\t4\t12\t3.41421\n"
                                 "0\tarena.map\t49\t49\t1\t3\t3\t1\t3.41421\n");
  const Result r = plan("--planner rrt_star --iterations 5000 --map " + kData + "arena.map --scen " + scen);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines_of(r.out);
  ASSERT_EQ(rows.size(), 5u) << r.out;
  EXPECT_EQ(rows[0], "index,start_x,start_y,goal_x,goal_y,optimal,cost,match");
  EXPECT_EQ(rows[1], "0,1,11,1,12,1.00000000,1.00000000,1");
  EXPECT_EQ(rows[2], "1,1,12,1,10,2.00000000,2.00000000,1");
  EXPECT_THAT(rows[3], ::testing::StartsWith("2,1,13,4,12,3.41421000,3.16"));  // the straight line, sqrt(10)
  EXPECT_THAT(rows[4], ::testing::MatchesRegex("3,1,3,3,1,3\\.41421000,2\\.8[0-9]+,1"));
  EXPECT_THAT(r.err, HasSubstr("4 of 4 problems at most 10 % longer than the optimal length (rrt_star, "));

  const std::string tight = write("tight.scen", "version 1\n0\tarena.map\t49\t49\t1\t3\t3\t1\t2.5\n");
  const Result mismatch = plan("--planner rrt_star --iterations 5000 --map " + kData + "arena.map --scen " + tight);
  EXPECT_EQ(mismatch.exit_code, 1);
  EXPECT_THAT(lines_of(mismatch.out).at(1), ::testing::MatchesRegex("0,1,3,3,1,2\\.50000000,2\\.8[0-9]+,0"));
  EXPECT_THAT(mismatch.err, HasSubstr("0 of 1 problems"));
}

// ---- progress and bounds ----

TEST_F(PlanCli, RrtStarShowsProgressOffATerminalOnlyWhenAsked) {
  const std::string problem = "--planner rrt_star --map " + kData + "arena.map --start 1,7 --goal 47,46";
  // Quick plans say nothing (a line every 10 s by default)...
  const Result quiet = plan(problem + " --iterations 3000");
  EXPECT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  // ...but every --progress-every seconds, a plain line with the count, the pace and the ETA.
  const Result r = plan(problem + " --iterations 20000 --progress-every 0.001");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(r.err);
  ASSERT_FALSE(lines.empty());
  for (const std::string& line : lines) {
    EXPECT_TRUE(std::regex_match(line, std::regex("progress: rrt_star: [0-9]+/20000 iterations \\| "
                                                  "([0-9]+ iterations/s \\| ETA [0-9hms]+|ETA --)")))
        << line;
  }
  // Progress changes nothing: the same line as without it but for the time.
  EXPECT_EQ(without_time(r.out), without_time(plan(problem + " --iterations 20000").out));
}

TEST_F(PlanCli, TimeLimitStopsRrtStarWithTheBestPathSoFar) {
  const std::string problem = "--planner rrt_star --map " + kData + "arena.map --start 1,7 --goal 47,46";
  // 10^7 iterations would take minutes; a tenth of a second ends it.
  const Result r = plan(problem + " --iterations 10000000 --time-limit 0.1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::smatch m = [&] {
    std::smatch found;
    std::regex_search(r.out, found, std::regex(" iterations=([0-9]+) "));
    return found;
  }();
  ASSERT_EQ(m.size(), 2u) << r.out;
  const long iterations = std::stol(m[1]);
  EXPECT_GT(iterations, 0);
  EXPECT_LT(iterations, 10000000);
  EXPECT_EQ(iterations % 1024, 0);  // stopped where the search looks at the clock
  EXPECT_THAT(r.err, HasSubstr("rrt_star: stopped at --time-limit 0.1 s after " + std::to_string(iterations) +
                               " of 10000000 iterations"));
  // A scenario tries no further problem once the time is up, and says how many it left (exit 4: incomplete,
  // not wrong).
  const Result scen = plan("--planner rrt_star --iterations 10000000 --time-limit 0.1 --map " + kData +
                           "arena.map --scen " + kData + "arena.map.scen");
  EXPECT_EQ(scen.exit_code, 4);
  EXPECT_EQ(lines_of(scen.out).size(), 2u) << scen.out;  // the header and the problem cut short
  EXPECT_THAT(scen.err, HasSubstr("of 160 problems"));
  EXPECT_THAT(scen.err, HasSubstr("stopped at --time-limit 0.1 s with 159 problems not tried"));
  // Grid searches stop between problems; those tried matched their optima, the rest were left (exit 4).
  const Result grid = plan("--time-limit 0.001 --map " + kData + "arena.map --scen " + kData + "arena.map.scen");
  EXPECT_EQ(grid.exit_code, 4);
  EXPECT_THAT(grid.err, HasSubstr("problems not tried"));
}

// ---- which options apply ----

TEST_F(PlanCli, OptionsThatDoNotApplyOrAreBadExitTwo) {
  const std::string arena = " --map " + kData + "arena.map";
  const std::string dubins = "--planner dubins";
  const std::string rrt = "--planner rrt_star" + arena + " --start 1,7 --goal 47,46";
  struct Case {
    std::string args;
    std::string message;
  };
  for (const Case& c : {
           // dubins
           Case{dubins + " --from 0,0,90 --radius 2", "--to: expected --from X,Y,HEADING --to X,Y,HEADING --radius R"},
           Case{dubins + " --to 0,0,90 --radius 2", "--from: expected --from X,Y,HEADING"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90", "--radius: expected --from X,Y,HEADING"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius 0", "--radius: expected the turning radius in metres, a number in [1e-06, 1e+07], got \"0\""},
           // Issue 16: huge values are refused with exit 2, not an internal error.
           Case{dubins + " --from 0,0,1e308 --to 4,0,-90 --radius 2", "--from: expected X,Y,HEADING (metres, metres, degrees counter-clockwise from +x; |X|, |Y| <= 1e+07, |HEADING| <= 1e+06), got \"0,0,1e308\""},
           Case{dubins + " --from 0,0,90 --to 1e300,0,-90 --radius 2", "--to: expected X,Y,HEADING"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius 1e300", "--radius: expected the turning radius in metres, a number in [1e-06, 1e+07]"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius -1", "--radius: expected the turning radius"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius 2m", "--radius: expected the turning radius"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius inf", "--radius: expected the turning radius"},
           Case{dubins + " --from 0,0 --to 4,0,-90 --radius 2", "--from: expected X,Y,HEADING (metres, metres, degrees"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90,1 --radius 2", "--to: expected X,Y,HEADING"},
           Case{dubins + " --from 0,0,x --to 4,0,-90 --radius 2", "--from: expected X,Y,HEADING"},
           Case{dubins + " --from 0,,90 --to 4,0,-90 --radius 2", "--from: expected X,Y,HEADING"},
           Case{dubins + " --from 0,0,nan --to 4,0,-90 --radius 2", "--from: expected X,Y,HEADING"},
           Case{dubins + arena + " --from 0,0,90 --to 4,0,-90 --radius 2", "--map: does not apply to --planner dubins"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius 2 --start 1,7", "--start: does not apply to --planner dubins"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius 2 --seed 1", "--seed: does not apply to --planner dubins"},
           // grid planners
           Case{"--start 1,13 --goal 4,12", "--map: expected --map FILE.map with --planner astar"},
           Case{arena + " --start 1,13 --goal 4,12 --from 0,0,90", "--from: does not apply to --planner astar"},
           Case{arena + " --planner dstar_lite --start 1,13 --goal 4,12 --radius 2", "--radius: does not apply to --planner dstar_lite"},
           Case{arena + " --start 1,13 --goal 4,12 --iterations 10", "--iterations: does not apply to --planner astar"},
           Case{arena + " --planner lpa_star --start 1,13 --goal 4,12 --seed 3", "--seed: does not apply to --planner lpa_star"},
           // rrt_star
           Case{"--planner rrt_star --start 1,7 --goal 47,46", "--map: expected --map FILE.map with --planner rrt_star"},
           Case{"--planner rrt_star" + arena, "expected either --start X,Y and --goal X,Y, or --scen FILE.scen"},
           Case{"--planner rrt_star" + arena + " --start 1,7", "--goal: expected both --start X,Y and --goal X,Y"},
           Case{"--planner rrt_star" + arena + " --start 0,0 --goal 47,46", "--start: expected a passable cell"},
           Case{rrt + " --to 4,0,-90", "--to: does not apply to --planner rrt_star"},
           Case{rrt + " --radius 2", "--radius: does not apply to --planner rrt_star"},
           Case{rrt + " --iterations 0", "--iterations: expected an integer in [1, 10000000], got \"0\""},
           Case{rrt + " --iterations 2.5", "--iterations: expected an integer in [1, 10000000]"},
           Case{rrt + " --seed -1", "--seed: expected an integer seed in [0, 18446744073709551615], got \"-1\""},
           Case{rrt + " --seed 1.5", "--seed: expected an integer seed in [0, 18446744073709551615], got \"1.5\""},
           Case{rrt + " --step 0", "--step: expected the step in cells, a number in [0.001, 1e+06], got \"0\""},
           Case{rrt + " --step 1e-300", "--step: expected the step in cells, a number in [0.001, 1e+06], got \"1e-300\""},
           Case{rrt + " --step 1e300", "--step: expected the step in cells, a number in [0.001, 1e+06]"},
           Case{rrt + " --iterations 10000001", "--iterations: expected an integer in [1, 10000000], got \"10000001\""},
           Case{rrt + " --time-limit 0", "--time-limit: expected seconds of wall time, a number in [0.001, 1e+06], got \"0\""},
           Case{rrt + " --time-limit inf", "--time-limit: expected seconds of wall time"},
           Case{arena + " --scen x --time-limit -1", "--time-limit: expected seconds of wall time"},
           Case{rrt + " --progress-every 0", "--progress-every: expected seconds between progress lines, a number in [0.001, 1e+06]"},
           Case{dubins + " --from 0,0,90 --to 4,0,-90 --radius 2 --time-limit 1", "--time-limit: does not apply to --planner dubins"},
       }) {
    const Result r = plan(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(r.out, "") << c.args;
  }
}

}  // namespace
