#include "grid/movingai.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "grid/astar.hpp"
#include "grid/dstar_lite.hpp"

namespace campo::grid {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path data(const std::string& name) { return fs::path(CAMPO_SOURCE_DIR) / "tests/data/movingai" / name; }

// Solves every `stride`-th problem of a scenario and checks its optimal length.
void solve_scenario(const std::string& map_name, int stride, bool with_dstar) {
  const MovingAiMap map = read_movingai_map(data(map_name));
  const auto problems = read_movingai_scenario(data(map_name + ".scen"));
  check_scenario(data(map_name + ".scen"), problems, map);
  GridGraph graph = to_grid_graph(map);
  AStar astar(graph);
  DStarLite dstar(graph, problems.front().start, problems.front().goal);
  int solved = 0;
  for (std::size_t i = 0; i < problems.size(); i += static_cast<std::size_t>(stride)) {
    const MovingAiProblem& p = problems[i];
    SCOPED_TRACE(map_name + ".scen line " + std::to_string(p.line));
    const SearchResult a = astar.plan(p.start, p.goal);
    ASSERT_EQ(a.status, SearchStatus::found);
    EXPECT_TRUE(matches_optimal(to_cells(a.cost), p.optimal_length))
        << to_cells(a.cost) << " vs " << p.optimal_length;
    if (with_dstar) {
      dstar.reset(p.start, p.goal);
      EXPECT_EQ(dstar.plan().cost, a.cost);
    }
    ++solved;
  }
  EXPECT_GT(solved, 0);
}

TEST(MovingAi, ArenaEveryProblemAtItsOptimalLength) {
  const auto problems = read_movingai_scenario(data("arena.map.scen"));
  ASSERT_EQ(problems.size(), 160u);
  solve_scenario("arena.map", 1, true);
}

TEST(MovingAi, Maze512SampleAtItsOptimalLength) {
  const auto problems = read_movingai_scenario(data("maze512-32-9.map.scen"));
  ASSERT_EQ(problems.size(), 8010u);
  EXPECT_EQ(problems.back().line, 8011);
  EXPECT_EQ(problems.back().start, (Cell{373, 48, 0}));
  EXPECT_DOUBLE_EQ(problems.back().optimal_length, 3201.44696807);
  solve_scenario("maze512-32-9.map", 40, false);
}

TEST(MovingAi, ReadsTheMapHeaderAndCells) {
  const MovingAiMap map = read_movingai_map(data("arena.map"));
  EXPECT_EQ(map.width, 49);
  EXPECT_EQ(map.height, 49);
  EXPECT_FALSE(map.is_passable(0, 0));  // 'T'
  EXPECT_TRUE(map.is_passable(3, 1));   // '.'
  const GridGraph graph = to_grid_graph(map);
  EXPECT_EQ(graph.state({0, 0, 0}), CellState::blocked);
  EXPECT_EQ(graph.state({3, 1, 0}), CellState::free);
}

TEST(MovingAi, MatchesOptimalWithinTheFilesRounding) {
  EXPECT_TRUE(matches_optimal(3.414213562, 3.41421));
  EXPECT_TRUE(matches_optimal(3203.17489013, 3203.1749));
  EXPECT_FALSE(matches_optimal(4.0, 3.41421));
  EXPECT_FALSE(matches_optimal(-1.0, 0.0));
}

class MovingAiErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_movingai_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // The error message of reading `text` as a map.
  std::string map_error(const std::string& text) {
    const fs::path file = write("bad.map", text);
    try {
      read_movingai_map(file);
    } catch (const FormatError& e) {
      EXPECT_EQ(e.file(), file.string());
      return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }

  std::string scen_error(const std::string& text) {
    const fs::path file = write("bad.scen", text);
    try {
      read_movingai_scenario(file);
    } catch (const FormatError& e) {
      EXPECT_EQ(e.file(), file.string());
      return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }

  fs::path dir_;
};

TEST_F(MovingAiErrors, MapErrorsNameTheFileTheLineAndWhatWasExpected) {
  const std::string header = "type octile\nheight 2\nwidth 3\nmap\n";
  EXPECT_THAT(map_error("type tile\nheight 2\nwidth 3\nmap\n...\n...\n"),
              HasSubstr("bad.map: line 1: expected \"type octile\", got \"type tile\""));
  EXPECT_THAT(map_error("type octile\nheight x\nwidth 3\nmap\n...\n...\n"),
              HasSubstr("line 2: expected height (an integer in [1, 4096]), got \"x\""));
  EXPECT_THAT(map_error("type octile\nwidth 3\nheight 2\nmap\n"), HasSubstr("line 2: expected \"height N\""));
  EXPECT_THAT(map_error("type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n"),
              HasSubstr("line 6: column 1: expected one of . G S @ O T W, got 'x'"));
  EXPECT_THAT(map_error(header + "...\n....\n"), HasSubstr("line 6: expected a row of 3 cells, got 4"));
  EXPECT_THAT(map_error(header + "...\n"), HasSubstr("line 6: expected map row 1 of 2, got the end of the file"));
  EXPECT_THAT(map_error(header + "...\n...\n@@@\n"), HasSubstr("line 7: expected the end of the map after 2 rows"));
  EXPECT_THAT(map_error(""), HasSubstr("line 1: expected \"type octile\", got the end of the file"));
  // Windows line ends and trailing blank lines are fine.
  const MovingAiMap map = read_movingai_map(write("crlf.map", "type octile\r\nheight 1\r\nwidth 2\r\nmap\r\n.@\r\n\r\n"));
  EXPECT_EQ(map.width, 2);
  EXPECT_FALSE(map.is_passable(1, 0));
  try {
    read_movingai_map(dir_ / "missing.map");
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.map: cannot read the file"));
  }
}

TEST_F(MovingAiErrors, ScenarioErrorsNameTheFileTheLineAndWhatWasExpected) {
  const std::string ok = "0\tm.map\t4\t3\t0\t0\t3\t2\t3.82842712\n";
  EXPECT_THAT(scen_error("version 2\n" + ok), HasSubstr("bad.scen: line 1: expected \"version 1\""));
  EXPECT_THAT(scen_error("version 1\n" + ok + "0\tm.map\t4\t3\t0\t0\t3\t2\n"),
              HasSubstr("line 3: expected 9 fields (bucket map width height start_x start_y goal_x goal_y "
                        "optimal_length), got 8"));
  EXPECT_THAT(scen_error("version 1\n0\tm.map\t4\t3\t4\t0\t3\t2\t1\n"),
              HasSubstr("line 2: expected start_x (an integer in [0, 3]), got \"4\""));
  EXPECT_THAT(scen_error("version 1\n0\tm.map\t4\t3\t0\t0\t3\t2\tfar\n"),
              HasSubstr("line 2: expected the optimal length (a number >= 0), got \"far\""));
  const auto problems = read_movingai_scenario(write("ok.scen", "version 1\n\n" + ok));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].line, 3);
  EXPECT_EQ(problems[0].goal, (Cell{3, 2, 0}));

