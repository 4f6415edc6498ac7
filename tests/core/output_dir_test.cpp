// Outputs fail with the file and the system's reason; they write through
// symbolic links and refuse devices, FIFOs and directories; folders made for a
// failed output are removed again; stale staging directories of this host's
// killed processes are removed.
#include "core/output_dir.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
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

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the OutputError `f` throws ("" when it does not throw).
template <typename F>
std::string output_error(F f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(OutputDir, WritesThroughSymbolicLinksAndKeepsThem) {
  fs::create_directories(dir_ / "elsewhere");
  std::ofstream(dir_ / "elsewhere" / "old.png") << "old";
  fs::create_symlink("elsewhere/old.png", dir_ / "relative.png");         // relative to the link's folder
  fs::create_symlink(dir_ / "relative.png", dir_ / "chain.png");           // a link to a link
  fs::create_symlink(dir_ / "elsewhere" / "new.png", dir_ / "dangling.png");  // names a file not made yet
  write_file_atomically(dir_ / "chain.png", "through two links");
  EXPECT_TRUE(fs::is_symlink(dir_ / "chain.png"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "relative.png"));
  EXPECT_EQ(read(dir_ / "elsewhere" / "old.png"), "through two links");
  write_file_atomically(dir_ / "dangling.png", "new");
  EXPECT_TRUE(fs::is_symlink(dir_ / "dangling.png"));
  EXPECT_EQ(read(dir_ / "elsewhere" / "new.png"), "new");
  EXPECT_EQ(output_file_target(dir_ / "chain.png"), dir_ / "elsewhere" / "old.png");
  // Nothing temporary is left beside the targets.
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "elsewhere")) entries += !entry.path().empty();
  EXPECT_EQ(entries, 2);
}

TEST_F(OutputDir, RefusesDevicesFifosDirectoriesAndLinkLoopsNamingWhatItFound) {
  // A private device node with /dev/null's numbers: writing it would be harmless, replacing it is the bug.
  const fs::path device = dir_ / "device";
  const bool have_device = ::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  fs::create_symlink(fifo, dir_ / "to_fifo");
  fs::create_symlink(dir_ / "loop_b", dir_ / "loop_a");
  fs::create_symlink(dir_ / "loop_a", dir_ / "loop_b");
  if (have_device) {
    EXPECT_THAT(output_error([&] { write_file_atomically(device, "x"); }), HasSubstr("is a character device"));
    EXPECT_THAT(output_error([&] { check_output_file(device, "--out"); }), HasSubstr(device.string()));
    struct stat st {};
    ASSERT_EQ(::lstat(device.c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  }
  EXPECT_THAT(output_error([&] { write_file_atomically(fifo, "x"); }), HasSubstr("is a FIFO"));
  EXPECT_THAT(output_error([&] { write_file_atomically(dir_ / "to_fifo", "x"); }),
              HasSubstr("(links to " + fifo.string() + "): is a FIFO"));
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_THAT(output_error([&] { write_file_atomically(dir_, "x"); }), HasSubstr("is a directory"));
  EXPECT_THAT(output_error([&] { check_output_file(dir_ / "loop_a", "--out"); }),
              HasSubstr("too many levels of symbolic links"));
  EXPECT_THAT(output_error([&] { write_file_atomically("", "x"); }), HasSubstr("empty path"));
  // An output directory must be one.
  EXPECT_THAT(output_error([&] { check_output_directory(fifo, "--out"); }), HasSubstr("is a FIFO, expected a directory"));
  EXPECT_THAT(output_error([&] { check_output_directory(dir_ / "loop_a", "--out"); }),
              HasSubstr("Too many levels of symbolic links"));
  EXPECT_EQ(output_error([&] { check_output_directory(dir_ / "new" / "deeper", "--out"); }), "");
  EXPECT_FALSE(fs::exists(dir_ / "new")) << "a check makes nothing";
  std::ofstream(dir_ / "file") << "in the way";
  EXPECT_THAT(output_error([&] { check_output_directory(dir_ / "file" / "run", "--out"); }),
              HasSubstr("Not a directory"));
  EXPECT_THAT(output_error([&] { check_output_file(dir_ / "file" / "x.png", "--out"); }), HasSubstr("x.png"));
}

TEST_F(OutputDir, FoldersMadeForAFailedOutputAreRemovedWhatWasThereStays) {
  fs::create_directories(dir_ / "kept");
  {
    OutputDirectory made(dir_ / "kept" / "a" / "b");
    EXPECT_TRUE(fs::is_directory(dir_ / "kept" / "a" / "b"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "kept" / "a")) << "the empty folders it made are gone";
  EXPECT_TRUE(fs::is_directory(dir_ / "kept")) << "a folder that was there stays";
  {
    OutputDirectory made(dir_ / "kept" / "a" / "b");
    std::ofstream(dir_ / "kept" / "a" / "b" / "figure.png") << "png";
  }
  EXPECT_TRUE(fs::exists(dir_ / "kept" / "a" / "b" / "figure.png")) << "what was written stays";
  // A staged output that is never committed leaves nothing, not even its folder.
  {
    StagedOutput out(dir_ / "run" / "deep");
    write_file_atomically(out.path("run.json"), "{}");
  }
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

}  // namespace
}  // namespace campo
