#include "sweep/merge.hpp"

#include <map>

#include "campo/json_reader.hpp"
#include "sweep/results.hpp"

namespace campo {

SweepDir read_sweep_dir(const std::filesystem::path& dir, std::vector<std::string>& warnings) {
  SweepDir sweep;
  sweep.dir = dir;
  for (const char* name : {"sweep.json", "results.jsonl"}) {
    if (!std::filesystem::exists(dir / name)) {
      throw InputError((dir / name).string(), "", "expected a sweep directory (written by campo sweep) with " + std::string(name));
    }
  }
  sweep.manifest = read_json_file(dir / "sweep.json");
  for (const char* key : {"spec_sha256", "campo_version", "runs"}) {
    if (!sweep.manifest.contains(key)) {
      throw InputError((dir / "sweep.json").string(), std::string("/") + key,
                       "expected a sweep.json with \"" + std::string(key) + "\" (written by this version of campo sweep)");
    }
  }
  for (ResultLine& line : read_result_lines(dir / "results.jsonl", warnings)) {
    if (!line.value.is_object() || !line.value.contains("id") || !line.value["id"].is_string()) {
      throw InputError(line.source, "/id", "expected a results line: an object with a string \"id\"");
    }
    sweep.lines.push_back(std::move(line.value));
  }
  return sweep;
}

namespace {

// The plugin files a sweep's planners came from, by content: their paths may differ between the machines of shards.
nlohmann::json plugin_digests(const nlohmann::json& manifest) {
  nlohmann::json digests = nlohmann::json::array();
  for (const nlohmann::json& plugin : manifest.value("plugins", nlohmann::json::array())) {
    digests.push_back(plugin.is_object() ? plugin.value("sha256", nlohmann::json()) : nlohmann::json());
  }
  return digests;
}

}  // namespace

MergedSweep merge_sweeps(const std::vector<SweepDir>& inputs, bool allow_mismatch) {
  if (inputs.empty()) throw InputError("command line", "DIR", "expected at least one sweep directory to merge");
  const SweepDir& first = inputs.front();
  if (!allow_mismatch) {
    for (const SweepDir& input : inputs) {
      for (const char* key : {"spec_sha256", "campo_version"}) {
        if (input.manifest[key] != first.manifest[key]) {
          throw InputError((input.dir / "sweep.json").string(), std::string("/") + key,
                           "expected the " + std::string(key) + " of " + (first.dir / "sweep.json").string() + " (" +
                               first.manifest[key].dump() + "), got " + input.manifest[key].dump() +
                               "; merge runs of one spec and one campo version, or pass --allow-mismatch");
        }
      }
      if (plugin_digests(input.manifest) != plugin_digests(first.manifest)) {
        throw InputError((input.dir / "sweep.json").string(), "/plugins",
                         "expected the plugin files of " + (first.dir / "sweep.json").string() + " (SHA-256 " +
                             plugin_digests(first.manifest).dump() + "), got " +
                             plugin_digests(input.manifest).dump() +
                             "; merge runs of the same planner plugins, or pass --allow-mismatch");
      }
      for (std::size_t i = 0; i < input.lines.size(); ++i) {
        const nlohmann::json version = input.lines[i].value("campo_version", nlohmann::json());
        if (version != input.manifest["campo_version"]) {
          throw InputError((input.dir / "results.jsonl").string() + " line " + std::to_string(i + 1),
                           "/campo_version",
                           "expected the campo version of its sweep.json (" + input.manifest["campo_version"].dump() +
                               "), got " + version.dump() + "; or pass --allow-mismatch");
        }
      }
    }
  }
  MergedSweep merged;
  merged.manifest = first.manifest;
  merged.manifest.erase("shard");
  // id -> the line kept; order: the manifest's, then first appearance.
  std::map<std::string, std::pair<nlohmann::json, std::size_t>> kept;  // line and its input
  std::vector<std::string> order;
  for (const auto& run : merged.manifest["runs"]) order.push_back(run.value("id", ""));
  std::map<std::string, bool> in_order;
  for (const std::string& id : order) in_order[id] = true;
  std::size_t lines = 0;
  for (std::size_t source = 0; source < inputs.size(); ++source) {
    for (const nlohmann::json& line : inputs[source].lines) {
      ++lines;
      const std::string id = line["id"];
      if (!in_order.contains(id)) {
        in_order[id] = true;
        order.push_back(id);
      }
      auto [it, inserted] = kept.try_emplace(id, line, source);
      if (inserted) continue;
      const bool old_completed = it->second.first.value("status", "") == "completed";
      const bool new_completed = line.value("status", "") == "completed";
      if (new_completed || !old_completed) it->second = {line, source};
    }
  }
  for (const std::string& id : order) {
    if (const auto it = kept.find(id); it != kept.end()) {
      merged.lines.push_back(it->second.first);
      merged.sources.push_back(it->second.second);
    } else {
      ++merged.missing;
    }
  }
  merged.duplicates = lines - merged.lines.size();
  return merged;
}

}  // namespace campo
