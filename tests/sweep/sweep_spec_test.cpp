// Sweep specs: strict reading, expansion into runs, start jitter.
#include "sweep/sweep_spec.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/random.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"
#include "campo/version.hpp"
#include "scene/scene_overrides.hpp"
#include "sweep/expansion.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class SweepSpecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_sweep_spec_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& text, const std::string& name = "spec.json") {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  // The error of reading and expanding `text`, or "" if it is valid.
  std::string error_of(const std::string& text) {
    try {
      expand_sweep(read_sweep_spec(write(text)));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(SweepSpecTest, ErrorsNameFilePointerAndExpectation) {
  const std::string spec = (dir_ / "spec.json").string();
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seed": 3})"),
              HasSubstr(spec + ":1:48: /seed: unknown key \"seed\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "speed", "values": [1], "set": ["/world/time_limit_s"], "colour": 1}]})"),
              HasSubstr(spec + ":2:102: /axes/0/colour (speed): unknown key \"colour\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"count": "3"}})"),
              HasSubstr(spec + ":1:58: /seeds/count: expected an integer in [1, 100000], got \"3\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": "two_barriers"})"),
              HasSubstr(spec + ":1:20: /scenes: expected an array of 1 to 100 elements"));
  EXPECT_THAT(error_of(R"({"scenes": ["two_barriers"]})"), HasSubstr("missing required key \"campo_sweep\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "Speed", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":2:38: /axes/0/name (Speed): expected an axis name"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "runs", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr("or a table column"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "v", "values": [1, 1.0], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":2:65: /axes/0/values/1 (v): expected values with distinct labels"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "start_jitter": {"vehicle": "drone"}})"),
              HasSubstr(spec + ":1:48: /start_jitter: missing required key \"radius_m\""));
}

// The fuzz target's entry: text read as if it were the spec file, its scene
// paths relative to that file.
TEST_F(SweepSpecTest, TextReadsAsTheFileItIsNamedAfter) {
  fs::copy_file(fs::path(CAMPO_SOURCE_DIR) / "scenes" / "two_barriers.json", dir_ / "mine.json");
  const fs::path named = dir_ / "never_written.json";
  const SweepSpec spec =
      read_sweep_spec_text(R"({"campo_sweep": 1, "scenes": ["mine.json"], "seeds": {"count": 2}})", named);
  EXPECT_EQ(spec.file, named);
  EXPECT_EQ(spec.name, "never_written");
  ASSERT_EQ(spec.scenes.size(), 1u);
  EXPECT_EQ(spec.scenes[0].file, dir_ / "mine.json");
  EXPECT_EQ(expand_sweep(spec).size(), 2u);
  try {
    read_sweep_spec_text(R"({"campo_sweep": 1, "scenes": []})", named);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), named.string());
    EXPECT_EQ(e.pointer(), "/scenes");
  }
}

TEST_F(SweepSpecTest, BadPointersFailBeforeAnythingRuns) {
  const std::string spec = (dir_ / "spec.json").string();
  // Not a pointer at all.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"objects/drone": 1}})"),
              HasSubstr(spec + ":1:56: /set/objects~1drone: expected a JSON pointer"));
  // A pointer through an alias the scene does not have.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "set": {"/objects/drones/planner/name": "straight"}})"),
              HasSubstr(spec + ": /set/~1objects~1drones~1planner~1name: in scene two_barriers: no element with "
                               "alias \"drones\""));
  // A key the scene format does not know: the run's scene is validated, naming the run.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                           "axes": [{"name": "x", "values": [1, 2], "set": ["/world/colour"]}]})"),
              HasSubstr(spec + ": /scenes/0: run two_barriers__x-1__seed-1: scenes/two_barriers.json: "
                               "/world/colour: unknown key"));
  // Two sources for one pointer, the seed included.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"/world/seed": 4}})"),
              HasSubstr(spec + ":1:56: /set/~1world~1seed: expected a pointer set in one place only"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"/world/time_limit_s": 4},
                           "axes": [{"name": "t", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":2:74: /axes/0/set/0 (t): expected a pointer set in one place only"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["missing.json"]})"),
              HasSubstr(spec + ": /scenes/0: cannot load the scene"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "start_jitter": {"vehicle": "goal", "radius_m": 1}})"),
              HasSubstr(spec + ": /start_jitter/vehicle: expected a vehicle of scene two_barriers, got \"goal\""));
}

