// The planner registry with plugins loaded in this process: what a plugin
// registers, where each planner comes from, and every way a plugin is refused
// (tests/plugins/ builds the fixture plugins).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/plugin.hpp"
#include "campo/scene_loader.hpp"
#include "campo/version.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

fs::path fixture(const std::string& name) { return fs::path(CAMPO_TEST_PLUGIN_DIR) / (name + ".so"); }

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the InputError loading `path` throws ("" when it loads).
std::string refusal(const fs::path& path) {
  try {
    load_planner_plugin(path, "test", "/plugins/0");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "test");
    EXPECT_EQ(e.pointer(), "/plugins/0");
    return e.what();
  }
  return "";
}

std::vector<std::string> names(const std::vector<PlannerEntry>& entries) {
  std::vector<std::string> out;
  for (const PlannerEntry& e : entries) out.push_back(e.name);
  return out;
}

std::unique_ptr<Planner> make_nothing(const ParamsBlock&, const PlannerContext&) { return nullptr; }

class PluginRegistry : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_plugins_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(PluginRegistry, BuiltInPlannersComeFirstAndSayTheyAreBuiltIn) {
  const std::vector<PlannerEntry> entries = planner_registry();
  ASSERT_GE(entries.size(), 4u);
  const std::vector<std::string> all = names(entries);
  EXPECT_THAT(std::vector<std::string>(all.begin(), all.begin() + 4),
              ElementsAre("straight", "depth_reactive", "dstar_lite_3d", "rover_route"));
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(entries[i].source, "built-in");
    EXPECT_TRUE(entries[i].source_sha256.empty());
  }
  EXPECT_EQ(planner_provenance("straight"), (nlohmann::json{{"name", "straight"}, {"source", "built-in"}}));
  EXPECT_EQ(planner_provenance(""), (nlohmann::json{{"name", "straight"}, {"source", "built-in"}}));
}

TEST_F(PluginRegistry, AProgramsOwnPlannersAreAddedExplicitlyWithItsSourceAndChecked) {
  add_linked_planners({{"linked_test_planner", "added by the test program itself", &make_nothing,
                        {VehicleType::rover}}},
                      "test_planners");
  const std::vector<PlannerEntry> entries = planner_registry();
  const auto it = std::find_if(entries.begin(), entries.end(),
                               [](const PlannerEntry& e) { return e.name == "linked_test_planner"; });
  ASSERT_NE(it, entries.end());
  EXPECT_EQ(it->description, "added by the test program itself");
  EXPECT_EQ(it->source, "test_planners");
  // The registry, not the factory, refuses a vehicle the planner does not declare.
  PlannerSpec spec;
  spec.name = "linked_test_planner";
  spec.params.file = "scene.json";
  spec.params.pointer = "/objects/0/planner/params";
  try {
    create_planner(spec, {VehicleType::quadrotor, nullptr});
    ADD_FAILURE() << "a quadrotor was given a rover-only planner";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scene.json: /objects/0/planner/params: planner linked_test_planner drives a "
                                    "rover only, not a quadrotor"));
  }
  EXPECT_THROW(add_linked_planners({{"linked_test_planner", "again", &make_nothing, {VehicleType::rover}}}, "again"),
               InputError);
  EXPECT_THROW(add_linked_planners({{"no_vehicle", "none", &make_nothing, {}}}, "empty"), InputError);
}

TEST_F(PluginRegistry, APluginAddsEachPlannerItRegistersWithItsFileAndDigest) {
  const std::size_t before = planner_registry().size();
  const LoadedPlugin plugin = load_planner_plugin(fixture("two_planners"), "test", "/plugins/0");
  EXPECT_EQ(plugin.path, fixture("two_planners").string());
  EXPECT_EQ(plugin.sha256, sha256_hex(file_bytes(fixture("two_planners"))));
  EXPECT_THAT(plugin.planners, ElementsAre("fixture_goto", "fixture_hold"));

  const std::vector<PlannerEntry> entries = planner_registry();
  ASSERT_EQ(entries.size(), before + 2);
  EXPECT_EQ(entries[before].name, "fixture_goto");
  EXPECT_EQ(entries[before].description, "fixture: straight to each waypoint");
  EXPECT_EQ(entries[before + 1].name, "fixture_hold");
  for (const PlannerEntry& e : {entries[before], entries[before + 1]}) {
    EXPECT_EQ(e.source, plugin.path);
    EXPECT_EQ(e.source_sha256, plugin.sha256);
  }
  EXPECT_EQ(planner_provenance("fixture_hold"),
            (nlohmann::json{{"name", "fixture_hold"}, {"source", plugin.path}, {"sha256", plugin.sha256}}));
  ASSERT_EQ(loaded_plugins().size(), 1u);
  EXPECT_EQ(loaded_plugins()[0].path, plugin.path);

  // The plugin's factory reads its parameters strictly, as built-in planners do.
  PlannerSpec spec;
  spec.name = "fixture_hold";
  spec.params.values = {{"hold_s", 2.0}};
  spec.params.file = "scene.json";
  spec.params.pointer = "/objects/0/planner/params";
  const std::unique_ptr<Planner> hold = create_planner(spec, {VehicleType::quadrotor, nullptr});
  ASSERT_NE(hold, nullptr);
  EXPECT_EQ(hold->parameters(), (nlohmann::json{{"hold_s", 2.0}}));
  Observation o;
  o.time_s = 1.0;
  EXPECT_EQ(hold->plan(o).status, PlanStatus::running);
  o.time_s = 2.5;
  EXPECT_EQ(hold->plan(o).status, PlanStatus::aborted);
  spec.params.values = {{"hold_for", 2.0}};
  try {
    create_planner(spec, {VehicleType::quadrotor, nullptr});
    ADD_FAILURE() << "an unknown parameter was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scene.json: /objects/0/planner/params/hold_for: unknown key"));
  }
}

