// The architecture as a test: data flows one way through the rooms
//   core -> scene -> physics / sensors -> vehicles -> grid, planners -> metrics -> run -> render -> sweep -> session
//   -> reproduce -> tools, python
// Each room's sources may include the rooms listed for it here, never a room further down, and the public
// headers (include/campo/) whose floor is the room itself or one of those. A public header's floor is the
// room that implements it (the room of the source whose first include it is); a header that no source
// implements (plain data, the plugin entry point) stands on the highest floor of what it includes. A public
// header includes only public headers, on its floor or below it: the public API is self-contained and an
// embedding program that links the library sees no arrow back up.
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>
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
    // A vehicle reports its state as an estimator would (campo/state_estimation.hpp, StateError).
    {"vehicles", {"core", "scene", "physics", "sensors"}},
    {"grid", {"core"}},
    // The planner contract (campo/planner.hpp) reads a VehicleState and gives commands: campo/vehicle.hpp.
    {"planners", {"core", "scene", "sensors", "vehicles", "grid"}},
    // Measured on what the loop records (campo/episode_record.hpp): the vehicle's states and commands, the
    // planner's decisions, the clearances as the physics measures them (campo/world.hpp).
    {"metrics", {"core", "scene", "physics", "vehicles", "planners"}},
    {"run", {"core", "scene", "physics", "sensors", "vehicles", "grid", "planners", "metrics"}},
    {"render", {"core", "scene", "sensors", "run"}},
    {"sweep", {"core", "scene", "sensors", "run", "render", "planners"}},
    // A run from its inputs to its directory, and one sweep item (SweepItem): every room that takes part.
    {"session",
     {"core", "scene", "physics", "sensors", "vehicles", "grid", "planners", "metrics", "run", "render", "sweep"}},
    {"reproduce", {"core", "scene", "sensors", "grid", "metrics", "run", "render", "sweep", "planners"}},
    // The command line parses arguments and prints: it may call every room of the library.
    {"tools",
     {"core", "scene", "physics", "sensors", "vehicles", "grid", "planners", "metrics", "run", "render", "sweep",
      "session", "reproduce"}},
    // The Python module is a program embedding the library: every room of it, never the command line.
    {"python",
     {"core", "scene", "physics", "sensors", "vehicles", "grid", "planners", "metrics", "run", "render", "sweep",
      "session", "reproduce"}},
};

// Includes that break the table today, each with the issue that removes it; nothing else may.
const std::set<std::pair<std::string, std::string>> kKnownExceptions = {};

const std::set<std::string> kLibraryRooms = {"core",    "scene",   "physics", "sensors", "vehicles", "grid",
                                             "planners", "metrics", "run",     "render",  "sweep",    "session",
                                             "reproduce"};

struct Include {
  fs::path file;
  std::string target;  // as written: "scene/scene_mesh.hpp"
};