TEST_F(SweepSpecTest, SetPointersTakeArrayIndicesAsRfc6901Writes) {
  const std::string spec = (dir_ / "spec.json").string();
  // two_barriers has 5 objects; "04" is not index 4, in an axis's "set" as in "set".
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                         "axes": [{"name": "v", "values": [1], "set": ["/objects/04/planner/params/speed_mps"]}]})"),
            spec + ": /axes/0/values/0: in scene two_barriers: expected an array index in [0, 5) without leading zeros "
                   "(RFC 6901) or the alias of an element of /objects, got \"04\" (a leading zero) at /objects/04");
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "set": {"/objects/+4/planner/name": "straight"}})"),
              HasSubstr(spec + ": /set/~1objects~1+4~1planner~1name: in scene two_barriers: no element with alias \"+4\" "
                               "at /objects/+4; expected an array index in [0, 5) without leading zeros (RFC 6901)"));
  // Index 4 as RFC 6901 writes it is the drone.
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                         "axes": [{"name": "v", "values": [1], "set": ["/objects/4/planner/params/speed_mps"]}]})"),
            "");
}

TEST_F(SweepSpecTest, RangeCountsAreCheckedBeforeTheyBecomeIntegers) {
  // to - from overflows to infinity: refused, not cast to a count (which would be undefined).
  const std::string spec = (dir_ / "spec.json").string();
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "axes": [{"name": "a",
                           "range": {"from": -1e308, "to": 1e308, "step": 1}, "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":2:67: /axes/0/range/step (a): expected a step giving at most "));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "axes": [{"name": "a",
                           "range": {"from": 0, "to": 1, "step": 1e-300}, "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":2:58: /axes/0/range/step (a): expected a step giving at most "));
}

TEST_F(SweepSpecTest, ExpandsScenesAxesAndSeedsInOrder) {
  // A scene beside the spec, by relative path, and a bundled one. Runs call a scene by its name (the
  // copy of two_barriers renamed "local"), as run.json does; the copy under its own name would be refused.
  nlohmann::json local = nlohmann::json::parse(std::ifstream(fs::path(CAMPO_SOURCE_DIR) / "scenes/two_barriers.json"));
  local["name"] = "local";
  write(local.dump(), "local.json");
  const SweepSpec spec = read_sweep_spec(write(R"({
    "campo_sweep": 1, "name": "order",
    "scenes": ["local.json", "two_barriers"],
    "set": {"/world/time_limit_s": 5, "/objects/drone/planner/name": "straight"},
    "axes": [{"name": "speed", "values": [0.5, 1], "set": ["/objects/drone/planner/params/speed_mps"]},
             {"name": "res", "values": [[16, 8], [32, 16], [64, 32]],
              "set": ["/objects/drone/sensors/scanner/resolution"]}],
    "seeds": {"first": 7, "count": 2}})"));
  EXPECT_EQ(spec.name, "order");
  const std::vector<SweepRun> runs = expand_sweep(spec);
  ASSERT_EQ(runs.size(), 2u * 2u * 3u * 2u);
  EXPECT_EQ(runs[0].name, "local__speed-0.5__res-16x8__seed-7");
  EXPECT_EQ(runs[1].name, "local__speed-0.5__res-16x8__seed-8");
  EXPECT_EQ(runs[2].name, "local__speed-0.5__res-32x16__seed-7");
  EXPECT_EQ(runs[6].name, "local__speed-1__res-16x8__seed-7");
  EXPECT_EQ(runs[12].name, "two_barriers__speed-0.5__res-16x8__seed-7");
  EXPECT_EQ(runs.back().name, "two_barriers__speed-1__res-64x32__seed-8");
  std::set<std::string> ids, names;
  for (const SweepRun& run : runs) {
    ids.insert(run.id);
    names.insert(run.name);
    EXPECT_EQ(run.planner, "straight");  // as the overrides set it
  }
  EXPECT_EQ(ids.size(), runs.size());
  EXPECT_EQ(names.size(), runs.size());

  const SweepRun& run = runs[3];
  EXPECT_EQ(run.scene, "local");
  EXPECT_EQ(run.scene_file, dir_ / "local.json");
  EXPECT_EQ(run.seed, 8u);
  EXPECT_EQ(run.params, nlohmann::json({{"speed", 0.5}, {"res", {32, 16}}}));
  // Fixed overrides (by pointer), then the axes in order, then the seed.
  EXPECT_EQ(override_texts(run.overrides), (std::vector<std::string>{"/objects/drone/planner/name=\"straight\"",
                                                                    "/world/time_limit_s=5",
                                                                    "/objects/drone/planner/params/speed_mps=0.5",
                                                                    "/objects/drone/sensors/scanner/resolution=[32,16]",
                                                                    "/world/seed=8"}));
  EXPECT_EQ(run.scene_sha256.size(), 64u);

  const nlohmann::json manifest = sweep_manifest(spec, runs);
  EXPECT_EQ(manifest["runs"].size(), runs.size());
  EXPECT_EQ(manifest["runs"][3]["id"], run.id);
  EXPECT_EQ(manifest["runs"][3]["name"], run.name);
  EXPECT_EQ(manifest["spec"]["name"], "order");
  EXPECT_EQ(manifest["spec_sha256"], spec_sha256(spec));
  EXPECT_EQ(manifest["campo_version"], CAMPO_VERSION_STRING);
}

// IDs come from what a run is, not where it sits in a spec: the same run has
// the same ID in another spec that orders things differently, and any change
// to the scene, a parameter or the seed gives another ID.
TEST_F(SweepSpecTest, RunIdsAreContentHashesStableAcrossSpecs) {
  const auto ids_by_name = [&](const std::string& text) {
    std::map<std::string, std::string> ids;
    for (const SweepRun& run : expand_sweep(read_sweep_spec(write(text)))) {
      EXPECT_EQ(run.id.size(), 16u);
      EXPECT_EQ(run.id.find_first_not_of("0123456789abcdef"), std::string::npos) << run.id;
      ids[run.name] = run.id;
    }
    return ids;
  };
  const auto first = ids_by_name(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
    "axes": [{"name": "limit", "values": [5, 6], "set": ["/world/time_limit_s"]}], "seeds": {"count": 2}})");
  const auto again = ids_by_name(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
    "axes": [{"name": "limit", "values": [5, 6], "set": ["/world/time_limit_s"]}], "seeds": {"count": 2}})");
  EXPECT_EQ(first, again);
  // Other order, other name, more values and seeds: the shared runs keep their IDs.
  const auto reordered = ids_by_name(R"({"campo_sweep": 1, "name": "other", "scenes": ["two_barriers"],
    "axes": [{"name": "limit", "values": [7, 6, 5], "set": ["/world/time_limit_s"]}],
    "seeds": {"first": 1, "count": 3}})");
  for (const auto& [name, id] : first) EXPECT_EQ(reordered.at(name), id) << name;
  std::set<std::string> distinct;
  for (const auto& [name, id] : reordered) distinct.insert(id);
  EXPECT_EQ(distinct.size(), reordered.size());
  // A change of scene content that the name does not show changes the ID.
  const auto changed = ids_by_name(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
    "set": {"/world/sensor_rate_hz": 20},
    "axes": [{"name": "limit", "values": [5, 6], "set": ["/world/time_limit_s"]}], "seeds": {"count": 2}})");
  for (const auto& [name, id] : first) EXPECT_NE(changed.at(name), id) << name;
}