TEST_F(PluginRegistry, APluginLoadedAgainUnderAnyPathIsLoadedOnce) {
  const LoadedPlugin first = load_planner_plugin(fixture("two_planners"), "test", "/plugins/0");
  const std::size_t count = planner_registry().size();
  fs::create_symlink(fixture("two_planners"), dir_ / "link.so");
  EXPECT_EQ(load_planner_plugin(fixture("two_planners"), "test", "/plugins/1").path, first.path);
  EXPECT_EQ(load_planner_plugin(dir_ / "link.so", "test", "/plugins/2").path, first.path);
  EXPECT_EQ(planner_registry().size(), count);
  EXPECT_EQ(loaded_plugins().size(), 1u);
}

TEST_F(PluginRegistry, AMissingFileIsRefusedWithTheLoadersReason) {
  const fs::path missing = dir_ / "missing.so";
  const std::string message = refusal(missing);
  EXPECT_THAT(message, HasSubstr("test: /plugins/0: plugin " + missing.string() + ": cannot load it ("));
  EXPECT_THAT(message, HasSubstr("No such file or directory"));
  EXPECT_THAT(message, HasSubstr("expected a planner plugin"));
}

TEST_F(PluginRegistry, AFileThatIsNoSharedLibraryIsRefusedWithTheLoadersReason) {
  const fs::path text = dir_ / "notes.so";
  std::ofstream(text) << std::string(200, '#') << "\nnot a shared library\n";
  const std::string message = refusal(text);
  EXPECT_THAT(message, HasSubstr("plugin " + text.string() + ": cannot load it ("));
  EXPECT_THAT(message, HasSubstr("invalid ELF header"));
}

TEST_F(PluginRegistry, ALibraryWithoutItsOwnMarkerIsNoPlugin) {
  // not_a_plugin.so depends on marker_library.so, which defines the marker: dlsym finds it there,
  // and the loader must not take the dependency's marker for the library's own.
  const std::string message = refusal(fixture("not_a_plugin"));
  EXPECT_THAT(message, HasSubstr("plugin " + fixture("not_a_plugin").string() + ": not a campo planner plugin: it "
                                 "does not define the symbol campo_plugin_abi_version"));
  EXPECT_THAT(message, HasSubstr("CAMPO_REGISTER_PLANNERS"));
}

TEST_F(PluginRegistry, APluginWithoutItsEntryPointIsRefusedNamingTheMissingSymbol) {
  EXPECT_THAT(refusal(fixture("no_entry")),
              HasSubstr("plugin " + fixture("no_entry").string() + ": defines campo_plugin_abi_version but not the "
                                                                   "symbol campo_plugin_register_planners"));
}

TEST_F(PluginRegistry, APluginOfAnotherAbiVersionIsRefusedWithBothVersions) {
  const std::string message = refusal(fixture("abi_mismatch"));
  EXPECT_THAT(message, HasSubstr("plugin " + fixture("abi_mismatch").string() +
                                 ": built against campo plugin ABI version 999, but this campo (" +
                                 std::string(CAMPO_VERSION_STRING) + ") loads plugin ABI version " +
                                 std::to_string(CAMPO_PLUGIN_ABI_VERSION) + ": rebuild it against this campo"));
  EXPECT_EQ(planner_provenance("fixture_other_abi")["source"], nullptr);
}

TEST_F(PluginRegistry, APluginThatRegistersNothingIsRefused) {
  EXPECT_THAT(refusal(fixture("no_planner")),
              HasSubstr("plugin " + fixture("no_planner").string() + ": registers no planner; expected at least one "
                                                                     "registrar.add"));
}

TEST_F(PluginRegistry, ANameOfABuiltInPlannerIsRefusedAndTheBuiltInStays) {
  const std::size_t count = planner_registry().size();
  EXPECT_THAT(refusal(fixture("name_clash")),
              HasSubstr("plugin " + fixture("name_clash").string() +
                        ": registers planner \"straight\", a name already taken by the built-in planner of that name"));
  EXPECT_EQ(planner_registry().size(), count);
  EXPECT_EQ(planner_provenance("straight")["source"], "built-in");
}

TEST_F(PluginRegistry, ANameAnotherPluginRegisteredIsRefusedNamingBothFiles) {
  const fs::path copy = dir_ / "copy_of_two_planners.so";
  fs::copy_file(fixture("two_planners"), copy);
  load_planner_plugin(fixture("two_planners"), "test", "/plugins/0");
  const std::size_t count = planner_registry().size();
  const std::string message = refusal(copy);
  EXPECT_THAT(message, HasSubstr("plugin " + copy.string() + ": registers planner \"fixture_goto\", a name already "
                                 "taken by planner \"fixture_goto\" of " + fixture("two_planners").string()));
  EXPECT_EQ(planner_registry().size(), count);
  EXPECT_EQ(loaded_plugins().size(), 1u);
}

}  // namespace
}  // namespace campo
