// Runs `campo plan` as a user would: the one-line result, the scenario CSV,
// and exit code 2 with a precise message on bad input.
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
  const std::string map = write("walled.map", "type octile\nheight 3\nwidth 5\nmap\n..@..\n..@..\n..@..\n");
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
                           "index,start_x,start_y,goal_x,goal_y,optimal,cost,match", "no corner cutting", "dstar_lite"}) {
    EXPECT_THAT(r.out, HasSubstr(text));
  }
}

}  // namespace