  // Against a map: sizes must agree and the ends must be passable.
  const MovingAiMap map = read_movingai_map(write("m.map", "type octile\nheight 3\nwidth 4\nmap\n....\n....\n...@\n"));
  try {
    check_scenario(dir_ / "ok.scen", problems, map);
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ok.scen: line 3: expected a passable goal cell, got (3, 2), which the map blocks"));
  }
  const MovingAiMap small = read_movingai_map(write("s.map", "type octile\nheight 2\nwidth 4\nmap\n....\n....\n"));
  try {
    check_scenario(dir_ / "ok.scen", problems, small);
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("line 3: expected the map's size 4 x 2, got 4 x 3"));
  }
}

TEST_F(MovingAiErrors, ControlCharactersInAMapAreEscapedAndUtf8StaysReadable) {
  using namespace std::string_literals;
  const std::string header = "type octile\nheight 1\nwidth 3\nmap\n";
  // NUL, ESC and CR inside a row, and in a header line quoted whole.
  EXPECT_THAT(map_error(header + ".\0.\n"s), HasSubstr("line 5: column 1: expected one of . G S @ O T W, got '\\x00'"));
  EXPECT_THAT(map_error(header + "\x1b[2\n"), HasSubstr("line 5: column 0: expected one of . G S @ O T W, got '\\x1b'"));
  EXPECT_THAT(map_error(header + ".\r.\n"), HasSubstr("line 5: column 1: expected one of . G S @ O T W, got '\\r'"));
  EXPECT_THAT(map_error("type octile\nheight 1\x1b]0;pwned\a\nwidth 3\nmap\n...\n"),
              HasSubstr("line 2: expected height (an integer in [1, 4096]), got \"1\\x1b]0;pwned\\x07\""));
  EXPECT_THAT(map_error("type octile\x1b[2J\nheight 1\nwidth 3\nmap\n...\n"),
              HasSubstr("line 1: expected \"type octile\", got \"type octile\\x1b[2J\""));
  // A two-byte character in a row of 3 bytes: quoted whole, as it reads.
  EXPECT_THAT(map_error(header + "\xc3\xa9.\n"), HasSubstr("column 0: expected one of . G S @ O T W, got '\xc3\xa9'"));
  for (const std::string& text : {header + ".\0.\n"s, header + "\x1b[2\n", header + ".\r.\n"}) {
    const std::string error = map_error(text);
    EXPECT_EQ(error.find_first_of("\0\x1b\r\n\a"s), std::string::npos) << error;
  }
  // A long line is quoted in part.
  const std::string long_line = "type " + std::string(100000, 'x');
  EXPECT_LT(map_error(long_line + "\n").size(), 300u);
}

TEST_F(MovingAiErrors, AnEmptyPathIsNamedAsOne) {
  try {
    read_movingai_map("");
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_STREQ(e.what(), "\"\" (empty path): expected the path of a file, got an empty string");
  }
}

}  // namespace
}  // namespace campo::grid