// An ID hashes the version, the name and the run's document: the scene file with the run's overrides
// applied in order, as `campo run --set` applies them, however the expansion builds it (the seeds of one
// point share a document whose text has the seed's digits spliced in).
TEST_F(SweepSpecTest, RunIdsHashTheDocumentTheOverridesMake) {
  for (const std::string text : {
           std::string(R"({"campo_sweep": 1, "scenes": ["two_barriers", "wall"],
               "planners": ["straight", {"name": "depth_reactive", "params": {"speed_mps": 0.5}}],
               "set": {"/world/time_limit_s": 30},
               "axes": [{"name": "rate", "values": [10, 20], "set": ["/world/sensor_rate_hz"]}],
               "seeds": {"first": 7, "count": 5}})"),
           std::string(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
               "seeds": {"first": 18446744073709551610, "count": 6}})"),
           std::string(R"({"campo_sweep": 1, "scenes": ["trees_rolling_terrain"], "vary_scene_with_seed": true,
               "seeds": {"first": 1, "count": 3}})"),
           std::string(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"first": 8, "count": 3},
               "start_jitter": {"vehicle": "drone", "radius_m": 0.5}})"),
       }) {
    const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(text)));
    ASSERT_FALSE(runs.empty());
    std::size_t streamed = 0;
    for_each_sweep_run(read_sweep_spec(write(text)), {}, [&](const SweepRun& run) {
      ASSERT_LT(streamed, runs.size());
      EXPECT_EQ(run.id, runs[streamed].id);
      EXPECT_EQ(override_texts(run.overrides), override_texts(runs[streamed++].overrides));
    });
    EXPECT_EQ(streamed, runs.size());
    for (const SweepRun& run : runs) {
      nlohmann::json document = read_json_file(run.scene_file);
      for (const SceneOverride& o : run.overrides) apply_override(document, parse_override(o.text));
      EXPECT_EQ(run.id, sha256_hex(std::string(library_version()) + "\n" + run.name + "\n" + document.dump())
                            .substr(0, 16))
          << run.name;
      EXPECT_EQ(run.overrides.back().text.rfind("/world/seed=", 0) == 0,
                text.find("vary") == std::string::npos && text.find("jitter") == std::string::npos)
          << run.name;
    }
  }
}

