#include "sweep/results.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <set>

#include <fcntl.h>
#include <unistd.h>

#include "campo/json_reader.hpp"
#include "campo/version.hpp"
#include "core/output_dir.hpp"

namespace campo {

namespace {

// The fields every line has, whatever its status.
nlohmann::json result_line(const SweepRun& run, const std::string& status) {
  return {{"id", run.id},     {"name", run.name},     {"scene", run.scene},       {"planner", run.planner},
          {"params", run.params}, {"seed", run.seed}, {"status", status},      {"overrides", run.overrides},
          {"run_dir", nullptr}};
}

RunMetrics read_metrics(const JsonNode& node) {
  // Only the keys the table uses: run.json's metrics are defined (and grow) in run/, so no finish().
  ObjectReader r(node);
  RunMetrics m;
  m.outcome = r.required("outcome").as_string();
  r.read("waypoints_reached", m.waypoints_reached, Range::non_negative());
  r.read("waypoints_discarded", m.waypoints_discarded, Range::non_negative());
  m.path_length_m = r.required("path_length_m").as_number(Range::non_negative());
  m.path_ratio = r.required("path_ratio").as_number(Range::non_negative());
  m.time_s = r.required("sim_time_s").as_number(Range::non_negative());
  m.collisions = static_cast<int>(r.required("collisions").as_int(0, 1 << 30));
  if (auto c = r.optional("min_clearance_m"); c && !c->value().is_null()) m.min_clearance_m = c->as_number();
  r.read("replans", m.replans, 0, 1 << 30);
  r.read("replan_time_ms_median", m.replan_ms_median, Range::non_negative());
  r.read("replan_time_ms_max", m.replan_ms_max, Range::non_negative());
  return m;
}

RunResult read_result(const JsonNode& node) {
  ObjectReader r(node);
  RunResult result;
  result.id = r.required("id").as_string();
  result.name = result.id;
  r.read("name", result.name);
  result.scene = r.required("scene").as_string();
  r.read("planner", result.planner);
  const JsonNode params = r.required("params");
  if (!params.value().is_object()) params.fail("an object of axis values");
  result.params = params.value();
  result.seed = r.required("seed").as_seed();
  result.completed = r.required("status").as_choice({"failed", "completed"}) == 1;
  for (const JsonNode& o : r.required("overrides").as_array(0, 100000)) result.overrides.push_back(o.as_string());
  const JsonNode metrics = r.required("metrics");
  if (result.completed) {
    if (!metrics.value().is_object()) metrics.fail("the metrics object of a completed run");
    result.metrics = read_metrics(metrics);
    result.metrics_json = metrics.value();
  } else {
    result.reason = r.required("reason").as_string();
    if (!metrics.value().is_null()) metrics.fail("null for a failed run");
  }
  // Results written before trajectories were digested lack it; identical_runs then compares metrics only.
  r.read("trajectory_sha256", result.trajectory_sha256);
  if (auto dir = r.optional("run_dir"); dir && !dir->value().is_null()) dir->as_string();
  if (auto triage = r.optional("triage"); triage && !triage->value().is_object()) triage->fail("an object");
  // A failed run that had completed but whose kept files could not be written (docs/sweeps.md).
  if (auto files = r.optional("files_error"); files && !result.completed) {
    files->as_string();
    result.files_failed = true;
  }
  // Provenance and timing are for people and scripts; tables and plots do not use them.
  for (const char* key : {"campo_version", "git_rev", "scene_sha256", "spec_sha256", "wall_time_s", "files_error"}) {
    r.accept(key);
  }
  r.finish();
  return result;
}

// Mean and sd of one metric over some completed runs; empty when there are none.
template <class Metric>
std::optional<MeanSd> spread(const std::vector<const RunResult*>& completed, Metric metric) {
  if (completed.empty()) return std::nullopt;
  std::vector<double> values;
  for (const RunResult* r : completed) values.push_back(metric(r->metrics));
  const Summary s = summarize_values(values);
  return MeanSd{s.mean, s.sd};
}

TableRow summarize(const std::vector<const RunResult*>& group, const std::vector<std::string>& axes) {
  TableRow row;
  row.scene = group.front()->scene;
  for (const std::string& axis : axes) row.params.push_back(group.front()->params.value(axis, nlohmann::json()));
  row.runs = static_cast<int>(group.size());
  std::vector<const RunResult*> completed, reached;
  std::vector<double> replan_medians, replan_maxima;
  for (const RunResult* r : group) {
    if (!r->completed) {
      ++row.failed;
      continue;
    }
    completed.push_back(r);
    if (r->metrics.outcome == "reached") reached.push_back(r);
    row.collisions += r->metrics.collisions;
    if (const auto& c = r->metrics.min_clearance_m) row.min_clearance_m = std::min(row.min_clearance_m.value_or(*c), *c);
    if (r->metrics.replans > 0) {
      replan_medians.push_back(r->metrics.replan_ms_median);
      replan_maxima.push_back(r->metrics.replan_ms_max);
    }
  }
  row.reached = static_cast<int>(reached.size());
  row.success_rate = static_cast<double>(row.reached) / row.runs;
  row.identical = identical_runs(group);
  row.waypoints_reached = spread(completed, [](const RunMetrics& m) { return m.waypoints_reached; });
  row.waypoints_discarded = spread(completed, [](const RunMetrics& m) { return m.waypoints_discarded; });
  row.path_length_m = spread(completed, [](const RunMetrics& m) { return m.path_length_m; });
  row.path_ratio = spread(completed, [](const RunMetrics& m) { return m.path_ratio; });
  row.time_s = spread(completed, [](const RunMetrics& m) { return m.time_s; });
  // An aborted run's short path would pull the all-run means down: the same over the successes alone.
  row.path_length_m_reached = spread(reached, [](const RunMetrics& m) { return m.path_length_m; });
  row.path_ratio_reached = spread(reached, [](const RunMetrics& m) { return m.path_ratio; });
  row.time_s_reached = spread(reached, [](const RunMetrics& m) { return m.time_s; });
  if (!replan_medians.empty()) {
    row.replan_ms_median = box_stats(replan_medians).median;
    row.replan_ms_max = *std::max_element(replan_maxima.begin(), replan_maxima.end());
  }
  return row;
}

}  // namespace

std::string run_dir(const std::string& name) { return "runs/" + name; }

nlohmann::json completed_result(const SweepRun& run, const nlohmann::json& run_record,
                                const std::string& trajectory_sha256) {
  const nlohmann::json& provenance = run_record.at("provenance");
  nlohmann::json line = result_line(run, "completed");
  line["metrics"] = run_record.at("metrics");
  line["campo_version"] = provenance.at("campo_version");
  line["git_rev"] = provenance.at("git_revision");
  line["scene_sha256"] = provenance.at("scene").at("sha256");
  line["trajectory_sha256"] = trajectory_sha256;
  return line;
}

nlohmann::json failed_result(const SweepRun& run, const std::string& reason) {
  nlohmann::json line = result_line(run, "failed");
  line["reason"] = reason;
  line["metrics"] = nullptr;
  line["campo_version"] = library_version();
  line["git_rev"] = library_git_revision();
  line["scene_sha256"] = run.scene_sha256;
  return line;
}

ResultsLog::ResultsLog(const std::filesystem::path& path) : path_(path) {
  // Find where the last complete line ends, reading backwards from the end.
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > 0) {
    std::ifstream in(path, std::ios::binary);
    auto end = size;
    for (char c = 0; end > 0; --end) {
      in.seekg(static_cast<std::streamoff>(end - 1));
      if (!in.get(c)) throw OutputError(path, "cannot read it back to resume");
      if (c == '\n') break;
    }
    if (end < size) {
      std::filesystem::resize_file(path, end, ec);
      if (ec) throw OutputError(path, system_reason("cannot cut off its incomplete last line", ec.value()));
      cut_partial_line_ = true;
    }
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0666);
  if (fd_ < 0) throw OutputError(path, system_reason("cannot open for appending", errno));
}

