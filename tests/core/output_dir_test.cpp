// Outputs fail with the file and the system's reason; stale staging
// directories of this host's killed processes are removed.
#include "core/output_dir.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class OutputDir : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest runs the tests of this suite in parallel.
    dir_ = fs::temp_directory_path() /
           ("campo_output_dir_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(OutputDir, AFileThatCannotBeWrittenNamesItAndTheSystemsReason) {
  const fs::path file = dir_ / "missing" / "run.json";
  try {
    write_file_atomically(file, "{}");
    ADD_FAILURE() << "expected an OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ": cannot write: No such file or directory");
  }
  write_file_atomically(dir_ / "run.json", "{}\n");
  std::ifstream in(dir_ / "run.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "{}\n");
  // Nothing temporary is left behind.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST_F(OutputDir, AnOutputDirectoryThatCannotBeMadeIsAnOutputError) {
  std::ofstream(dir_ / "file") << "in the way";
  try {
    StagedOutput out(dir_ / "file" / "run");
    ADD_FAILURE() << "expected an OutputError";
  } catch (const OutputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot create the output directory: Not a directory"));
  }
}

TEST_F(OutputDir, StaleStagingOfThisHostIsRemovedOthersAreKept) {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);  // its PID now belongs to no process
  const fs::path stale = dir_ / staging_name(child);
  const fs::path live = dir_ / staging_name(::getppid());
  const fs::path other_host = dir_ / ".staging-elsewhere.example-12345";
  const fs::path legacy = dir_ / (".staging-" + std::to_string(child));
  for (const fs::path& d : {stale, live, other_host, legacy}) fs::create_directories(d / "replans");
  EXPECT_EQ(remove_stale_staging(dir_), 1);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other_host));
  EXPECT_TRUE(fs::exists(legacy));
  {
    StagedOutput out(dir_);
    write_file_atomically(out.path("a.txt"), "a");
    out.commit();
  }
  EXPECT_TRUE(fs::is_regular_file(dir_ / "a.txt"));
  EXPECT_FALSE(fs::exists(dir_ / staging_name(::getpid())));
}

}  // namespace
}  // namespace campo