// Runs differing in their seed alone share one validation: a spec of 10 x 10 points and 100 seeds
// validates 100 scenes, not 10,000 (campo sweep --list of 100,000 runs in about a second).
TEST_F(SweepSpecTest, SeedsOfOnePointShareOneValidation) {
  int checks = 0;
  const SweepSpec spec = read_sweep_spec(write(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
      "axes": [{"name": "a", "values": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10], "set": ["/world/time_limit_s"]},
               {"name": "b", "values": [1, 2, 3, 4, 5, 6, 8, 10, 12, 15], "set": ["/world/sensor_rate_hz"]}],
      "seeds": {"first": 0, "count": 100}})"));
  std::size_t runs = 0;
  for_each_sweep_run(spec, [&](const Scene&) { ++checks; }, [&](const SweepRun&) { ++runs; });
  EXPECT_EQ(runs, 10000u);
  EXPECT_EQ(checks, 100);
  // With the seeds varying the scene, each run is validated.
  checks = 0;
  const SweepSpec varying = read_sweep_spec(write(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
      "seeds": {"first": 0, "count": 4}, "start_jitter": {"vehicle": "drone", "radius_m": 0.5}})"));
  for_each_sweep_run(varying, [&](const Scene&) { ++checks; }, [](const SweepRun&) {});
  EXPECT_EQ(checks, 4);
}

TEST_F(SweepSpecTest, RangesExpandToValues) {
  const SweepSpec spec = read_sweep_spec(write(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
    "axes": [{"name": "limit", "range": {"from": 0.1, "to": 0.5, "step": 0.1}, "set": ["/world/time_limit_s"]},
             {"name": "rate", "range": {"from": 20, "to": 80, "step": 20}, "set": ["/world/control_rate_hz"]},
             {"name": "speed", "range": {"from": 1, "to": 2, "count": 3},
              "set": ["/objects/drone/planner/params/speed_mps"]}]})"));
  // Stepped decimals read as written, integers stay integers, counts include both ends.
  EXPECT_EQ(nlohmann::json(spec.axes[0].values), nlohmann::json::parse("[0.1, 0.2, 0.3, 0.4, 0.5]"));
  EXPECT_EQ(nlohmann::json(spec.axes[1].values), nlohmann::json::parse("[20, 40, 60, 80]"));
  EXPECT_TRUE(spec.axes[1].values[0].is_number_integer());
  EXPECT_EQ(nlohmann::json(spec.axes[2].values), nlohmann::json::parse("[1.0, 1.5, 2.0]"));
  EXPECT_EQ(expand_sweep(spec).size(), 5u * 4u * 3u);
}

TEST_F(SweepSpecTest, SpecErrorsOfRangesSamplingAndPlanners) {
  const std::string spec = (dir_ / "spec.json").string();
  const std::string head = R"({"campo_sweep": 1, "scenes": ["two_barriers"], )";
  EXPECT_THAT(error_of(head + R"("axes": [{"name": "a", "range": {"from": 1, "to": 2}, "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":1:71: /axes/0/range (a): expected a \"step\" or \"count\" (a range without them is an interval"));
  EXPECT_THAT(error_of(head + R"("axes": [{"name": "a", "values": [1], "range": {"from": 1, "to": 2, "step": 1},
                                "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":1:57: /axes/0 (a): expected an axis with either \"values\" or \"range\""));
  EXPECT_THAT(error_of(head + R"("axes": [{"name": "a", "range": {"from": 2, "to": 1, "step": 1}, "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":1:92: /axes/0/range/to (a): expected a number > from (2)"));
  EXPECT_THAT(error_of(head + R"("sampling": {"method": "sobol", "samples": 4}, "axes": [{"name": "a", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":1:61: /sampling/method: expected one of"));
  EXPECT_THAT(error_of(head + R"("sampling": {"method": "random", "samples": 4}})"),
              HasSubstr(spec + ":1:48: /sampling: expected a sampling of at least one axis"));
  EXPECT_THAT(error_of(head + R"("planners": ["straight", {"name": "straight"}]})"),
              HasSubstr(spec + ":1:73: /planners/1 (straight): expected planners with distinct labels"));
  EXPECT_THAT(error_of(head + R"("axes": [{"name": "seed", "values": [1], "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":1:58: /axes/0/name (seed): expected an axis name that is not also a run field"));
  EXPECT_THAT(error_of(head + R"("time_limit_s": 0})"), HasSubstr(spec + ":1:48: /time_limit_s: expected a number > 0"));
  EXPECT_THAT(error_of(head + R"("axes": [{"name": "a", "range": {"from": 1, "to": 1.0000000000001, "count": 3},
                                "set": ["/world/time_limit_s"]}]})"),
              HasSubstr(spec + ":1:71: /axes/0/range (a): expected values with distinct labels in run names (\"1\" appears twice)"));
  EXPECT_THAT(error_of(head + R"("planners": ["straight"], "set": {"/objects/drone/planner/name": "straight"}})"),
              HasSubstr(spec + ":1:82: /set/~1objects~1drone~1planner~1name: expected no planner choice when \"planners\" is given"));
}

