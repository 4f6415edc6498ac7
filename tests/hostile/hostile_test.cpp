/// Replays the hostile-input corpus (tests/hostile/corpus/) through the
/// `campo` program as a user would, each command under a time and memory
/// limit, and requires the promise of docs/running.md "Limits": every input
/// ends with exit 0, or with exit 2 and one error line naming the file.
///   scenes/*.json    campo validate F; campo run F (validate accepts exactly what run can run)
///   sweeps/*.json    campo sweep F --list
///   maps/*.map       campo plan --map F --start 0,0 --goal 1,1
///   commands/*.args  campo ARGS (one line; @CORPUS@ stands for the corpus folder, @SOURCE@ for campo's)
/// Inputs too big to commit (megabytes of JSON) are written by the test itself.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "tests/cli_support.hpp"
#include "tests/hostile/hostile_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kCorpus = fs::path(CAMPO_SOURCE_DIR) / "tests" / "hostile" / "corpus";

using hostile::kSecondsPerCommand;
using hostile::Outcome;
using hostile::quoted;
using hostile::run_campo;

/// Messages that a terminal shows as written: no raw control character (but the
/// line ends), and no error about a path that reads empty ("error: : ...").
void expect_printable(const Outcome& o, const std::string& what) {
  for (const char c : o.err) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n') || byte == 0x7f) {
      ADD_FAILURE() << what << ": a raw control character (" << int{byte} << ") on stderr\n" << o.err.substr(0, 2000);
      break;
    }
  }
  EXPECT_EQ(o.err.find("error: : "), std::string::npos) << what << ": an error names an empty path\n" << o.err;
}

/// Exit 0, or exit 2 with an error line that names `file`.
void expect_clean(const Outcome& o, const std::string& what, const std::string& file) {
  expect_printable(o, what);
  EXPECT_TRUE(o.exit_code == 0 || o.exit_code == 2)
      << what << ": exit " << o.exit_code << " (124/137: over " << kSecondsPerCommand
      << " s; else a crash or an internal error)\n" << o.err.substr(0, 2000);
  if (o.exit_code == 2) {
    EXPECT_THAT(o.err, HasSubstr("error: ")) << what;
    // An option that does not fit the file is named as the command line's.
    if (o.err.find("error: command line: ") == std::string::npos) {
      EXPECT_THAT(o.err, HasSubstr(file)) << what << ": the error does not name the file";
    }
  }
}