// The project includes of every source under `dir` (its subfolders too: python/bindings/, tools/slurm/).
std::vector<Include> project_includes(const fs::path& dir) {
  static const std::regex include_line(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<Include> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
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

std::string source_path(const fs::path& file) { return file.lexically_relative(kSource).generic_string(); }

bool known_exception(const Include& inc) { return kKnownExceptions.count({source_path(inc.file), inc.target}) > 0; }

// The rooms below `room`: those it may include, and theirs, down to core.
std::set<std::string> rooms_below(const std::string& room) {
  std::set<std::string> below;
  std::vector<std::string> todo = {room};
  while (!todo.empty()) {
    const std::string r = todo.back();
    todo.pop_back();
    const auto it = kMayInclude.find(r);
    if (it == kMayInclude.end()) continue;
    for (const std::string& next : it->second) {
      if (below.insert(next).second) todo.push_back(next);
    }
  }
  return below;
}

bool at_or_below(const std::string& floor, const std::string& room) {
  return floor == room || rooms_below(room).count(floor) > 0;
}

// "campo/scene.hpp" -> "scene.hpp"
std::string public_name(const std::string& include) { return include.substr(include.find('/') + 1); }

// Public header (file name) -> its floor (the room that implements it); "" when none could be given.
std::map<std::string, std::string> public_header_floors() {
  std::map<std::string, std::string> floor;
  std::map<std::string, std::vector<std::string>> includes;  // public header -> public headers it includes
  for (const auto& entry : fs::directory_iterator(kSource / "include" / "campo")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".hpp") floor[name] = "";
  }
  floor["version.hpp"] = "core";  // generated from version.hpp.in, implemented by core/version.cpp
  for (const Include& inc : project_includes(kSource / "include" / "campo")) {
    if (room_of(inc.target) == "campo") includes[inc.file.filename().string()].push_back(public_name(inc.target));
  }
  // Implemented: the room of a library source whose first include the header is.
  for (const std::string& room : kLibraryRooms) {
    for (const auto& entry : fs::directory_iterator(kSource / room)) {
      if (entry.path().extension() != ".cpp") continue;
      static const std::regex first_include(R"re(^\s*#\s*include\s*"campo/([^"]+)")re");
      std::ifstream in(entry.path());
      std::string line;
      std::smatch m;
      while (std::getline(in, line)) {
        if (line.find("#include") == std::string::npos) continue;
        if (std::regex_search(line, m, first_include)) {
          std::string& f = floor[m[1].str()];
          EXPECT_TRUE(f.empty() || f == room) << "campo/" << m[1].str() << " is implemented both in " << f
                                              << "/ and in " << room << "/";
          f = room;
        }
        break;
      }
    }
  }
  // Not implemented: the floor of what it includes that all the rest is at or below; repeated until no
  // header gains a floor, so a header-only one may include another.
  for (bool changed = true; changed;) {
    changed = false;
    for (auto& [name, f] : floor) {
      if (!f.empty()) continue;
      std::string top = "core";
      bool known = true;
      for (const std::string& dep : includes[name]) {
        const std::string& g = floor[dep];
        if (g.empty()) known = false;
        else if (at_or_below(top, g)) top = g;
      }
      if (known) {
        f = top;
        changed = true;
      }
    }
  }
  return floor;
}

TEST(Layering, EveryRoomIncludesOnlyTheRoomsUpstreamOfIt) {
  for (const auto& [room, allowed] : kMayInclude) {
    ASSERT_TRUE(fs::is_directory(kSource / room)) << room;
    for (const Include& inc : project_includes(kSource / room)) {
      const std::string target = room_of(inc.target);
      if (target == "campo" || target == room || known_exception(inc)) continue;
      EXPECT_TRUE(allowed.count(target)) << source_path(inc.file) << " includes " << inc.target << ": " << room
                                         << "/ may not reach " << target << "/";
    }
  }
}

TEST(Layering, TheKnownExceptionsStillExist) {
  // Once an exception is removed from the code, it goes from the table too.
  for (const auto& [file, target] : kKnownExceptions) {
    bool found = false;
    for (const Include& inc : project_includes(kSource / room_of(file))) found |= source_path(inc.file) == file && inc.target == target;
    EXPECT_TRUE(found) << file << " no longer includes " << target << ": remove it from kKnownExceptions";
  }
}

TEST(Layering, EveryRoomIncludesOnlyPublicHeadersAtOrBelowIt) {
  const std::map<std::string, std::string> floor = public_header_floors();
  for (const auto& [room, allowed] : kMayInclude) {
    for (const Include& inc : project_includes(kSource / room)) {
      if (room_of(inc.target) != "campo") continue;
      const auto it = floor.find(public_name(inc.target));
      ASSERT_NE(it, floor.end()) << source_path(inc.file) << " includes " << inc.target << ", no public header";
      EXPECT_TRUE(at_or_below(it->second, room))
          << source_path(inc.file) << " includes " << inc.target << ", implemented in " << it->second << "/ above "
          << room << "/";
    }
  }
}

TEST(Layering, EverySourceFolderIsARoomOfTheTable) {
  // A new room must take its place in the flow above (and in CMakeLists.txt's list).
  const std::set<std::string> not_rooms = {"include", "tests", "bench", "fuzz", "docs", "scenes",
                                           "examples", "build", "web"};
  for (const auto& entry : fs::directory_iterator(kSource)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name.starts_with(".") || name.starts_with("build") || not_rooms.count(name)) continue;
    bool has_sources = false;
    for (const auto& f : fs::recursive_directory_iterator(entry.path())) has_sources |= f.path().extension() == ".cpp";
    if (has_sources) EXPECT_TRUE(kMayInclude.count(name)) << name << "/ holds sources but is not in kMayInclude";
  }
}

TEST(Layering, PublicHeadersIncludeOnlyPublicHeaders) {
  for (const Include& inc : project_includes(kSource / "include" / "campo")) {
    EXPECT_EQ(room_of(inc.target), "campo") << inc.file.filename().string() << " includes private " << inc.target;
  }
}

TEST(Layering, EveryPublicHeaderHasAFloor) {
  for (const auto& [name, floor] : public_header_floors()) {
    EXPECT_TRUE(kMayInclude.count(floor)) << "campo/" << name << ": no floor (what it includes has no one top)";
  }
}

TEST(Layering, PublicHeadersIncludeOnlyHeadersAtOrBelowTheirFloor) {
  const std::map<std::string, std::string> floor = public_header_floors();
  for (const Include& inc : project_includes(kSource / "include" / "campo")) {
    if (room_of(inc.target) != "campo") continue;
    const std::string& own = floor.at(inc.file.filename().string());
    const std::string& theirs = floor.at(public_name(inc.target));
    EXPECT_TRUE(at_or_below(theirs, own)) << "campo/" << inc.file.filename().string() << " (implemented in " << own
                                          << "/) includes " << inc.target << ", implemented in " << theirs
                                          << "/ above it";
  }
}

}  // namespace
}  // namespace campo
