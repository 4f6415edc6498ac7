// Every command that writes a file writes only what is its own: an output path
// that is a device, a FIFO or a directory where a file is expected is refused
// (exit 2) before any work and left as it was; a symbolic link is followed and
// its target written; a full or read-only file system is exit 2 with the path
// and the system's reason, and no empty or partial output folder is left.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include "tests/cli_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::Result;
using testing::slurp;

// A two-second flight on a plane: cheap enough to make a run and a two-run sweep per test.
constexpr const char* kScene = R"j({"world": {"time_limit_s": 2}, "objects": [
  {"alias": "ground", "type": "plane"},
  {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
   "planner": {"name": "straight", "params": {"speed_mps": 1.0}},
   "mission": {"waypoints": [{"position_m": [8, 0, 1.5]}]}}]})j";

// Two runs along one numeric axis, so `campo table` draws a chart.
constexpr const char* kSpec = R"({"campo_sweep": 1, "name": "outputs", "scenes": ["scene.json"],
  "axes": [{"name": "speed", "values": [1.0, 2.0], "set": ["/objects/drone/planner/params/speed_mps"]}]})";

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The kind of file at `path`, links not followed: "file", "dir", "fifo", "chr", "link", "none".
std::string kind_at(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "none";
  if (S_ISLNK(st.st_mode)) return "link";
  if (S_ISCHR(st.st_mode)) return "chr";
  if (S_ISFIFO(st.st_mode)) return "fifo";
  if (S_ISDIR(st.st_mode)) return "dir";
  return S_ISREG(st.st_mode) ? "file" : "other";
}