// Latin hypercube: each axis cut into as many slices as samples, every slice
// used exactly once; the same sampling seed gives the same points, another seed others.
TEST_F(SweepSpecTest, LatinHypercubeUsesEverySliceOnceAndIsSeeded) {
  const auto spec_text = [](int seed, const char* method) {
    return std::string(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
      "sampling": {"method": ")") + method + R"(", "samples": 8, "seed": )" + std::to_string(seed) + R"(},
      "axes": [{"name": "limit", "range": {"from": 10, "to": 20}, "set": ["/world/time_limit_s"]},
               {"name": "rate", "values": [5, 10, 15, 20], "set": ["/world/sensor_rate_hz"]}]})";
  };
  const SweepSpec spec = read_sweep_spec(write(spec_text(3, "latin_hypercube")));
  const auto samples = sample_axes(spec);
  ASSERT_EQ(samples.size(), 8u);
  std::set<int> slices;
  std::map<int, int> res_count;
  for (const auto& sample : samples) {
    const double limit = sample[0].get<double>();
    EXPECT_GE(limit, 10.0);
    EXPECT_LT(limit, 20.0);
    slices.insert(static_cast<int>((limit - 10.0) / 10.0 * 8.0));
    ++res_count[sample[1].get<int>()];
  }
  EXPECT_EQ(slices.size(), 8u);  // one sample per slice of [10, 20)
  // 8 slices over 4 listed values: each value twice.
  EXPECT_EQ(res_count, (std::map<int, int>{{5, 2}, {10, 2}, {15, 2}, {20, 2}}));
  EXPECT_EQ(sample_axes(read_sweep_spec(write(spec_text(3, "latin_hypercube")))), samples);
  EXPECT_NE(sample_axes(read_sweep_spec(write(spec_text(4, "latin_hypercube")))), samples);

  const std::vector<SweepRun> runs = expand_sweep(spec);
  ASSERT_EQ(runs.size(), 8u);
  EXPECT_EQ(runs[2].name, "two_barriers__sample-3__seed-1");
  EXPECT_EQ(runs[2].params["limit"], samples[2][0]);
  EXPECT_EQ(runs[2].overrides[0].text, "/world/time_limit_s=" + samples[2][0].dump());

  // Random sampling: values inside the interval, from the seed.
  const auto random = sample_axes(read_sweep_spec(write(spec_text(3, "random"))));
  ASSERT_EQ(random.size(), 8u);
  for (const auto& sample : random) EXPECT_GE(sample[0].get<double>(), 10.0);
  EXPECT_EQ(sample_axes(read_sweep_spec(write(spec_text(3, "random")))), random);
}

// Planners: the scene's own one gets the given parameters on top of the
// scene's; another replaces it with only its own.
TEST_F(SweepSpecTest, PlannersAreRunOnEveryScene) {
  const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(R"({"campo_sweep": 1,
    "scenes": ["two_barriers"],
    "planners": ["straight", {"name": "depth_reactive", "label": "reactive_slow", "params": {"speed_mps": 0.5}}],
    "seeds": {"count": 2}})")));
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[0].name, "two_barriers__straight__seed-1");
  EXPECT_EQ(runs[0].planner, "straight");
  EXPECT_EQ(runs[0].overrides[0].text, R"(/objects/drone/planner={"name":"straight","params":{}})");
  EXPECT_EQ(runs[3].name, "two_barriers__reactive_slow__seed-2");
  EXPECT_EQ(runs[3].planner, "reactive_slow");
  EXPECT_EQ(runs[3].overrides[0].text, "/objects/drone/planner/params/speed_mps=0.5");
}

TEST(SweepShards, DisjointCoveringAndBalanced) {
  std::vector<SweepRun> runs(23);
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i].id = std::to_string(i);
  for (int count : {1, 2, 5, 23, 30}) {
    std::multiset<std::string> seen;
    std::size_t smallest = runs.size(), largest = 0;
    for (int k = 1; k <= count; ++k) {
      const auto shard = shard_of(runs, k, count);
      smallest = std::min(smallest, shard.size());
      largest = std::max(largest, shard.size());
      for (const SweepRun& run : shard) seen.insert(run.id);
    }
    EXPECT_EQ(seen.size(), runs.size()) << count;
    EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), runs.size()) << count;
    EXPECT_LE(largest - smallest, 1u) << count;
  }
}

TEST_F(SweepSpecTest, NoAxesGiveOneRunPerSceneAndSeed) {
  const std::vector<SweepRun> runs =
      expand_sweep(read_sweep_spec(write(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"count": 3}})")));
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].name, "two_barriers__seed-1");
  EXPECT_EQ(runs[0].planner, "depth_reactive");  // the scene's
  EXPECT_EQ(override_texts(runs[2].overrides), std::vector<std::string>{"/world/seed=3"});
  EXPECT_EQ(runs[0].params, nlohmann::json::object());
}

