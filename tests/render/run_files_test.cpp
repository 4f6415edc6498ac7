#include "render/run_files.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class RunFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_run_files_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The message of reading `rows` under a trajectory.csv header, "" when it reads.
  std::string trajectory_error(const std::string& rows) {
    const fs::path file = dir_ / "trajectory.csv";
    std::ofstream(file, std::ios::binary) << "time_s,x_m,command\n" << rows;
    try {
      read_trajectory_table(file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(RunFiles, RecordedTimesAreFiniteFromZeroAndInOrder) {
  EXPECT_EQ(trajectory_error("0.000000,1,hold\n0.010000,2,go\n0.010000,3,go\n"), "");
  const std::string file = (dir_ / "trajectory.csv").string();
  EXPECT_EQ(trajectory_error("0,1,go\n-5.000000,2,go\n"),
            file + ": line 3: expected a time_s in seconds, a finite number >= the previous line's 0.000000, got \"-5.000000\"");
  EXPECT_EQ(trajectory_error("-5,1,go\n"), file + ": line 2: expected a time_s in seconds, a finite number >= 0, got \"-5\"");
  EXPECT_THAT(trajectory_error("0,1,go\n2,1,go\n1,1,go\n"), HasSubstr("line 4: expected a time_s in seconds, a finite "
                                                                       "number >= the previous line's 2.000000, got \"1\""));
  EXPECT_THAT(trajectory_error("nan,1,go\n"), HasSubstr("line 2: expected a time_s in seconds, a finite number >= 0, got \"nan\""));
  EXPECT_THAT(trajectory_error("0,1,go\ninf,1,go\n"), HasSubstr("got \"inf\""));
  EXPECT_THAT(trajectory_error("1e999,1,go\n"), HasSubstr("got \"1e999\""));
  EXPECT_THAT(trajectory_error("hold,1,go\n"), HasSubstr("got \"hold\""));
  EXPECT_THAT(trajectory_error("1s,1,go\n"), HasSubstr("got \"1s\""));
  // The text is quoted in part, with its control characters escaped.
  const std::string error = trajectory_error("\x1b[2J" + std::string(1000, '9') + ",1,go\n");
  EXPECT_THAT(error, HasSubstr("got \"\\x1b[2J999"));
  EXPECT_LT(error.size(), file.size() + 200);
}

TEST_F(RunFiles, AnEmptyRunDirectoryPathIsNamedAsOne) {
  try {
    load_run_dir("");
    FAIL() << "an empty path was read (as the working directory)";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "\"\" (empty path): expected the path of a run directory, got an empty string");
  }
}

}  // namespace
}  // namespace campo
