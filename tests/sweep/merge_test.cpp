// Merging the result directories of one sweep: one line per run, completed
// lines first, mismatched specs and versions refused.
#include "sweep/merge.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

nlohmann::json line(const std::string& id, const std::string& status, const std::string& version = "0.1.0") {
  return {{"id", id}, {"status", status}, {"campo_version", version}};
}

SweepDir shard(const std::string& dir, std::vector<nlohmann::json> lines, const std::string& spec = "s1",
               int index = 1) {
  nlohmann::json runs = nlohmann::json::array();
  for (const char* id : {"a", "b", "c", "d"}) runs.push_back({{"id", id}});
  return {dir,
          {{"spec_sha256", spec}, {"campo_version", "0.1.0"}, {"runs", runs}, {"shard", {{"index", index}, {"count", 2}}}},
          std::move(lines)};
}

TEST(MergeSweeps, OneLinePerRunInManifestOrderCompletedFirst) {
  const MergedSweep merged = merge_sweeps(
      {shard("s1", {line("c", "completed"), line("a", "failed")}),
       shard("s2", {line("a", "completed"), line("c", "failed"), line("x", "completed")}, "s1", 2)},
      false);
  ASSERT_EQ(merged.lines.size(), 3u);
  EXPECT_EQ(merged.lines[0]["id"], "a");  // manifest order, then runs it does not list
  EXPECT_EQ(merged.lines[0]["status"], "completed");
  EXPECT_EQ(merged.lines[1]["id"], "c");
  EXPECT_EQ(merged.lines[1]["status"], "completed");  // not replaced by the later failure
  EXPECT_EQ(merged.lines[2]["id"], "x");
  EXPECT_EQ(merged.sources, (std::vector<std::size_t>{1, 0, 1}));  // where each kept line (and its folders) is
  EXPECT_EQ(merged.duplicates, 2u);
  EXPECT_EQ(merged.missing, 2u);  // b and d
  EXPECT_FALSE(merged.manifest.contains("shard"));
}

TEST(MergeSweeps, RefusesAnotherSpecOrVersionUnlessAllowed) {
  try {
    merge_sweeps({shard("one", {}), shard("two", {}, "s2")}, false);
    FAIL() << "merged two specs";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("two/sweep.json: /spec_sha256: expected the spec_sha256 of one/sweep.json"));
    EXPECT_THAT(e.what(), HasSubstr("--allow-mismatch"));
  }
  try {
    merge_sweeps({shard("one", {line("a", "completed", "0.0.9")})}, false);
    FAIL() << "merged another version's line";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("one/results.jsonl line 1: /campo_version: expected the campo version"));
  }
  EXPECT_EQ(merge_sweeps({shard("one", {line("a", "completed")}), shard("two", {line("b", "completed")}, "s2")}, true)
                .lines.size(),
            2u);
}

TEST(MergeSweeps, RefusesShardsOfOtherPluginFilesUnlessAllowed) {
  SweepDir one = shard("one", {line("a", "completed")});
  SweepDir two = shard("two", {line("b", "completed")}, "s1", 2);
  one.manifest["plugins"] = {{{"path", "/home/a/steer.so"}, {"sha256", "aaaa"}, {"planners", {"steer"}}}};
  // The same file elsewhere (another machine's mount) is the same plugin.
  two.manifest["plugins"] = {{{"path", "/mnt/a/steer.so"}, {"sha256", "aaaa"}, {"planners", {"steer"}}}};
  EXPECT_EQ(merge_sweeps({one, two}, false).lines.size(), 2u);
  two.manifest["plugins"][0]["sha256"] = "bbbb";
  try {
    merge_sweeps({one, two}, false);
    FAIL() << "merged runs of two builds of a plugin";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("two/sweep.json: /plugins: expected the plugin files of one/sweep.json (SHA-256 "
                                    "[\"aaaa\"]), got [\"bbbb\"]"));
  }
  two.manifest.erase("plugins");
  EXPECT_THROW(merge_sweeps({one, two}, false), InputError);
  EXPECT_EQ(merge_sweeps({one, two}, true).lines.size(), 2u);
}

}  // namespace
}  // namespace campo