TEST_F(SweepSpecTest, SeedsAreIntegersInZeroTo2To64Minus1) {
  const std::string spec = (dir_ / "spec.json").string();
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"first": -1, "count": 2}})"),
            spec + ":1:58: /seeds/first: expected an integer seed in [0, 18446744073709551615], got -1");
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"first": 2.5}})"),
            spec + ":1:58: /seeds/first: expected an integer seed in [0, 18446744073709551615], got 2.5");
  // The last seed, first + count - 1, must be a seed too.
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                          "seeds": {"first": 18446744073709551615, "count": 2}})"),
            spec + ":2:27: /seeds: expected seeds first .. first + count - 1 that are all in [0, 18446744073709551615], "
                   "got {\"count\":2,\"first\":18446744073709551615}");
  const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(
      R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"first": 18446744073709551614, "count": 2}})")));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].seed, 18446744073709551615u);
  EXPECT_EQ(runs[1].overrides.back().text, "/world/seed=18446744073709551615");
  // A seed swept as an axis (a generator's) goes through the scene loader.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["trees_rolling_terrain"],
                           "axes": [{"name": "forest", "values": [3, -3], "set": ["/objects/forest/seed"]}]})"),
              HasSubstr(spec + ": /scenes/0: run trees_rolling_terrain__forest--3__seed-1: "));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["trees_rolling_terrain"],
                           "axes": [{"name": "forest", "values": [3, -3], "set": ["/objects/forest/seed"]}]})"),
              HasSubstr("scenes/trees_rolling_terrain.json:22:7: /objects/1/seed (forest): expected an integer seed in "
                        "[0, 18446744073709551615], got -3"));
}

TEST_F(SweepSpecTest, SweptRatesMustDivideThePhysicsRate) {
  const std::string spec = (dir_ / "spec.json").string();
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                            "axes": [{"name": "rate", "values": [60, 100], "set": ["/world/control_rate_hz"]}]})"),
              ::testing::AllOf(
                  ::testing::StartsWith(spec + ": /scenes/0: run two_barriers__rate-100__seed-1: "),
                  ::testing::EndsWith("scenes/two_barriers.json:7:5: /world/control_rate_hz: expected a rate that divides "
                                      "the physics rate 240 Hz (1 / physics_step_s) into a whole number of steps, "
                                      "such as 240, 120, 80 or 60, got 100")));
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"],
                          "axes": [{"name": "rate", "values": [60, 40, 30], "set": ["/world/control_rate_hz"]}]})"),
            "");
}

TEST_F(SweepSpecTest, ValueLabelsAreShortAndFilesystemSafe) {
  EXPECT_EQ(value_label(0.25), "0.25");
  EXPECT_EQ(value_label(256), "256");
  EXPECT_EQ(value_label(nlohmann::json({16, 8})), "16x8");
  EXPECT_EQ(value_label("a b/c"), "a b/c");
  EXPECT_EQ(value_id_label("a b/c"), "a_b_c");
  EXPECT_EQ(value_id_label(true), "true");
}

TEST(StartJitter, DeterministicInsideTheDiscAndDifferentPerSeed) {
  std::set<std::pair<double, double>> offsets;
  double farthest = 0.0;
  for (std::uint64_t seed = 0; seed < 500; ++seed) {
    const Eigen::Vector2d d = start_jitter_offset(seed, 0.25);
    EXPECT_EQ(d, start_jitter_offset(seed, 0.25));
    EXPECT_LE(d.norm(), 0.25);
    farthest = std::max(farthest, d.norm());
    offsets.insert({d.x(), d.y()});
  }
  EXPECT_EQ(offsets.size(), 500u);
  EXPECT_GT(farthest, 0.2);  // the whole disc is used, not only its centre
}

TEST_F(SweepSpecTest, StartJitterMovesTheSceneStartTheSameForEveryAxisValue) {
  const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(R"({
    "campo_sweep": 1, "scenes": ["two_barriers"],
    "axes": [{"name": "limit", "values": [5, 6], "set": ["/world/time_limit_s"]}],
    "seeds": {"first": 1, "count": 2},
    "start_jitter": {"vehicle": "drone", "radius_m": 0.25}})")));
  ASSERT_EQ(runs.size(), 4u);
  const auto start_of = [](const SweepRun& run) {
    const std::string& last = run.overrides.back().text;
    const std::string prefix = "/objects/drone/pose/position_m=";
    EXPECT_EQ(last.substr(0, prefix.size()), prefix);
    return nlohmann::json::parse(last.substr(prefix.size()));
  };
  // two_barriers starts the drone at (0, 0, 1.5).
  for (const SweepRun& run : runs) {
    const nlohmann::json p = start_of(run);
    const Eigen::Vector2d d = start_jitter_offset(run.seed, 0.25);
    EXPECT_DOUBLE_EQ(p[0].get<double>(), d.x());
    EXPECT_DOUBLE_EQ(p[1].get<double>(), d.y());
    EXPECT_DOUBLE_EQ(p[2].get<double>(), 1.5);
  }
  EXPECT_EQ(start_of(runs[0]), start_of(runs[2]));  // seed 1 at both limits
  EXPECT_NE(start_of(runs[0]), start_of(runs[1]));  // seeds 1 and 2
}

// The scene of a run: its scene file with the run's overrides, loaded as `campo run` loads it.
Scene run_scene(const SweepRun& run) {
  nlohmann::json document = read_json_file(run.scene_file);
  for (const SceneOverride& o : run.overrides) apply_override(document, parse_override(o.text));
  return parse_scene(document, run.scene_file.string(), run.scene_file.parent_path());
}