std::vector<std::string> corpus(const std::string& folder, const std::string& extension) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kCorpus / folder)) {
    if (entry.path().extension() == extension) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

class Hostile : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("campo_hostile_" + test_name({GetParam(), 0}) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// validate then run: both clean; validate accepts exactly what run can run,
  /// and a refused run does not even create its output folder.
  void replay_scene(const fs::path& scene) {
    const std::string file = scene.string();
    const Outcome validate = run_campo("validate " + quoted(file), dir_);
    expect_clean(validate, "campo validate", file);
    const fs::path out = dir_ / "run";
    const Outcome run = run_campo("run " + quoted(file) + " --out " + quoted(out.string()), dir_);
    expect_clean(run, "campo run", file);
    EXPECT_EQ(validate.exit_code == 0, run.exit_code == 0)
        << "validate exit " << validate.exit_code << " but run exit " << run.exit_code << "\n" << validate.err
        << run.err.substr(0, 2000);
    if (run.exit_code == 2) {
      EXPECT_FALSE(fs::exists(out)) << "a refused run left " << out << " behind";
    }
  }

  fs::path dir_;
};

class HostileScene : public Hostile {};
TEST_P(HostileScene, ValidateAndRunEndCleanly) { replay_scene(kCorpus / "scenes" / GetParam()); }
INSTANTIATE_TEST_SUITE_P(Corpus, HostileScene, ::testing::ValuesIn(corpus("scenes", ".json")), test_name);

class HostileSweep : public Hostile {};
TEST_P(HostileSweep, ListingEndsCleanly) {
  const std::string file = (kCorpus / "sweeps" / GetParam()).string();
  expect_clean(run_campo("sweep " + quoted(file) + " --list", dir_), "campo sweep --list", file);
}
INSTANTIATE_TEST_SUITE_P(Corpus, HostileSweep, ::testing::ValuesIn(corpus("sweeps", ".json")), test_name);

class HostileMap : public Hostile {};
TEST_P(HostileMap, PlanningEndsCleanly) {
  const std::string file = (kCorpus / "maps" / GetParam()).string();
  expect_clean(run_campo("plan --map " + quoted(file) + " --start 0,0 --goal 1,1", dir_), "campo plan", file);
  expect_clean(run_campo("plan --planner rrt_star --iterations 2000 --map " + quoted(file) + " --start 0,0 --goal 1,1",
                         dir_),
               "campo plan --planner rrt_star", file);
}
INSTANTIATE_TEST_SUITE_P(Corpus, HostileMap, ::testing::ValuesIn(corpus("maps", ".map")), test_name);

class HostileCommand : public Hostile {};
TEST_P(HostileCommand, EndsCleanly) {
  std::string args = testing::slurp(kCorpus / "commands" / GetParam());
  while (!args.empty() && (args.back() == '\n' || args.back() == ' ')) args.pop_back();
  for (std::size_t at; (at = args.find("@CORPUS@")) != std::string::npos;) args.replace(at, 8, kCorpus.string());
  for (std::size_t at; (at = args.find("@SOURCE@")) != std::string::npos;) args.replace(at, 8, CAMPO_SOURCE_DIR);
  const Outcome o = run_campo(args, dir_);
  EXPECT_TRUE(o.exit_code == 0 || o.exit_code == 2) << "campo " << args << ": exit " << o.exit_code << "\n"
                                                    << o.err.substr(0, 2000);
  if (o.exit_code == 2) EXPECT_THAT(o.err, HasSubstr("error: "));
  expect_printable(o, "campo " + args);
}
INSTANTIATE_TEST_SUITE_P(Corpus, HostileCommand, ::testing::ValuesIn(corpus("commands", ".args")), test_name);

// Inputs of megabytes, written here rather than committed.
class HostileGenerated : public Hostile {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_hostile_generated_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
};

const std::string kDrone =
    R"({"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]}, "planner": {"name": "straight"},
        "mission": {"waypoints": [{"position_m": [5, 0, 1.5]}]}})";

TEST_F(HostileGenerated, ArrayOfAQuarterMillionObjectsParsesInLinearTime) {
  // Parsed whole (linear time; nlohmann's callback parser was quadratic here), then refused at the object limit.
  std::string objects;
  for (int i = 0; i < 250000; ++i) objects += R"({"alias": "b)" + std::to_string(i) + R"(", "type": "dummy"},)";
  replay_scene(write("many_objects.json", R"({"campo_scene": 1, "name": "many", "world": {"time_limit_s": 2},
      "objects": [)" + objects + kDrone + "]}"));
}

TEST_F(HostileGenerated, TenMegabyteNameInFigureTitles) {
  replay_scene(write("long_name.json", R"({"campo_scene": 1, "name": ")" + std::string(10 << 20, 'n') +
                                           R"(", "world": {"time_limit_s": 1}, "objects": [)" + kDrone + "]}"));
}

