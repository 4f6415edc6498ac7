// The messages of refused command lines (docs/limits.md, "What errors look like"):
// every one starts with "error:", names a non-empty path, never wraps a negative
// number and never echoes a control character raw, whoever finds the error
// (CLI11's parser, an option's check, a reader of a file).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using campo::testing::Result;
using campo::testing::slurp;
using Messages = campo::testing::CliTest;

// Exit 2 and one "error: " line first, without raw control characters or an unnamed path.
void expect_refused(const Result& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
  EXPECT_THAT(r.err, StartsWith("error: ")) << what;
  EXPECT_EQ(r.err.find("error: : "), std::string::npos) << what << ": an unnamed path\n" << r.err;
  for (const char c : r.err) {
    const auto byte = static_cast<unsigned char>(c);
    EXPECT_FALSE((byte < 0x20 && c != '\n') || byte == 0x7f) << what << ": a raw control character " << int{byte} << " in\n"
                                                             << r.err;
  }
}

const std::string kScene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";

TEST_F(Messages, ParseErrorsOfEveryCommandStartWithErrorCommandLine) {
  for (const std::string command : {"", "run", "render", "validate", "scan", "sweep", "table", "plot", "merge", "plan",
                                    "reproduce", "bench"}) {
    const Result r = campo(command + " --no-such-option");
    expect_refused(r, command);
    // CLI11 names the unknown option, or first what is missing ("runs is required").
    EXPECT_THAT(r.err, StartsWith("error: command line: ")) << command;
    EXPECT_THAT(r.err, HasSubstr("\nRun with --help for more information.\n")) << command;
    EXPECT_EQ(r.out, "") << command;
  }
  EXPECT_THAT(campo("plan --no-such-option").err,
              StartsWith("error: command line: The following argument was not expected: --no-such-option\n"));
  expect_refused(campo("render"), "render without a run");
  EXPECT_THAT(campo("render").err, StartsWith("error: command line: runs is required"));
  EXPECT_THAT(campo("sweep --jobs 0 x").err, StartsWith("error: command line: --jobs: "));
  // Numbers are said as given, not against a range up to 1.8e308 written out in 300 digits.
  Result r = campo("render " + dir_.string() + " --kind sequence --at -5");
  expect_refused(r, "--at -5");
  EXPECT_THAT(r.err, StartsWith("error: command line: --at: expected a number >= 0, got \"-5\"\n"));
  r = campo("sweep x --time-limit 0");
  expect_refused(r, "--time-limit 0");
  EXPECT_THAT(r.err, StartsWith("error: command line: --time-limit: expected a number > 0, got \"0\"\n"));
  r = campo("run --record-depth nan");
  expect_refused(r, "--record-depth nan");
  EXPECT_THAT(r.err, StartsWith("error: command line: --record-depth: expected a number >= 0, got \"nan\"\n"));
}