class Outputs : public testing::CliTest {
 protected:
  // A run and a sweep (its runs' files kept) to draw from, made once per test that needs them.
  fs::path run() {
    const fs::path out = dir_ / "run";
    if (!fs::exists(out)) {
      write("scene.json", kScene);
      const Result r = campo("run " + (dir_ / "scene.json").string() + " --out " + out.string());
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    return out;
  }
  fs::path sweep() {
    const fs::path out = dir_ / "sweep";
    if (!fs::exists(out)) {
      write("scene.json", kScene);
      write("spec.json", kSpec);
      const Result r =
          campo("sweep " + (dir_ / "spec.json").string() + " --jobs 1 --keep-runs --out " + out.string());
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    return out;
  }

  // Every command that writes one file, with OUT standing for that file (its extension given).
  struct FileCommand {
    std::string extension;
    std::string args;
  };
  std::vector<FileCommand> file_commands() {
    const std::string r = run().string(), s = sweep().string();
    return {{".png", "plot " + s + " --x speed --y path_length_m --out OUT"},
            {".png", "table " + s + " --chart OUT"},
            {".mp4", "render " + r + " --kind video --out OUT"},
            {".html", "render " + r + " --kind replay --out OUT"},
            {".json", "bench lidar --json OUT"},
            {".md", "reproduce --quick --work " + (dir_ / "work").string() + " --report OUT"}};
  }
  // Every command that writes into a directory, with OUT standing for it.
  std::vector<std::string> directory_commands() {
    const std::string scene = (dir_ / "scene.json").string();
    return {"run " + scene + " --out OUT",
            "sweep " + (dir_ / "spec.json").string() + " --out OUT",
            "merge " + sweep().string() + " --out OUT",
            "render " + run().string() + " --kind map --out OUT",
            "scan " + scene + " --out OUT",
            "reproduce --quick --work OUT --report " + (dir_ / "report" / "r.md").string()};
  }

  static std::string with_out(std::string args, const fs::path& out) {
    return args.replace(args.find("OUT"), 3, quoted(out.string()));
  }

  // `campo ARGS` inside a private mount namespace where a fresh tmpfs with `options` is mounted
  // at dir_/mnt (OUT in ARGS stands for dir_/mnt/out); what the command left in the mount is
  // listed before the namespace goes. nullopt where mounting is not allowed (not root).
  struct MountedResult {
    Result result;
    std::vector<std::string> left;  ///< paths under the mount, relative to it
  };
  std::optional<MountedResult> campo_on_tmpfs(const std::string& options, const std::string& args) {
    const fs::path mnt = dir_ / "mnt";
    fs::create_directories(mnt);
    const std::string script = "mount -t tmpfs -o " + options + " tmpfs " + quoted(mnt.string()) +
                               " || exit 99; " + CAMPO_BINARY + " " + with_out(args, mnt / "out") + " >" +
                               quoted((dir_ / "stdout").string()) + " 2>" + quoted((dir_ / "stderr").string()) +
                               "; echo $? >" + quoted((dir_ / "code").string()) + "; cd " + quoted(mnt.string()) +
                               " && find . -mindepth 1 >" + quoted((dir_ / "listing").string());
    fs::remove(dir_ / "code");
    const int status = std::system(("unshare -m sh -c " + quoted(script) + " 2>/dev/null").c_str());
    if (!WIFEXITED(status) || WEXITSTATUS(status) == 99 || !fs::exists(dir_ / "code")) return std::nullopt;
    MountedResult m{{std::stoi(slurp(dir_ / "code")), slurp(dir_ / "stdout"), slurp(dir_ / "stderr")},
                    testing::lines_of(slurp(dir_ / "listing"))};
    return m;
  }
};

TEST_F(Outputs, FileOutputsRefuseDevicesFifosAndDirectoriesAndLeaveThemAsTheyWere) {
  for (const FileCommand& c : file_commands()) {
    // A private device node with /dev/null's numbers (writing it is harmless; replacing it was the bug).
    const fs::path device = dir_ / ("device" + c.extension);
    const bool have_device = ::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
    const fs::path fifo = dir_ / ("fifo" + c.extension);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
    const fs::path folder = dir_ / ("folder" + c.extension);
    fs::create_directories(folder);
    std::vector<std::pair<fs::path, std::string>> cases{{fifo, "fifo"}, {folder, "dir"}};
    if (have_device) cases.emplace_back(device, "chr");
    for (const auto& [path, kind] : cases) {
      const Result r = campo(with_out(c.args, path));
      EXPECT_EQ(r.exit_code, 2) << c.args << " with " << kind << ": " << r.err;
      EXPECT_THAT(r.err, HasSubstr("error: ")) << c.args;
      EXPECT_THAT(r.err, HasSubstr(path.string())) << c.args;
      EXPECT_THAT(r.out + r.err, Not(HasSubstr("wrote"))) << c.args;
      EXPECT_EQ(kind_at(path), kind) << c.args << ": the " << kind << " was replaced";
    }
    EXPECT_TRUE(fs::is_empty(folder)) << c.args;
    fs::remove(device);
    fs::remove(fifo);
    fs::remove(folder);
  }
  EXPECT_FALSE(fs::exists(dir_ / "work")) << "reproduce made its work folder before refusing its report";
}

TEST_F(Outputs, DirectoryOutputsRefuseDevicesFifosAndFiles) {
  write("scene.json", kScene);
  write("spec.json", kSpec);
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const fs::path device = dir_ / "device";
  const bool have_device = ::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
  const std::string file = write("file", "mine");
  for (const std::string& args : directory_commands()) {
    std::vector<std::pair<fs::path, std::string>> cases{{fifo, "fifo"}, {file, "file"}};
    if (have_device) cases.emplace_back(device, "chr");
    for (const auto& [path, kind] : cases) {
      const Result r = campo(with_out(args, path));
      EXPECT_EQ(r.exit_code, 2) << args << " with " << kind << ": " << r.err;
      EXPECT_THAT(r.err, HasSubstr("error: ")) << args;
      EXPECT_THAT(r.err, HasSubstr(path.string())) << args;
      EXPECT_EQ(kind_at(path), kind) << args;
    }
  }
  EXPECT_EQ(slurp(file), "mine");
}

TEST_F(Outputs, SymbolicLinksAreFollowedAndTheirTargetsWritten) {
  fs::create_directories(dir_ / "figures");
  std::ofstream(dir_ / "figures" / "old.png") << "an older figure";
  for (const FileCommand& c : file_commands()) {
    if (c.args.rfind("bench", 0) == 0 || c.args.rfind("reproduce", 0) == 0) continue;  // minutes of work
    const fs::path target = dir_ / "figures" / ("target" + c.extension);
    fs::remove(target);
    // One link to a file that exists, one to a file that does not yet.
    for (const bool exists : {true, false}) {
      if (exists) std::ofstream(target) << "old";
      const fs::path link = dir_ / ("link" + c.extension);
      fs::remove(link);
      fs::create_symlink(fs::path("figures") / target.filename(), link);  // relative to the link's folder
      const Result r = campo(with_out(c.args, link));
      ASSERT_EQ(r.exit_code, 0) << c.args << ": " << r.err;
      EXPECT_EQ(kind_at(link), "link") << c.args << ": the link was replaced";
      EXPECT_EQ(kind_at(target), "file") << c.args;
      EXPECT_GT(fs::file_size(target), 100u) << c.args;
      fs::remove(target);
    }
  }
  // An output directory that is a link to one: the files go into its target.
  fs::create_directories(dir_ / "real_run");
  fs::create_directory_symlink(dir_ / "real_run", dir_ / "run_link");
  const Result r = campo("run " + (dir_ / "scene.json").string() + " --out " + (dir_ / "run_link").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(kind_at(dir_ / "run_link"), "link");
  EXPECT_TRUE(fs::exists(dir_ / "real_run" / "run.json"));
  EXPECT_EQ(slurp(dir_ / "figures" / "old.png"), "an older figure");
}

// Every command on a file system with almost no room: exit 2 naming the file and "No space left
// on device", and no empty or partial folder left behind (what is left is whole files only).
TEST_F(Outputs, AFullFileSystemIsExitTwoWithTheReasonAndLeavesNoFolders) {
  const std::string r = run().string(), s = sweep().string();
  const std::vector<std::string> commands{
      "run " + (dir_ / "scene.json").string() + " --out OUT/run",
      "sweep " + (dir_ / "spec.json").string() + " --jobs 1 --keep-runs --out OUT/sweep",
      "merge " + s + " --out OUT/merged",  // with the runs' kept files
      "table " + s + " --chart OUT.png",
      "plot " + s + " --x speed --y path_length_m --out OUT.png",
      "render " + r + " --kind map --kind side --out OUT/figures",
      "render " + r + " --kind video --out OUT.mp4",
      "render " + r + " --kind replay --out OUT.html",
      "scan " + (dir_ / "scene.json").string() + " --sensor scanner3d --pose 0,0,1.5,0,0,0 --out OUT/scan"};
  for (const std::string& args : commands) {
    // 8 KiB: room for a folder and a small file, not for a figure, a run or a video.
    const auto m = campo_on_tmpfs("size=8k", args);
    if (!m) GTEST_SKIP() << "cannot mount a tmpfs in a private namespace here (needs root)";
    EXPECT_EQ(m->result.exit_code, 2) << args << ": " << m->result.err;
    EXPECT_THAT(m->result.err, HasSubstr("error: ")) << args;
    EXPECT_THAT(m->result.err, HasSubstr("No space left on device")) << args;
    EXPECT_THAT(m->result.err, HasSubstr((dir_ / "mnt").string())) << args << ": the error names no path";
    EXPECT_THAT(m->result.err, Not(HasSubstr("internal error"))) << args;
    for (const std::string& left : m->left) {
      // Whole files of a sweep (its manifest, its log of finished runs) may stay; folders may not.
      EXPECT_TRUE(left == "./out" || left.rfind("./out/sweep", 0) == 0) << args << " left " << left;
      EXPECT_THAT(left, Not(HasSubstr("runs"))) << args << " left " << left;
      EXPECT_THAT(left, Not(HasSubstr(".staging"))) << args << " left " << left;
      EXPECT_THAT(left, Not(HasSubstr(".partial"))) << args << " left " << left;
    }
  }
}

TEST_F(Outputs, AReadOnlyFileSystemIsRefusedBeforeAnyWork) {
  write("scene.json", kScene);
  write("spec.json", kSpec);
  std::vector<std::string> commands;
  for (const FileCommand& c : file_commands()) commands.push_back(with_out(c.args, "OUT" + c.extension));
  for (const std::string& args : directory_commands()) commands.push_back(args);
  for (std::string args : commands) {
    // with_out quoted the placeholder above: unquote it for the mounted run.
    for (std::size_t at; (at = args.find("'OUT")) != std::string::npos;) {
      const std::size_t end = args.find('\'', at + 1);
      args = args.substr(0, at) + args.substr(at + 1, end - at - 1) + args.substr(end + 1);
    }
    const auto m = campo_on_tmpfs("ro", args);
    if (!m) GTEST_SKIP() << "cannot mount a tmpfs in a private namespace here (needs root)";
    EXPECT_EQ(m->result.exit_code, 2) << args << ": " << m->result.err;
    EXPECT_THAT(m->result.err, HasSubstr("Read-only file system")) << args;
    EXPECT_THAT(m->result.err, HasSubstr((dir_ / "mnt").string())) << args;
    EXPECT_TRUE(m->left.empty()) << args;
  }
}

}  // namespace
}  // namespace campo