// Poses of the vineyard's random obstacles ("field/obstacle<k>").
std::vector<std::vector<double>> obstacle_poses(const Scene& scene) {
  std::vector<std::vector<double>> poses;
  for (const Shape& shape : scene.shapes) {
    if (shape.alias.find("/obstacle") == std::string::npos) continue;
    const Eigen::Vector3d p = shape.pose.translation();
    poses.push_back({p.x(), p.y(), p.z()});
  }
  return poses;
}

TEST_F(SweepSpecTest, StateNoiseIsAnAxisLikeAnyParameter) {
  // The vehicle has no "state_noise" block: the axis creates it.
  const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(R"({"campo_sweep": 1,
    "scenes": ["two_barriers"], "axes": [{"name": "gps", "values": [0, 0.5],
      "set": ["/objects/drone/state_noise/position_stddev_m"]}]})")));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(run_scene(runs[0]).vehicles.front().state_noise.position_stddev_m, 0.0);
  EXPECT_FALSE(run_scene(runs[0]).vehicles.front().state_noise.enabled());
  EXPECT_EQ(run_scene(runs[1]).vehicles.front().state_noise.position_stddev_m, 0.5);
  EXPECT_TRUE(run_scene(runs[1]).vehicles.front().state_noise.enabled());
}

TEST_F(SweepSpecTest, VarySceneWithSeedReseedsTheScenesGenerators) {
  const std::string spec = R"({"campo_sweep": 1, "scenes": ["vineyard"], "seeds": {"first": 1, "count": 2})";
  // Without it, the seeds leave the vineyard's obstacles where the scene file's seed puts them.
  const std::vector<SweepRun> fixed = expand_sweep(read_sweep_spec(write(spec + "}")));
  ASSERT_EQ(fixed.size(), 2u);
  EXPECT_EQ(override_texts(fixed[1].overrides), std::vector<std::string>{"/world/seed=2"});
  const auto fixed_1 = obstacle_poses(run_scene(fixed[0]));
  ASSERT_EQ(fixed_1.size(), 12u);  // scenes/vineyard.json's obstacle_count
  EXPECT_EQ(fixed_1, obstacle_poses(run_scene(fixed[1])));

  // With it, each run seed gives the generator its own seed, after the world seed.
  const std::vector<SweepRun> varied =
      expand_sweep(read_sweep_spec(write(spec + R"(, "vary_scene_with_seed": true})")));
  ASSERT_EQ(varied.size(), 2u);
  for (const SweepRun& run : varied) {
    EXPECT_EQ(override_texts(run.overrides),
              (std::vector<std::string>{"/world/seed=" + std::to_string(run.seed),
                                        "/objects/field/seed=" + std::to_string(generator_seed(run.seed, "field"))}));
  }
  const auto varied_1 = obstacle_poses(run_scene(varied[0]));
  const auto varied_2 = obstacle_poses(run_scene(varied[1]));
  ASSERT_EQ(varied_1.size(), 12u);
  ASSERT_EQ(varied_2.size(), 12u);
  EXPECT_NE(varied_1, varied_2);
  EXPECT_NE(varied_1, fixed_1);
  EXPECT_NE(varied[0].id, fixed[0].id);  // another effective scene, another ID
  // Deterministic: the same spec expands to the same runs.
  const std::vector<SweepRun> again = expand_sweep(read_sweep_spec(write(spec + R"(, "vary_scene_with_seed": true})")));
  EXPECT_EQ(override_texts(again[1].overrides), override_texts(varied[1].overrides));
  EXPECT_EQ(again[1].id, varied[1].id);
}