TEST_F(Messages, HelpAndVersionStillPrintToStandardOutputWithExitZero) {
  for (const std::string args : {"--help", "run --help", "render --help", "plan --help"}) {
    const Result r = campo(args);
    EXPECT_EQ(r.exit_code, 0) << args;
    EXPECT_THAT(r.out, HasSubstr("Usage: ")) << args;
    EXPECT_EQ(r.err, "") << args;
  }
  const Result version = campo("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_THAT(version.out, StartsWith("campo "));
  EXPECT_EQ(version.err, "");
}

TEST_F(Messages, ALoopOfSymbolicLinksIsNamedWithTheSystemsReason) {
  fs::create_symlink("b", dir_ / "a");
  fs::create_symlink("a", dir_ / "b");
  const std::string loop = (dir_ / "a").string();
  Result r = campo("render " + loop);
  expect_refused(r, "render");
  EXPECT_EQ(r.err, "error: command line: runs: expected an existing directory, got \"" + loop +
                       "\": Too many levels of symbolic links\nRun with --help for more information.\n");
  r = campo("merge " + loop + " --out " + (dir_ / "merged").string());
  expect_refused(r, "merge");
  EXPECT_THAT(r.err, StartsWith("error: command line: dirs: expected an existing directory, got \"" + loop + "\""));
  r = campo("bench --compare " + loop);
  expect_refused(r, "bench --compare");
  EXPECT_THAT(r.err, StartsWith("error: command line: --compare: expected an existing regular file, got \"" + loop +
                                "\": Too many levels of symbolic links"));
  // The readers behind options without a check say the same.
  for (const std::string args : {"validate " + loop, "run " + loop, "sweep " + loop + " --list",
                                 "plan --map " + loop + " --start 0,0 --goal 1,1"}) {
    r = campo(args);
    expect_refused(r, args);
    EXPECT_THAT(r.err, HasSubstr(loop)) << args;
    EXPECT_THAT(r.err, HasSubstr("Too many levels of symbolic links")) << args;
  }
  // Where a directory is expected, a file is named as one.
  r = campo("render " + kScene);
  expect_refused(r, "render FILE");
  EXPECT_THAT(r.err, StartsWith("error: command line: runs: expected a directory, got \"" + kScene + "\", which is a file"));
}

TEST_F(Messages, AnEmptyPathIsRefusedAsEmptyByEveryCommand) {
  const std::string out = (dir_ / "out").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"validate ''", "error: command line: files: expected a path, got an empty string"},
      {"run ''", "error: command line: scene: expected a path, got an empty string"},
      {"run --plugin '' " + kScene + " --out " + out, "error: command line: --plugin: expected a path, got an empty string"},
      {"scan '' --out " + out, "error: command line: scene: expected a path, got an empty string"},
      {"sweep '' --list", "error: command line: spec: expected a path, got an empty string"},
      {"table ''", "error: command line: dir: expected a path, got an empty string"},
      {"plot '' --x seed --y time_s --out " + out + ".png", "error: command line: dir: expected a path, got an empty string"},
      {"render ''", "error: command line: runs: expected the path of a directory, got an empty string"},
      {"merge '' --out " + out, "error: command line: dirs: expected the path of a directory, got an empty string"},
      {"plan --map '' --start 0,0 --goal 1,1", "error: command line: --map: expected a path, got an empty string"},
      {"plan --map x.map --scen ''", "error: command line: --scen: expected a path, got an empty string"},
      {"bench --compare ''", "error: command line: --compare: expected the path of a regular file, got an empty string"},
      {"bench --table ''", "error: command line: --table: expected the path of a regular file, got an empty string"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = campo(args);
    expect_refused(r, args);
    EXPECT_THAT(r.err, StartsWith(message + "\n")) << args;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

TEST_F(Messages, ControlCharactersInFileNamesAndFilesAreEscapedAndUtf8StaysReadable) {
  // A scene file whose name holds ESC and CR, and one whose name is UTF-8.
  const std::string hostile = write("bad\x1b[2J\r.json", R"({"campo_scene": 1, "objects": [], "colour": 1})");
  Result r = campo("validate '" + hostile + "'");
  expect_refused(r, "validate");
  EXPECT_THAT(r.err, HasSubstr("bad\\x1b[2J\\r.json:1:35: /colour: unknown key"));
  const std::string utf8 = write("caf\xc3\xa9.json", R"({"campo_scene": 1, "objects": [], "colour": 1})");
  r = campo("validate '" + utf8 + "'");
  expect_refused(r, "validate UTF-8");
  EXPECT_THAT(r.err, HasSubstr("caf\xc3\xa9.json:1:35: /colour: unknown key"));
  // A key with ESC (JSON strings may hold any control character but NUL).
  r = campo("validate '" + write("key.json", R"({"campo_scene": 1, "objects": [], "a\u001b[31m": 1})") + "'");
  expect_refused(r, "validate key");
  EXPECT_THAT(r.err, HasSubstr("/a\\x1b[31m: unknown key \"a\\x1b[31m\""));
  // A NUL in a map row (the literal's own length: a count past its end read beyond it, caught by ASan).
  static constexpr char kNulMap[] = "type octile\nheight 1\nwidth 2\nmap\n.\0\n";
  r = campo("plan --map '" + write("nul.map", std::string(kNulMap, sizeof kNulMap - 1)) + "' --start 0,0 --goal 1,0");
  expect_refused(r, "plan");
  EXPECT_THAT(r.err, HasSubstr("nul.map: line 5: column 1: expected one of . G S @ O T W, got '\\x00'"));
  // A --set pointer with ESC, and an unknown option with one.
  r = campo("run " + kScene + " --set '/objects/\x1b[2J/x=1' --out " + (dir_ / "out").string());
  expect_refused(r, "run --set");
  EXPECT_THAT(r.err, HasSubstr("no element with alias \"\\x1b[2J\""));
  r = campo("run '--\x1b[2J'");
  expect_refused(r, "an option with ESC");
  EXPECT_THAT(r.err, HasSubstr("--\\x1b[2J"));
}

TEST_F(Messages, SetPointersWithLeadingZerosAreRefused) {
  const fs::path out = dir_ / "out";
  const Result r = campo("run " + kScene + " --set /objects/04/alias=x --out " + out.string());
  expect_refused(r, "--set /objects/04");
  EXPECT_EQ(r.err, "error: command line: --set /objects/04/alias=x: expected an array index in [0, 5) without leading "
                   "zeros (RFC 6901) or the alias of an element of /objects, got \"04\" (a leading zero) at /objects/04\n");
  EXPECT_FALSE(fs::exists(out));
}

// Replaces the time of trajectory.csv's last line.
void set_last_time(const fs::path& csv, const std::string& time) {
  std::string text = slurp(csv);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t last = text.rfind('\n') + 1;
  text.replace(last, text.find(',', last) - last, time);
  std::ofstream(csv, std::ios::binary) << text << "\n";
}

TEST_F(Messages, RecordedTimesAreCheckedAndFrameCountsNeverWrap) {
  const fs::path run = dir_ / "run";
  ASSERT_EQ(campo("run " + kScene + " --no-figures --set /world/time_limit_s=1 --out " + run.string()).exit_code, 0);
  const std::string csv = (run / "trajectory.csv").string();
  const std::string video = "render " + run.string() + " --kind video --out " + (dir_ / "v.gif").string();

  set_last_time(csv, "-5");
  Result r = campo(video);
  expect_refused(r, "a run ending at -5 s");
  EXPECT_THAT(r.err, StartsWith("error: " + csv + ": line "));
  EXPECT_THAT(r.err, HasSubstr(": expected a time_s in seconds, a finite number >= the previous line's "));
  EXPECT_THAT(r.err, HasSubstr("got \"-5\""));
  EXPECT_EQ(r.err.find("18446744"), std::string::npos);
  r = campo("render " + run.string() + " --kind map --out " + (dir_ / "figures").string());
  expect_refused(r, "a map of a run ending at -5 s");
  EXPECT_THAT(r.err, HasSubstr("got \"-5\""));

  // A time far beyond any run: the frame count is said as it is, not wrapped or cast out of range.
  set_last_time(csv, "1e300");
  r = campo(video);
  expect_refused(r, "a run ending at 1e300 s");
  EXPECT_THAT(r.err, HasSubstr("error: command line: --speed: a "));
  EXPECT_THAT(r.err, HasSubstr("frames, more than 60000; raise --speed or lower --fps"));
  EXPECT_THAT(r.err, HasSubstr("a 1e+300 s run at this speed and frame rate takes 2.5e+301 frames"));
  EXPECT_FALSE(fs::exists(dir_ / "v.gif"));
}

}  // namespace