ResultsLog::~ResultsLog() {
  if (fd_ >= 0) ::close(fd_);
}

void ResultsLog::append(const nlohmann::json& line) {
  const std::string text = line.dump() + "\n";
  const off_t before = ::lseek(fd_, 0, SEEK_END);
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int errnum = errno;
      // No half line stays behind for the next line to continue.
      if (before >= 0) (void)!::ftruncate(fd_, before);
      throw OutputError(path_, system_reason("cannot append", errnum));
    }
    done += static_cast<std::size_t>(n);
  }
}

std::vector<ResultLine> read_result_lines(const std::filesystem::path& path, std::vector<std::string>& warnings) {
  const std::string file = path.string();
  const std::string text = read_text_file(path, {.max_file_bytes = std::uintmax_t{1} << 32});
  std::vector<ResultLine> lines;
  std::size_t start = 0;
  for (int number = 1; start < text.size(); ++number) {
    const std::size_t newline = text.find('\n', start);
    const bool last = newline == std::string::npos;
    const std::string line = text.substr(start, last ? std::string::npos : newline - start);
    start = last ? text.size() : newline + 1;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string source = file + " line " + std::to_string(number);
    try {
      lines.push_back({parse_json_text(line, source), source});
    } catch (const InputError&) {
      // A sweep killed mid-write leaves a partial last line without its newline.
      if (!last) throw;
      warnings.push_back(source + " is incomplete (an interrupted sweep?) and was ignored");
    }
  }
  return lines;
}