TEST_F(HostileGenerated, SlowTenThousandGridBoxesOnTerrain) {
  // A grid_obstacles block at its limit: 10000 blocks, each over most of a 10000 x 10000 grid, on rolling
  // terrain. Sampling 257 x 257 points under every block took 15-23 s; one budget of ground queries per
  // generator (docs/limits.md) makes it about 0.4 s to validate, 1.6 s to run (Release).
  std::string boxes;
  for (int k = 0; k < 10000; ++k) {
    boxes += (k ? "," : "") + std::string(R"({"rows": [)") + std::to_string(1 + k % 100) + ", " +
             std::to_string(10000 - k % 37) + R"(], "cols": [)" + std::to_string(1 + k * 7 % 1000) + ", " +
             std::to_string(10000 - k * 13 % 500) + R"(], "height_m": )" + std::to_string(1 + k % 5) + "}";
  }
  replay_scene(write("grid_boxes.json", R"({"campo_scene": 1, "name": "grid_boxes", "world": {"time_limit_s": 2},
      "objects": [{"alias": "hills", "type": "rolling_terrain", "size_m": [200, 200], "spacing_m": 0.5, "amplitude_m": 2},
        {"alias": "g", "type": "grid_obstacles", "origin_m": [10, -50], "rows": 10000, "cols": 10000,
         "cell_size_m": 0.01, "boxes": [)" + boxes + R"(]},
        {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 3.5]}, "planner": {"name": "straight"},
         "mission": {"waypoints": [{"position_m": [5, 0, 3.5]}]}}]})"));
}

TEST_F(HostileGenerated, SweepSpecWithAHugeValueList) {
  std::string values;
  for (int i = 0; i < 400000; ++i) values += std::to_string(i % 7 + 1) + ",";
  const fs::path spec = write("huge_axis.json", R"({"campo_sweep": 1, "name": "huge", "scenes": ["two_barriers"],
      "axes": [{"name": "speed", "values": [)" + values + R"(1], "set": ["/objects/drone/planner/params/speed_mps"]}],
      "seeds": {"first": 0, "count": 1}})");
  expect_clean(run_campo("sweep " + quoted(spec.string()) + " --list", dir_), "campo sweep --list", spec.string());
}

// A loop of symbolic links given where a run directory, a scene, a spec or a map is read.
TEST_F(HostileGenerated, ALoopOfSymbolicLinksAsEveryInput) {
  fs::create_symlink("loop_b", dir_ / "loop_a");
  fs::create_symlink("loop_a", dir_ / "loop_b");
  const std::string loop = (dir_ / "loop_a").string();
  for (const std::string args : {"render " + loop, "merge " + loop + " --out merged", "validate " + loop,
                                 "run " + loop + " --out run", "sweep " + loop + " --list", "table " + loop,
                                 "plan --map " + loop + " --start 0,0 --goal 1,1"}) {
    const Outcome o = run_campo(args, dir_);
    EXPECT_EQ(o.exit_code, 2) << args << "\n" << o.err;
    expect_clean(o, "campo " + args, loop);
    EXPECT_THAT(o.err, HasSubstr("error: ")) << args;
  }
}

// A recorded run whose trajectory.csv ends at -5 s, or whose times go back: refused by
// every reader of the run, naming the file and line; no frame count wraps.
TEST_F(HostileGenerated, ARunWhoseRecordedTimesGoBackwards) {
  const fs::path scene = write("flat.json", R"({"campo_scene": 1, "name": "flat", "world": {"time_limit_s": 1},
      "objects": [{"alias": "ground", "type": "plane"}, )" + kDrone + "]}");
  ASSERT_EQ(run_campo("run " + quoted(scene.string()) + " --no-figures --out run", dir_).exit_code, 0);
  const fs::path csv = dir_ / "run" / "trajectory.csv";
  std::string text = testing::slurp(csv);
  const std::size_t last = text.rfind('\n', text.size() - 2) + 1;
  text += "-5.000000" + text.substr(text.find(',', last));  // the last line again, at -5 s
  std::ofstream(csv, std::ios::binary) << text;
  for (const std::string kind : {"video", "map", "replay", "sequence"}) {
    const std::string out = kind == "video" ? "video.gif" : kind;
    const Outcome o = run_campo("render run --kind " + kind + " --out " + out, dir_);
    EXPECT_EQ(o.exit_code, 2) << kind << "\n" << o.err;
    expect_clean(o, "campo render --kind " + kind, "trajectory.csv");
    EXPECT_THAT(o.err, HasSubstr("got \"-5.000000\"")) << kind;
    EXPECT_EQ(o.err.find("18446744"), std::string::npos) << kind;
  }
}

}  // namespace
}  // namespace campo
