#include "sweep/results.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "sim/json_reader.hpp"

namespace campo {

namespace {

// The fields every line has, whatever its status.
nlohmann::json result_line(const SweepRun& run, const std::string& status) {
  return {{"id", run.id},         {"scene", run.scene},         {"params", run.params},
          {"seed", run.seed},     {"status", status},           {"overrides", run.overrides},
          {"run_dir", run_dir(run.id)}};
}

RunMetrics read_metrics(const JsonNode& node) {
  // Only the keys the table uses: run.json's metrics are defined (and grow) in sim/, so no finish().
  ObjectReader r(node);
  RunMetrics m;
  m.outcome = r.required("outcome").as_string();
  r.read("waypoints_reached", m.waypoints_reached, Range::non_negative());
  r.read("waypoints_discarded", m.waypoints_discarded, Range::non_negative());
  m.path_length_m = r.required("path_length_m").as_number(Range::non_negative());
  m.path_ratio = r.required("path_ratio").as_number(Range::non_negative());
  m.time_s = r.required("sim_time_s").as_number(Range::non_negative());
  m.collisions = static_cast<int>(r.required("collisions").as_int(0, 1 << 30));
  r.read("replans", m.replans, 0, 1 << 30);
  r.read("replan_time_ms_median", m.replan_ms_median, Range::non_negative());
  r.read("replan_time_ms_max", m.replan_ms_max, Range::non_negative());
  return m;
}

RunResult read_result(const JsonNode& node) {
  ObjectReader r(node);
  RunResult result;
  result.id = r.required("id").as_string();
  result.scene = r.required("scene").as_string();
  const JsonNode params = r.required("params");
  if (!params.value().is_object()) params.fail("an object of axis values");
  result.params = params.value();
  result.seed = r.required("seed").as_seed();
  result.completed = r.required("status").as_choice({"failed", "completed"}) == 1;
  for (const JsonNode& o : r.required("overrides").as_array(0, 100000)) result.overrides.push_back(o.as_string());
  const JsonNode metrics = r.required("metrics");
  if (result.completed) {
    result.metrics = read_metrics(metrics);
  } else {
    result.reason = r.required("reason").as_string();
    if (!metrics.value().is_null()) metrics.fail("null for a failed run");
  }
  // Provenance is for people and scripts; the table does not use it.
  for (const char* key : {"run_dir", "campo_version", "git_rev", "scene_sha256"}) r.accept(key);
  r.finish();
  return result;
}

MeanSd mean_sd(const std::vector<double>& values) {
  const double n = static_cast<double>(values.size());
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  double squares = 0.0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return {mean, values.size() > 1 ? std::sqrt(squares / (n - 1.0)) : 0.0};
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Mean and sd of one metric over the completed runs; empty when there are none.
template <class Metric>
std::optional<MeanSd> spread(const std::vector<const RunResult*>& completed, Metric metric) {
  if (completed.empty()) return std::nullopt;
  std::vector<double> values;
  for (const RunResult* r : completed) values.push_back(metric(r->metrics));
  return mean_sd(values);
}

TableRow summarize(const std::vector<const RunResult*>& group, const std::vector<std::string>& axes) {
  TableRow row;
  row.scene = group.front()->scene;
  for (const std::string& axis : axes) row.params.push_back(group.front()->params.value(axis, nlohmann::json()));
  row.runs = static_cast<int>(group.size());
  std::vector<const RunResult*> completed;
  std::vector<double> replan_medians, replan_maxima;
  int reached = 0;
  for (const RunResult* r : group) {
    if (!r->completed) {
      ++row.failed;
      continue;
    }
    completed.push_back(r);
    if (r->metrics.outcome == "reached") ++reached;
    row.collisions += r->metrics.collisions;
    if (r->metrics.replans > 0) {
      replan_medians.push_back(r->metrics.replan_ms_median);
      replan_maxima.push_back(r->metrics.replan_ms_max);
    }
  }
  row.success_rate = static_cast<double>(reached) / row.runs;
  row.waypoints_reached = spread(completed, [](const RunMetrics& m) { return m.waypoints_reached; });
  row.waypoints_discarded = spread(completed, [](const RunMetrics& m) { return m.waypoints_discarded; });
  row.path_length_m = spread(completed, [](const RunMetrics& m) { return m.path_length_m; });
  row.path_ratio = spread(completed, [](const RunMetrics& m) { return m.path_ratio; });
  row.time_s = spread(completed, [](const RunMetrics& m) { return m.time_s; });
  if (!replan_medians.empty()) {
    row.replan_ms_median = median(replan_medians);
    row.replan_ms_max = *std::max_element(replan_maxima.begin(), replan_maxima.end());
  }
  return row;
}

}  // namespace

std::string run_dir(const std::string& id) { return "runs/" + id; }

nlohmann::json completed_result(const SweepRun& run, const nlohmann::json& run_record) {
  const nlohmann::json& provenance = run_record.at("provenance");
  nlohmann::json line = result_line(run, "completed");
  line["metrics"] = run_record.at("metrics");
  line["campo_version"] = provenance.at("campo_version");
  line["git_rev"] = provenance.at("git_revision");
  line["scene_sha256"] = provenance.at("scene").at("sha256");
  return line;
}

nlohmann::json failed_result(const SweepRun& run, const std::string& reason) {
  nlohmann::json line = result_line(run, "failed");
  line["reason"] = reason;
  line["metrics"] = nullptr;
  line["campo_version"] = CAMPO_VERSION;
  line["git_rev"] = CAMPO_GIT_REV;
  line["scene_sha256"] = run.scene_sha256;
  return line;
}

ResultsLog::ResultsLog(const std::filesystem::path& path) {
  // Find where the last complete line ends, reading backwards from the end.
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > 0) {
    std::ifstream in(path, std::ios::binary);
    auto end = size;
    for (char c = 0; end > 0; --end) {
      in.seekg(static_cast<std::streamoff>(end - 1));
      if (!in.get(c)) throw std::runtime_error("cannot read " + path.string());
      if (c == '\n') break;
    }
    if (end < size) {
      std::filesystem::resize_file(path, end);
      cut_partial_line_ = true;
    }
  }
  out_.open(path, std::ios::app | std::ios::binary);
  if (!out_) throw std::runtime_error("cannot open " + path.string() + " for appending");
}

void ResultsLog::append(const nlohmann::json& line) {
  out_ << line.dump() << '\n' << std::flush;
  if (!out_) throw std::runtime_error("cannot append to results.jsonl");
}

ResultsFile read_results(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string text = read_text_file(path, {.max_file_bytes = std::uintmax_t{1} << 32});
  ResultsFile results;
  std::map<std::string, std::size_t> index_of;  // id -> position in results.runs
  std::size_t start = 0;
  for (int number = 1; start < text.size(); ++number) {
    const std::size_t newline = text.find('\n', start);
    const bool last = newline == std::string::npos;
    const std::string line = text.substr(start, last ? std::string::npos : newline - start);
    start = last ? text.size() : newline + 1;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string source = file + " line " + std::to_string(number);
    nlohmann::json value;
    try {
      value = parse_json_text(line, source);
    } catch (const InputError&) {
      // A sweep killed mid-write leaves a partial last line without its newline.
      if (!last) throw;
      results.warnings.push_back(source + " is incomplete (an interrupted sweep?) and was ignored");
      continue;
    }
    RunResult result = read_result(JsonNode(value, source, ""));
    const auto [it, inserted] = index_of.emplace(result.id, results.runs.size());
    if (inserted) {
      results.runs.push_back(std::move(result));
    } else {
      results.runs[it->second] = std::move(result);  // a rerun (resumed sweep): the last line counts
    }
  }
  return results;
}

TableLayout table_layout(const std::filesystem::path& dir, const std::vector<RunResult>& runs) {
  TableLayout layout;
  const std::filesystem::path manifest = dir / "sweep.json";
  if (std::filesystem::exists(manifest)) {
    const nlohmann::json document = read_json_file(manifest);
    ObjectReader r(JsonNode(document, manifest.string(), ""));
    const std::string spec_file = r.required("spec_file").as_string();
    const SweepSpec spec = parse_sweep_spec(r.required("spec").value(), spec_file);
    layout.name = spec.name;
    for (const SweepAxis& axis : spec.axes) layout.axes.push_back(axis.name);
    for (const JsonNode& run : r.required("runs").as_array(0, SweepLimits{}.max_runs)) {
      ObjectReader entry(run);
      layout.run_order.push_back(entry.required("id").as_string());
      for (const char* key : {"scene", "scene_file", "params", "seed", "overrides"}) entry.accept(key);
      entry.finish();
    }
    r.finish();
    return layout;
  }
  layout.name = dir.filename().string();
  for (const RunResult& run : runs) {
    for (const auto& [axis, value] : run.params.items()) {
      if (std::find(layout.axes.begin(), layout.axes.end(), axis) == layout.axes.end()) layout.axes.push_back(axis);
    }
  }
  return layout;
}

SweepTable aggregate(const std::vector<RunResult>& runs, const TableLayout& layout) {
  // A run's rank: its place in the expansion, else after all of them in order of appearance.
  std::map<std::string, std::size_t> rank_of;
  for (std::size_t i = 0; i < layout.run_order.size(); ++i) rank_of.emplace(layout.run_order[i], i);
  struct Group {
    std::size_t rank;
    std::vector<const RunResult*> runs;
  };
  std::map<std::string, Group> groups;  // key: scene and axis values
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResult& run = runs[i];
    nlohmann::json key = nlohmann::json::array({run.scene});
    for (const std::string& axis : layout.axes) key.push_back(run.params.value(axis, nlohmann::json()));
    const auto it = rank_of.find(run.id);
    const std::size_t rank = it != rank_of.end() ? it->second : layout.run_order.size() + i;
    auto [group, inserted] = groups.try_emplace(key.dump(), Group{rank, {}});
    group->second.rank = std::min(group->second.rank, rank);
    group->second.runs.push_back(&run);
  }
  std::vector<const Group*> ordered;
  for (const auto& [key, group] : groups) ordered.push_back(&group);
  std::sort(ordered.begin(), ordered.end(), [](const Group* a, const Group* b) { return a->rank < b->rank; });

  SweepTable table{layout.name, layout.axes, {}};
  for (const Group* group : ordered) table.rows.push_back(summarize(group->runs, layout.axes));
  return table;
}

}  // namespace campo