ResultsFile read_results(const std::filesystem::path& path) {
  ResultsFile results;
  std::map<std::string, std::size_t> index_of;  // id -> position in results.runs
  for (const ResultLine& line : read_result_lines(path, results.warnings)) {
    RunResult result = read_result(JsonNode(line.value, line.source, ""));
    const auto [it, inserted] = index_of.emplace(result.id, results.runs.size());
    if (inserted) {
      results.runs.push_back(std::move(result));
    } else {
      results.runs[it->second] = std::move(result);  // a rerun (resumed sweep): the last line counts
    }
  }
  return results;
}

TableRequest read_table_request(const JsonNode& node) {
  ObjectReader r(node);
  TableRequest request;
  request.file = node.file();
  request.rows_at = child_pointer(node.pointer(), "rows");
  request.cols_at = child_pointer(node.pointer(), "cols");
  request.metrics_at = child_pointer(node.pointer(), "metrics");
  request.rows = r.required("rows").as_string();
  r.read("cols", request.cols);
  for (const JsonNode& metric : r.required("metrics").as_array(1, 100)) request.metrics.push_back(metric.as_string());
  r.finish();
  return request;
}

TableLayout table_layout(const std::filesystem::path& dir, const std::vector<RunResult>& runs) {
  TableLayout layout;
  const std::filesystem::path manifest = dir / "sweep.json";
  if (std::filesystem::exists(manifest)) {
    // campo sweep validated the spec and wrote this file: read only what the table needs, so a sweep
    // directory stays readable wherever it is copied (scene files elsewhere) and as the format grows.
    const nlohmann::json document = read_json_file(manifest);
    ObjectReader r(JsonNode(document, manifest.string(), ""));
    const JsonNode spec = r.required("spec");
    ObjectReader s(spec);
    layout.name = std::filesystem::path(r.required("spec_file").as_string()).stem().string();
    s.read("name", layout.name);
    if (auto axes = s.optional("axes")) {
      for (const JsonNode& axis : axes->as_array(0, SweepLimits{}.max_axes)) {
        layout.axes.push_back(ObjectReader(axis).required("name").as_string());
      }
    }
    if (auto table = s.optional("table")) layout.table = read_table_request(*table);
    for (const JsonNode& run : r.required("runs").as_array(0, SweepLimits{}.max_runs)) {
      layout.run_order.push_back(ObjectReader(run).required("id").as_string());
    }
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

nlohmann::json field_value(const RunResult& run, const std::string& field) {
  if (field == "scene") return run.scene;
  if (field == "planner") return run.planner.empty() ? nlohmann::json() : nlohmann::json(run.planner);
  if (field == "seed") return run.seed;
  return run.params.value(field, nlohmann::json());
}

void check_field(const std::string& field, const std::vector<std::string>& axes, const std::string& file,
                 const std::string& where) {
  std::string known;
  for (std::string_view f : kRunFields) (known += known.empty() ? "" : ", ") += f;
  for (const std::string& axis : axes) known += ", " + axis;
  const bool found = std::find(kRunFields.begin(), kRunFields.end(), field) != kRunFields.end() ||
                     std::find(axes.begin(), axes.end(), field) != axes.end();
  if (!found) throw InputError(file, where, "expected a field of the runs (" + known + "), got \"" + field + "\"");
}

std::vector<std::string> available_metrics(const std::vector<RunResult>& runs) {
  std::set<std::string> names;
  for (const RunResult& run : runs) {
    if (!run.completed) continue;
    for (const auto& [key, value] : run.metrics_json.items()) {
      if (value.is_number() || value.is_boolean()) names.insert(key);
    }
  }
  std::vector<std::string> metrics{"success"};
  metrics.insert(metrics.end(), names.begin(), names.end());
  return metrics;
}

MetricName split_metric(const std::string& metric) {
  const std::size_t at = metric.find('@');
  if (at == std::string::npos) return {metric, false};
  return {metric.substr(0, at), metric.substr(at) == kReachedSuffix};
}

bool measured_metric(std::string_view key) {
  return key == "wall_time_s" || key.starts_with("planner_time_ms_") || key.starts_with("replan_time_ms_");
}

bool identical_runs(const std::vector<const RunResult*>& runs) {
  if (runs.size() < 2) return false;
  // Everything a run's seed could change but the wall-clock measurements.
  const auto deterministic = [](const RunResult& run) {
    nlohmann::json metrics = nlohmann::json::object();
    for (const auto& [key, value] : run.metrics_json.items()) {
      if (!measured_metric(key)) metrics[key] = value;
    }
    return metrics;
  };
  const RunResult& first = *runs.front();
  if (!first.completed) return false;
  const nlohmann::json reference = deterministic(first);
  return std::all_of(runs.begin() + 1, runs.end(), [&](const RunResult* run) {
    return run->completed && run->trajectory_sha256 == first.trajectory_sha256 && deterministic(*run) == reference;
  });
}

MetricKind check_metric(const std::string& metric, const std::vector<RunResult>& runs, const std::string& file,
                        const std::string& where) {
  const MetricName name = split_metric(metric);
  if (name.base.size() != metric.size() && !name.reached_only) {
    throw InputError(file, where, "expected a metric, or a metric over the runs that reached their goal as \"" +
                                      name.base + std::string(kReachedSuffix) + "\", got \"" + metric + "\"");
  }
  const bool success = name.base == "success" || name.base == "outcome";
  if (success && name.reached_only) {
    throw InputError(file, where, "expected \"success\" without \"@reached\" (over the runs that reached their "
                                  "goal it is 100 % by definition), got \"" + metric + "\"");
  }
  if (success) return MetricKind::rate;
  bool completed = false, number = false, boolean = false;
  for (const RunResult& run : runs) {
    if (!run.completed) continue;
    completed = true;
    const nlohmann::json value = run.metrics_json.value(name.base, nlohmann::json());
    number = number || value.is_number();
    boolean = boolean || value.is_boolean();
  }
  if (completed && !number && !boolean) {
    std::string known;
    for (const std::string& m : available_metrics(runs)) (known += known.empty() ? "" : ", ") += m;
    throw InputError(file, where, "expected a metric of the runs (" + known + "), got \"" + metric + "\"");
  }
  return boolean && !number ? MetricKind::rate : MetricKind::number;
}

std::optional<double> metric_value(const RunResult& run, const std::string& metric) {
  const MetricName name = split_metric(metric);
  const bool reached = run.completed && run.metrics.outcome == "reached";
  if (name.base == "success" || name.base == "outcome") return reached ? 1.0 : 0.0;
  if (!run.completed || (name.reached_only && !reached)) return std::nullopt;
  const nlohmann::json value = run.metrics_json.value(name.base, nlohmann::json());
  if (value.is_boolean()) return value.get<bool>() ? 1.0 : 0.0;
  if (value.is_number()) return value.get<double>();
  return std::nullopt;
}

std::optional<Summary> summarize_metric(const std::vector<const RunResult*>& runs, const std::string& metric,
                                        MetricKind kind) {
  std::vector<double> values;
  for (const RunResult* run : runs) {
    if (const auto v = metric_value(*run, metric)) values.push_back(*v);
  }
  if (values.empty()) return std::nullopt;
  if (kind == MetricKind::number) return summarize_values(values);
  const auto successes = std::count(values.begin(), values.end(), 1.0);
  return summarize_rate(static_cast<int>(successes), static_cast<int>(values.size()));
}

std::size_t index_in_order(std::vector<nlohmann::json>& values, const nlohmann::json& value) {
  const auto it = std::find(values.begin(), values.end(), value);
  if (it != values.end()) return static_cast<std::size_t>(it - values.begin());
  values.push_back(value);
  return values.size() - 1;
}

std::vector<RunGroup> group_runs(const std::vector<RunResult>& runs, const TableLayout& layout,
                                 const std::vector<std::string>& fields) {
  // A run's rank: its place in the expansion, else after all of them in order of appearance.
  std::map<std::string, std::size_t> rank_of;
  for (std::size_t i = 0; i < layout.run_order.size(); ++i) rank_of.emplace(layout.run_order[i], i);
  std::vector<RunGroup> groups;
  std::vector<std::size_t> ranks;                 // per group: its first run's rank
  std::map<std::string, std::size_t> index_of;    // key as JSON text -> group
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResult& run = runs[i];
    std::vector<nlohmann::json> key;
    for (const std::string& field : fields) key.push_back(field_value(run, field));
    const auto it = rank_of.find(run.id);
    const std::size_t rank = it != rank_of.end() ? it->second : layout.run_order.size() + i;
    const auto [group, inserted] = index_of.try_emplace(nlohmann::json(key).dump(), groups.size());
    if (inserted) {
      groups.push_back({std::move(key), {}});
      ranks.push_back(rank);
    }
    groups[group->second].runs.push_back(&run);
    ranks[group->second] = std::min(ranks[group->second], rank);
  }
  std::vector<std::size_t> order(groups.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ranks[a] < ranks[b]; });
  std::vector<RunGroup> ordered;
  for (std::size_t i : order) ordered.push_back(std::move(groups[i]));
  return ordered;
}

SweepTable aggregate(const std::vector<RunResult>& runs, const TableLayout& layout) {
  std::vector<std::string> fields{"scene"};
  fields.insert(fields.end(), layout.axes.begin(), layout.axes.end());
  SweepTable table{layout.name, layout.axes, {}};
  for (const RunGroup& group : group_runs(runs, layout, fields)) table.rows.push_back(summarize(group.runs, layout.axes));
  return table;
}

}  // namespace campo
