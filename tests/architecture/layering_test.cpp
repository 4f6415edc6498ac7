// The architecture as a test: data flows one way through the rooms
//   core -> scene -> physics / sensors -> vehicles -> grid, planners -> metrics -> run -> render -> sweep -> reproduce
//   -> tools
// and the public headers (include/campo/) depend on nothing private. Each room's sources may
// include the public headers and the rooms listed for it here, never a room further down.
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = CAMPO_SOURCE_DIR;

// Room -> rooms it may include (besides itself and campo/).
const std::map<std::string, std::set<std::string>> kMayInclude = {
    {"core", {}},
    {"scene", {"core"}},
    {"physics", {"core", "scene"}},
    {"sensors", {"core", "scene"}},
    {"vehicles", {"core", "scene", "physics"}},
    {"grid", {}},
    {"planners", {"core", "scene", "sensors", "grid"}},
    {"metrics", {"core", "scene"}},
    {"run", {"core", "scene", "physics", "sensors", "vehicles", "grid", "planners", "metrics"}},
    {"render", {"core", "scene", "sensors", "run"}},
    {"sweep", {"core", "scene", "sensors", "run", "render", "planners"}},
    {"reproduce", {"core", "scene", "sensors", "grid", "metrics", "run", "render", "sweep", "planners"}},
};

struct Include {
  fs::path file;
  std::string target;  // as written: "scene/scene_mesh.hpp"
};

std::vector<Include> project_includes(const fs::path& dir) {
  static const std::regex include_line(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<Include> out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".hpp") continue;
    std::ifstream in(entry.path());
    std::string line;
    std::smatch m;
    while (std::getline(in, line)) {
      if (std::regex_search(line, m, include_line)) out.push_back({entry.path(), m[1].str()});
    }
  }
  return out;
}

std::string room_of(const std::string& include) { return include.substr(0, include.find('/')); }

TEST(Layering, EveryRoomIncludesOnlyTheRoomsUpstreamOfIt) {
  for (const auto& [room, allowed] : kMayInclude) {
    ASSERT_TRUE(fs::is_directory(kSource / room)) << room;
    for (const Include& inc : project_includes(kSource / room)) {
      const std::string target = room_of(inc.target);
      if (target == "campo" || target == room) continue;
      EXPECT_TRUE(allowed.count(target)) << inc.file.lexically_relative(kSource).string() << " includes "
                                         << inc.target << ": " << room << "/ may not reach " << target << "/";
    }
  }
}

TEST(Layering, EverySourceFolderIsARoomOfTheTable) {
  // A new room must take its place in the flow above (and in CMakeLists.txt's list).
  const std::set<std::string> not_rooms = {"include", "tools", "tests", "bench", "fuzz", "docs", "scenes",
                                           "examples", "build", "python", "web"};
  for (const auto& entry : fs::directory_iterator(kSource)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name.starts_with(".") || name.starts_with("build") || not_rooms.count(name)) continue;
    bool has_sources = false;
    for (const auto& f : fs::directory_iterator(entry.path())) has_sources |= f.path().extension() == ".cpp";
    if (has_sources) EXPECT_TRUE(kMayInclude.count(name)) << name << "/ holds sources but is not in kMayInclude";
  }
}

TEST(Layering, PublicHeadersIncludeOnlyPublicHeaders) {
  for (const Include& inc : project_includes(kSource / "include" / "campo")) {
    EXPECT_EQ(room_of(inc.target), "campo") << inc.file.filename().string() << " includes private " << inc.target;
  }
}

}  // namespace
}  // namespace campo