TEST_F(SweepSpecTest, VarySceneWithSeedReachesNestedGeneratorsAndDiffersPerGenerator) {
  // trees_rolling_terrain has two generators; one placed under a dummy here.
  write(R"({"campo_scene": 1, "world": {"seed": 0}, "objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "group", "type": "dummy", "children": [
      {"alias": "forest", "type": "trees", "count": 3, "area_min_m": [-10, -10], "area_max_m": [10, 10]}]},
    {"alias": "grove", "type": "trees", "count": 3, "seed": 7, "area_min_m": [20, 20], "area_max_m": [30, 30]}]})",
        "grove.json");
  const std::vector<SweepRun> runs = expand_sweep(read_sweep_spec(write(R"({"campo_sweep": 1,
    "scenes": ["grove.json"], "seeds": {"first": 5}, "vary_scene_with_seed": true})")));
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(override_texts(runs[0].overrides),
            (std::vector<std::string>{"/world/seed=5",
                                      "/objects/group/children/forest/seed=" + std::to_string(generator_seed(5, "forest")),
                                      "/objects/grove/seed=" + std::to_string(generator_seed(5, "grove"))}));
  // The documented derivation, written out: FNV-1a-64 of "vary_scene_with_seed/<alias>", derive_seed, 53 bits.
  std::uint64_t label = 0xcbf29ce484222325ULL;
  for (char c : std::string("vary_scene_with_seed/forest")) label = (label ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  EXPECT_EQ(generator_seed(5, "forest"), Rng::derive_seed(5, label) % (std::uint64_t{1} << 53));
  EXPECT_NE(generator_seed(5, "forest"), generator_seed(5, "grove"));
  EXPECT_NE(generator_seed(5, "forest"), generator_seed(6, "forest"));
  EXPECT_LT(generator_seed(5, "forest"), std::uint64_t{1} << 53);
}

TEST_F(SweepSpecTest, VarySceneWithSeedErrors) {
  const std::string spec = (dir_ / "spec.json").string();
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["vineyard"], "vary_scene_with_seed": "yes"})"),
              HasSubstr(spec + ":1:44: /vary_scene_with_seed: expected true or false, got \"yes\""));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["vineyard"], "vary_scene_with_seed": 1})"),
              HasSubstr(spec + ":1:44: /vary_scene_with_seed: expected true or false, got 1"));
  // Nothing to vary.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "vary_scene_with_seed": true})"),
              HasSubstr(spec + ": /vary_scene_with_seed: expected a scene with a seeded generator (rolling_terrain, "
                               "trees, vineyard), or false"));
  // A generator's seed has one writer.
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["vineyard"], "set": {"/objects/field/seed": 4},
                           "vary_scene_with_seed": true})"),
              HasSubstr(spec + ": /vary_scene_with_seed: expected no other override of a generator's seed when the run "
                               "seeds vary the scene (/objects/field/seed is also set at /set/~1objects~1field~1seed"));
  EXPECT_THAT(error_of(R"({"campo_sweep": 1, "scenes": ["vineyard"],
                           "axes": [{"name": "layout", "values": [1, 2], "set": ["/objects/1/seed"]}],
                           "vary_scene_with_seed": true})"),
              HasSubstr(spec + ": /vary_scene_with_seed: expected no other override of a generator's seed"));
  // false is the default, and valid anywhere.
  EXPECT_EQ(error_of(R"({"campo_sweep": 1, "scenes": ["two_barriers"], "vary_scene_with_seed": false})"), "");
}

TEST(BundledSweeps, SensorSweepOfSeed000IsValid) {
  const SweepSpec spec = read_sweep_spec(fs::path("scenes/sweeps/sensor_000.json"));
  std::vector<std::pair<double, double>> fov_and_range;
  const std::vector<SweepRun> runs = expand_sweep(spec, [&fov_and_range](const Scene& scene) {
    const RangeSensorConfig& scanner = scene.vehicles.front().sensors.front().range;
    EXPECT_EQ(scanner.fov_h_deg, scanner.fov_v_deg);
    fov_and_range.emplace_back(scanner.fov_h_deg, scanner.max_range_m);
    for (const VehicleDef& vehicle : scene.vehicles) create_planner(vehicle.planner, {vehicle.type, &scene});
  });
  ASSERT_EQ(runs.size(), 3u * 3u * 5u);
  // Every field of view meets every range in the scenes the runs load.
  std::sort(fov_and_range.begin(), fov_and_range.end());
  fov_and_range.erase(std::unique(fov_and_range.begin(), fov_and_range.end()), fov_and_range.end());
  EXPECT_EQ(fov_and_range.size(), 9u);
  EXPECT_EQ(fov_and_range.front(), std::make_pair(60.0, 5.0));
  EXPECT_EQ(fov_and_range.back(), std::make_pair(120.0, 20.0));
}

TEST(BundledSweeps, ResolutionSweepOfSeed000IsValid) {
  const SweepSpec spec = read_sweep_spec(fs::path("scenes/sweeps/resolution_000.json"));
  const std::vector<SweepRun> runs = expand_sweep(spec, [](const Scene& scene) {
    for (const VehicleDef& vehicle : scene.vehicles) {
      validate_vehicle_params(vehicle);
      create_planner(vehicle.planner, {vehicle.type, &scene});
    }
  });
  ASSERT_EQ(runs.size(), 2u * 5u * 10u);  // ten seeds per resolution and scene
  EXPECT_FALSE(spec.vary_scene_with_seed);
  // Its table shows path ratio and time over the runs that reached the goal beside those over all runs.
  const std::vector<std::string> metrics = spec.document.at("table").at("metrics");
  for (const char* metric : {"path_ratio@reached", "path_ratio", "sim_time_s@reached", "sim_time_s"}) {
    EXPECT_NE(std::find(metrics.begin(), metrics.end(), metric), metrics.end()) << metric;
  }
  EXPECT_EQ(runs.front().name, "two_barriers__resolution-256__seed-1");
  EXPECT_EQ(runs.back().name, "trees_rolling_terrain__resolution-16__seed-10");
}

}  // namespace
}  // namespace campo
