#include "sweep/results.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
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

RunMetrics read_metrics(const JsonNode& node, bool fleet) {
  // Only the keys the table uses: run.json's metrics are defined (and grow) in run/, so no finish().
  ObjectReader r(node);
  RunMetrics m;
  m.outcome = r.required("outcome").as_string();
  if (fleet) {
    // A run of several vehicles: the fleet's outcome, time and collisions; paths are each vehicle's.
    m.fleet = true;
    m.time_s = r.required("sim_time_s").as_number(Range::non_negative());
    m.collisions = static_cast<int>(r.required("collisions").as_int(0, 1 << 30));
    return m;
  }
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
  // A run of several vehicles: each one's metrics beside the fleet's (absent for one vehicle and in older results).
  if (auto vehicles = r.optional("vehicles"); vehicles && result.completed) {
    for (const JsonNode& vehicle : vehicles->as_array(2, 100000)) {
      ObjectReader v(vehicle);
      VehicleMetrics entry;
      entry.alias = v.required("alias").as_string();
      const JsonNode vehicle_metrics = v.required("metrics");
      if (!vehicle_metrics.value().is_object()) vehicle_metrics.fail("the vehicle's metrics object");
      read_metrics(vehicle_metrics, false);
      entry.metrics = vehicle_metrics.value();
      v.finish();
      for (const VehicleMetrics& other : result.vehicles) {
        if (other.alias == entry.alias) vehicle.fail("a vehicle alias once (\"" + entry.alias + "\" appears twice)");
      }
      result.vehicles.push_back(std::move(entry));
    }
  } else if (vehicles) {
    vehicles->fail("no vehicles for a failed run");
  }
  if (result.completed) {
    if (!metrics.value().is_object()) metrics.fail("the metrics object of a completed run");
    result.metrics = read_metrics(metrics, !result.vehicles.empty());
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

// Mean, sd and interval of one metric over some completed runs; empty when there are none.
// Every statistic of the summary (waypoints, lengths, ratios, times) is >= 0 by definition.
std::optional<MeanSd> spread(const RunningStats& stats) {
  if (stats.count() == 0) return std::nullopt;
  const Summary s = stats.values(Support::non_negative);
  return MeanSd{s.mean, s.sd, s.ci95};
}

// One row of the summary table, a run at a time.
struct RowFold {
  std::string scene;
  nlohmann::json params;  // the first run's
  int runs = 0, failed = 0, reached = 0, collisions = 0;
  std::optional<double> min_clearance_m;
  // Over the completed runs, then over the reached ones.
  RunningStats waypoints_reached, waypoints_discarded, path_length_m, path_ratio, time_s;
  RunningStats path_length_m_reached, path_ratio_reached, time_s_reached;
  QuantileSketch replan_medians;
  std::optional<double> replan_max;
  IdenticalRuns identical;

  void add(const RunResult& r) {
    if (runs++ == 0) {
      scene = r.scene;
      params = r.params;
    }
    identical.add(r);
    if (!r.completed) {
      ++failed;
      return;
    }
    const RunMetrics& m = r.metrics;
    if (m.outcome == "reached") ++reached;
    collisions += m.collisions;
    if (m.fleet) {
      // Several vehicles: the path metrics are each vehicle's (campo table --vehicle, or ALIAS.METRIC).
      time_s.add(m.time_s);
      if (m.outcome == "reached") time_s_reached.add(m.time_s);
      return;
    }
    waypoints_reached.add(m.waypoints_reached);
    waypoints_discarded.add(m.waypoints_discarded);
    path_length_m.add(m.path_length_m);
    path_ratio.add(m.path_ratio);
    time_s.add(m.time_s);
    if (m.outcome == "reached") {
      path_length_m_reached.add(m.path_length_m);
      path_ratio_reached.add(m.path_ratio);
      time_s_reached.add(m.time_s);
    }
    if (const auto& c = m.min_clearance_m) min_clearance_m = std::min(min_clearance_m.value_or(*c), *c);
    if (m.replans > 0) {
      replan_medians.add(m.replan_ms_median);
      replan_max = std::max(replan_max.value_or(m.replan_ms_max), m.replan_ms_max);
    }
  }

  TableRow row(const std::vector<std::string>& axes) const {
    TableRow row;
    row.scene = scene;
    for (const std::string& axis : axes) row.params.push_back(params.value(axis, nlohmann::json()));
    row.runs = runs;
    row.failed = failed;
    row.reached = reached;
    row.success_rate = static_cast<double>(reached) / runs;
    row.identical = identical.identical();
    row.collisions = collisions;
    row.min_clearance_m = min_clearance_m;
    row.waypoints_reached = spread(waypoints_reached);
    row.waypoints_discarded = spread(waypoints_discarded);
    row.path_length_m = spread(path_length_m);
    row.path_ratio = spread(path_ratio);
    row.time_s = spread(time_s);
    // An aborted run's short path would pull the all-run means down: the same over the successes alone.
    row.path_length_m_reached = spread(path_length_m_reached);
    row.path_ratio_reached = spread(path_ratio_reached);
    row.time_s_reached = spread(time_s_reached);
    if (replan_medians.count() > 0) {
      row.replan_ms_median = replan_medians.median();
      row.replan_ms_max = replan_max;
    }
    return row;
  }
};

// 128 bits of a run ID: two independent 64-bit hashes (FNV-1a and the standard library's).
struct IdDigest {
  std::uint64_t a = 0, b = 0;
  bool operator<(const IdDigest& o) const { return a != o.a ? a < o.a : b < o.b; }
  bool operator==(const IdDigest& o) const { return a == o.a && b == o.b; }
};

IdDigest id_digest(const std::string& id) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : id) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return {h, static_cast<std::uint64_t>(std::hash<std::string>{}(id))};
}

}  // namespace

std::string run_dir(const std::string& name) { return "runs/" + name; }

bool SweepItemResult::reached() const { return completed && metrics.value("outcome", "") == "reached"; }

SweepItemResult completed_item(const nlohmann::json& run_record, const std::string& trajectory_sha256) {
  const nlohmann::json& provenance = run_record.at("provenance");
  SweepItemResult result;
  result.completed = true;
  result.metrics = run_record.at("metrics");
  if (const auto vehicles = run_record.find("vehicles"); vehicles != run_record.end()) {
    result.vehicles = nlohmann::json::array();
    for (const nlohmann::json& vehicle : *vehicles) {
      result.vehicles.push_back({{"alias", vehicle.at("alias")}, {"metrics", vehicle.at("metrics")}});
    }
  }
  result.campo_version = provenance.at("campo_version");
  result.git_rev = provenance.at("git_revision");
  result.scene_sha256 = provenance.at("scene").at("sha256");
  result.trajectory_sha256 = trajectory_sha256;
  return result;
}

SweepItemResult failed_item(const std::string& reason) {
  SweepItemResult result;
  result.reason = reason;
  return result;
}

nlohmann::json to_json(const SweepItemResult& r) {
  return {{"completed", r.completed},         {"reason", r.reason},
          {"files_failed", r.files_failed},   {"files_error", r.files_error},
          {"metrics", r.metrics},             {"campo_version", r.campo_version},
          {"git_rev", r.git_rev},             {"scene_sha256", r.scene_sha256},
          {"trajectory_sha256", r.trajectory_sha256}, {"kept_run_dir", r.kept_run_dir},
          {"vehicles", r.vehicles}};
}

SweepItemResult sweep_item_result_from_json(const nlohmann::json& json) {
  SweepItemResult r;
  r.completed = json.at("completed").get<bool>();
  r.reason = json.at("reason").get<std::string>();
  r.files_failed = json.at("files_failed").get<bool>();
  r.files_error = json.at("files_error").get<std::string>();
  r.metrics = json.at("metrics");
  r.campo_version = json.at("campo_version");
  r.git_rev = json.at("git_rev");
  r.scene_sha256 = json.at("scene_sha256");
  r.trajectory_sha256 = json.at("trajectory_sha256").get<std::string>();
  r.kept_run_dir = json.at("kept_run_dir").get<bool>();
  r.vehicles = json.at("vehicles");
  return r;
}

nlohmann::json result_line(const SweepRun& run, const SweepItemResult& result, const ResultLineContext& context) {
  nlohmann::json line = {{"id", run.id},
                         {"name", run.name},
                         {"scene", run.scene},
                         {"planner", run.planner},
                         {"params", run.params},
                         {"seed", run.seed},
                         {"status", result.completed ? "completed" : "failed"},
                         {"overrides", override_texts(run.overrides)},
                         {"run_dir", result.kept_run_dir ? nlohmann::json(run_dir(run.name)) : nlohmann::json()}};
  if (result.completed) {
    line["metrics"] = result.metrics;
    line["campo_version"] = result.campo_version;
    line["git_rev"] = result.git_rev;
    line["scene_sha256"] = result.scene_sha256;
    line["trajectory_sha256"] = result.trajectory_sha256;
    if (!result.vehicles.is_null()) line["vehicles"] = result.vehicles;
  } else {
    line["reason"] = result.reason;
    line["metrics"] = nullptr;
    line["campo_version"] = library_version();
    line["git_rev"] = library_git_revision();
    line["scene_sha256"] = run.scene_sha256;
  }
  if (!result.files_error.empty()) line["files_error"] = result.files_error;
  line["wall_time_s"] = context.wall_time_s;
  line["spec_sha256"] = context.spec_sha256;
  if (context.triage) line["triage"] = {{"dir", context.triage->dir}, {"repro", context.triage->repro}};
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

void for_each_result_line(const std::filesystem::path& path, std::vector<std::string>& warnings,
                          const std::function<void(nlohmann::json&&, const std::string&)>& line,
                          const ResultsLimits& limits) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "", "cannot read: not an existing regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > limits.max_file_bytes) {
    throw InputError(file, "", "file too large: " + std::to_string(size) + " bytes, expected at most " +
                                   std::to_string(limits.max_file_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open for reading");
  // Read in blocks; a line is parsed as soon as its newline is in, so memory is one line and one block.
  std::vector<char> block(std::size_t{1} << 20);
  std::string text;  // the current line so far
  int number = 1;
  const auto finish_line = [&](bool last) {
    const std::string source = file + " line " + std::to_string(number++);
    if (text.find_first_not_of(" \t\r") == std::string::npos) return;
    nlohmann::json value;
    try {
      value = parse_json_text(text, source, {.max_file_bytes = limits.max_line_bytes});
    } catch (const InputError&) {
      // A sweep killed mid-write leaves a partial last line without its newline.
      if (!last) throw;
      warnings.push_back(source + " is incomplete (an interrupted sweep?) and was ignored");
      return;
    }
    line(std::move(value), source);
  };
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const std::size_t got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    std::size_t start = 0;
    while (start < got) {
      const char* begin = block.data() + start;
      const char* newline = static_cast<const char*>(std::memchr(begin, '\n', got - start));
      const std::size_t count = newline ? static_cast<std::size_t>(newline - begin) : got - start;
      if (text.size() + count > limits.max_line_bytes) {
        throw InputError(file + " line " + std::to_string(number), "",
                         "line too long: expected at most " + std::to_string(limits.max_line_bytes) + " bytes");
      }
      text.append(begin, count);
      start += count;
      if (newline) {
        finish_line(false);
        text.clear();
        ++start;
      }
    }
  }
  if (in.bad()) throw InputError(file, "", "cannot read: " + std::string(std::strerror(errno)));
  if (!text.empty()) finish_line(true);
}

std::vector<ResultLine> read_result_lines(const std::filesystem::path& path, std::vector<std::string>& warnings) {
  std::vector<ResultLine> lines;
  for_each_result_line(path, warnings, [&](nlohmann::json&& value, const std::string& source) {
    lines.push_back({std::move(value), source});
  }, {});
  return lines;
}

void for_each_result(const std::filesystem::path& path, std::vector<std::string>& warnings,
                     const std::function<void()>& restart,
                     const std::function<void(const RunResult&, std::size_t)>& visit, const ResultsLimits& limits) {
  // First reading: every line visited as it comes, each ID's digest kept (16 bytes a line).
  std::vector<IdDigest> digests;
  restart();
  for_each_result_line(path, warnings, [&](nlohmann::json&& value, const std::string& source) {
    const RunResult run = read_result(JsonNode(value, source, ""));
    digests.push_back(id_digest(run.id));
    visit(run, digests.size() - 1);
  }, limits);
  std::sort(digests.begin(), digests.end());
  // How many lines each repeated ID has; none in a sweep that was never resumed.
  std::map<IdDigest, std::size_t> lines_of;
  for (std::size_t i = 0; i < digests.size();) {
    std::size_t j = i + 1;
    while (j < digests.size() && digests[j] == digests[i]) ++j;
    if (j - i > 1) lines_of.emplace(digests[i], j - i);
    i = j;
  }
  digests = {};
  if (lines_of.empty()) return;
  // Second reading: each repeated ID at its last line, in the place of its first.
  std::map<IdDigest, std::pair<std::size_t, std::size_t>> seen;  // repeated ID -> lines read, index
  std::size_t next_index = 0;
  std::vector<std::string> ignored;  // the first reading reported them
  restart();
  for_each_result_line(path, ignored, [&](nlohmann::json&& value, const std::string& source) {
    const RunResult run = read_result(JsonNode(value, source, ""));
    const IdDigest digest = id_digest(run.id);
    const auto repeated = lines_of.find(digest);
    if (repeated == lines_of.end()) {
      visit(run, next_index++);
      return;
    }
    auto [it, first] = seen.try_emplace(digest, 0, next_index);
    if (first) ++next_index;
    if (++it->second.first == repeated->second) visit(run, it->second.second);  // a rerun: the last line counts
  }, limits);
}

ResultsFile read_results(const std::filesystem::path& path) {
  ResultsFile results;
  std::vector<std::pair<std::size_t, RunResult>> runs;
  for_each_result(path, results.warnings, [&] { runs.clear(); },
                  [&](const RunResult& run, std::size_t index) { runs.emplace_back(index, run); });
  std::stable_sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [index, run] : runs) results.runs.push_back(std::move(run));
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

TableLayout table_layout(const std::filesystem::path& dir) {
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
  layout.axes_from_runs = true;
  return layout;
}

void add_axes(TableLayout& layout, const RunResult& run) {
  if (!layout.axes_from_runs) return;
  for (const auto& [axis, value] : run.params.items()) {
    if (std::find(layout.axes.begin(), layout.axes.end(), axis) == layout.axes.end()) layout.axes.push_back(axis);
  }
}

TableLayout table_layout(const std::filesystem::path& dir, const std::vector<RunResult>& runs) {
  TableLayout layout = table_layout(dir);
  for (const RunResult& run : runs) add_axes(layout, run);
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

MetricName split_metric(const std::string& metric) {
  const std::size_t at = metric.find('@');
  if (at == std::string::npos) return {metric, false};
  return {metric.substr(0, at), metric.substr(at) == kReachedSuffix};
}

VehicleMetricName split_vehicle_metric(const std::string& metric) {
  const std::size_t dot = metric.rfind('.', metric.find('@'));
  if (dot == std::string::npos) return {"", metric};
  return {metric.substr(0, dot), metric.substr(dot + 1)};
}

std::string vehicle_metric_name(const std::string& metric, const std::string& alias) {
  return split_vehicle_metric(metric).vehicle.empty() ? alias + "." + metric : metric;
}

namespace {

// A list of names for an error: "a, b, c".
std::string name_list(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) (text += text.empty() ? "" : ", ") += name;
  return text;
}

// The vehicle `alias` of a run, or null.
const VehicleMetrics* find_vehicle(const RunResult& run, const std::string& alias) {
  for (const VehicleMetrics& vehicle : run.vehicles) {
    if (vehicle.alias == alias) return &vehicle;
  }
  return nullptr;
}

// Whether `metric` names a vehicle's metric rather than one of the run's (whose names hold no dot,
// but a run's metric of that exact name would win).
std::optional<VehicleMetricName> vehicle_part(const std::string& metric, const nlohmann::json& run_metrics) {
  const VehicleMetricName name = split_vehicle_metric(metric);
  if (name.vehicle.empty()) return std::nullopt;
  if (run_metrics.is_object() && run_metrics.contains(split_metric(metric).base)) return std::nullopt;
  return name;
}

}  // namespace

RunResult vehicle_run(const RunResult& run, const std::string& alias, const std::string& file,
                      const std::string& where) {
  if (!run.completed) return run;
  const VehicleMetrics* vehicle = find_vehicle(run, alias);
  if (vehicle == nullptr) {
    std::vector<std::string> aliases;
    for (const VehicleMetrics& v : run.vehicles) aliases.push_back(v.alias);
    throw InputError(file, where,
                     "expected a vehicle of run " + run.name +
                         (aliases.empty() ? " (it has one vehicle: its metrics are the plain names, no --vehicle)"
                                          : " (" + name_list(aliases) + ")") +
                         ", got \"" + alias + "\"");
  }
  RunResult seen = run;
  seen.metrics_json = vehicle->metrics;
  seen.metrics = read_metrics(JsonNode(vehicle->metrics, file, "/vehicles/" + alias + "/metrics"), false);
  return seen;
}

bool measured_metric(std::string_view key) {
  return key == "wall_time_s" || key.starts_with("planner_time_ms_") || key.starts_with("replan_time_ms_");
}

namespace {

// Everything a run's seed could change but the wall-clock measurements.
nlohmann::json deterministic_metrics(const RunResult& run) {
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [key, value] : run.metrics_json.items()) {
    if (!measured_metric(key)) metrics[key] = value;
  }
  if (run.vehicles.empty()) return metrics;
  // Several vehicles: each one's too (the fleet's own "vehicles" is their number).
  nlohmann::json all = {{"run", std::move(metrics)}, {"vehicles", nlohmann::json::array()}};
  for (const VehicleMetrics& vehicle : run.vehicles) {
    nlohmann::json own = {{"alias", vehicle.alias}};
    for (const auto& [key, value] : vehicle.metrics.items()) {
      if (!measured_metric(key)) own[key] = value;
    }
    all["vehicles"].push_back(std::move(own));
  }
  return all;
}

}  // namespace

void IdenticalRuns::add(const RunResult& run) {
  if (same_ && !run.completed) {
    same_ = false;
  } else if (same_ && runs_ == 0) {
    metrics_ = deterministic_metrics(run);
    trajectory_sha256_ = run.trajectory_sha256;
  } else if (same_ && (run.trajectory_sha256 != trajectory_sha256_ || deterministic_metrics(run) != metrics_)) {
    same_ = false;
  }
  if (!same_) metrics_ = nullptr;  // nothing left to compare
  ++runs_;
}

bool identical_runs(const std::vector<const RunResult*>& runs) {
  IdenticalRuns identical;
  for (const RunResult* run : runs) identical.add(*run);
  return identical.identical();
}

void MetricCatalog::add(const RunResult& run) {
  if (!run.completed) return;
  completed_ = true;
  for (const auto& [key, value] : run.metrics_json.items()) {
    if (value.is_number()) kinds_[key] |= 1;
    if (value.is_boolean()) kinds_[key] |= 2;
  }
  for (const VehicleMetrics& vehicle : run.vehicles) {
    if (std::find(aliases_.begin(), aliases_.end(), vehicle.alias) == aliases_.end()) aliases_.push_back(vehicle.alias);
    auto& kinds = vehicle_kinds_[vehicle.alias];
    for (const auto& [key, value] : vehicle.metrics.items()) {
      if (value.is_number()) kinds[key] |= 1;
      if (value.is_boolean()) kinds[key] |= 2;
    }
  }
}

std::vector<std::string> MetricCatalog::available() const {
  std::vector<std::string> metrics{"success"};
  for (const auto& [name, kinds] : kinds_) metrics.push_back(name);
  for (const std::string& alias : aliases_) {
    metrics.push_back(alias + ".success");
    for (const auto& [name, kinds] : vehicle_kinds_.at(alias)) metrics.push_back(alias + "." + name);
  }
  return metrics;
}

MetricKind MetricCatalog::check(const std::string& metric, const std::string& file, const std::string& where) const {
  const MetricName name = split_metric(metric);
  if (name.base.size() != metric.size() && !name.reached_only) {
    throw InputError(file, where, "expected a metric, or a metric over the runs that reached their goal as \"" +
                                      name.base + std::string(kReachedSuffix) + "\", got \"" + metric + "\"");
  }
  // A vehicle's metric, "ALIAS.METRIC", unless the runs have a metric of that whole name.
  std::optional<VehicleMetricName> vehicle;
  if (kinds_.find(name.base) == kinds_.end()) {
    if (VehicleMetricName v = split_vehicle_metric(metric); !v.vehicle.empty()) vehicle = v;
  }
  const std::string base = vehicle ? split_metric(vehicle->metric).base : name.base;
  const bool success = base == "success" || base == "outcome";
  if (success && name.reached_only) {
    throw InputError(file, where, "expected \"success\" without \"@reached\" (over the runs that reached their "
                                  "goal it is 100 % by definition), got \"" + metric + "\"");
  }
  if (vehicle && completed_) {
    const auto own = vehicle_kinds_.find(vehicle->vehicle);
    if (own == vehicle_kinds_.end()) {
      throw InputError(file, where,
                       aliases_.empty()
                           ? "expected a metric of the runs (" + name_list(available()) +
                                 "): their runs have one vehicle each, no ALIAS.METRIC; got \"" + metric + "\""
                           : "expected ALIAS.METRIC with a vehicle of the runs (" + name_list(aliases_) +
                                 "), got \"" + vehicle->vehicle + "\" in \"" + metric + "\"");
    }
    if (success) return MetricKind::rate;
    const auto it = own->second.find(base);
    if (it == own->second.end()) {
      std::vector<std::string> known{vehicle->vehicle + ".success"};
      for (const auto& [key, kinds] : own->second) known.push_back(vehicle->vehicle + "." + key);
      throw InputError(file, where, "expected a metric of vehicle " + vehicle->vehicle + " (" + name_list(known) +
                                        "), got \"" + metric + "\"");
    }
    return (it->second & 2) != 0 && (it->second & 1) == 0 ? MetricKind::rate : MetricKind::number;
  }
  if (success) return MetricKind::rate;
  if (vehicle) return MetricKind::number;  // no run yet to check it against
  const auto it = kinds_.find(name.base);
  const bool number = it != kinds_.end() && (it->second & 1) != 0;
  const bool boolean = it != kinds_.end() && (it->second & 2) != 0;
  if (completed_ && !number && !boolean) {
    std::vector<std::string> known{"success"};
    for (const auto& [key, kinds] : kinds_) known.push_back(key);
    const std::string vehicles =
        aliases_.empty() ? "" : ", or ALIAS.METRIC of a vehicle (" + name_list(aliases_) + ")";
    throw InputError(file, where,
                     "expected a metric of the runs (" + name_list(known) + vehicles + "), got \"" + metric + "\"");
  }
  return boolean && !number ? MetricKind::rate : MetricKind::number;
}

std::vector<std::string> available_metrics(const std::vector<RunResult>& runs) {
  MetricCatalog catalog;
  for (const RunResult& run : runs) catalog.add(run);
  return catalog.available();
}

MetricKind check_metric(const std::string& metric, const std::vector<RunResult>& runs, const std::string& file,
                        const std::string& where) {
  MetricCatalog catalog;
  for (const RunResult& run : runs) catalog.add(run);
  return catalog.check(metric, file, where);
}

bool non_negative_metric(const std::string& metric) {
  // A vehicle's metric is what the same metric of a run of one vehicle is.
  const std::string base = split_metric(split_vehicle_metric(metric).metric).base;
  if (base.find("clearance") != std::string::npos) return false;  // signed distances
  static constexpr std::array<std::string_view, 7> kNonNegative{
      "path_ratio", "collisions", "replans", "planner_calls", "waypoints_planned", "waypoints_reached",
      "waypoints_discarded"};
  if (std::find(kNonNegative.begin(), kNonNegative.end(), base) != kNonNegative.end()) return true;
  // A unit of time or length among the words after the first: "sim_time_s", "replan_time_ms_max".
  std::size_t start = base.find('_');
  while (start != std::string::npos) {
    const std::size_t end = base.find('_', start + 1);
    const std::string_view word(base.data() + start + 1, (end == std::string::npos ? base.size() : end) - start - 1);
    if (word == "s" || word == "ms" || word == "m") return true;
    start = end;
  }
  return false;
}

Support metric_support(const std::string& metric) {
  return non_negative_metric(metric) ? Support::non_negative : Support::real;
}

std::optional<double> metric_value(const RunResult& run, const std::string& metric) {
  if (const auto vehicle = vehicle_part(metric, run.metrics_json)) {
    const VehicleMetrics* own = find_vehicle(run, vehicle->vehicle);
    const MetricName name = split_metric(vehicle->metric);
    if (!run.completed) {
      return name.base == "success" || name.base == "outcome" ? std::optional<double>(0.0) : std::nullopt;
    }
    if (own == nullptr) return std::nullopt;
    const bool reached = own->metrics.value("outcome", "") == "reached";
    if (name.base == "success" || name.base == "outcome") return reached ? 1.0 : 0.0;
    if (name.reached_only && !reached) return std::nullopt;
    const nlohmann::json value = own->metrics.value(name.base, nlohmann::json());
    if (value.is_boolean()) return value.get<bool>() ? 1.0 : 0.0;
    if (value.is_number()) return value.get<double>();
    return std::nullopt;
  }
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
  if (kind == MetricKind::number) return summarize_values(values, metric_support(metric));
  const auto successes = std::count(values.begin(), values.end(), 1.0);
  return summarize_rate(static_cast<int>(successes), static_cast<int>(values.size()));
}

std::size_t index_in_order(std::vector<nlohmann::json>& values, const nlohmann::json& value) {
  const auto it = std::find(values.begin(), values.end(), value);
  if (it != values.end()) return static_cast<std::size_t>(it - values.begin());
  values.push_back(value);
  return values.size() - 1;
}

RunGroups::RunGroups(const TableLayout& layout, std::vector<std::string> fields, bool all_params)
    : fields_(std::move(fields)), all_params_(all_params), order_size_(layout.run_order.size()) {
  for (std::size_t i = 0; i < layout.run_order.size(); ++i) rank_of_.emplace(layout.run_order[i], i);
}

std::size_t RunGroups::add(const RunResult& run, std::size_t index) {
  std::vector<nlohmann::json> key;
  for (const std::string& field : fields_) key.push_back(field_value(run, field));
  if (all_params_) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [axis, value] : run.params.items()) {
      if (!value.is_null()) params[axis] = value;
    }
    key.push_back(std::move(params));
  }
  // A run's rank: its place in the expansion, else after all of them in order of appearance.
  const auto it = rank_of_.find(run.id);
  const std::size_t rank = it != rank_of_.end() ? it->second : order_size_ + index;
  const auto [group, inserted] = index_of_.try_emplace(nlohmann::json(key).dump(), keys_.size());
  if (inserted) {
    keys_.push_back(std::move(key));
    ranks_.push_back(rank);
  }
  ranks_[group->second] = std::min(ranks_[group->second], rank);
  return group->second;
}

std::vector<std::size_t> RunGroups::order() const {
  std::vector<std::size_t> order(keys_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ranks_[a] < ranks_[b]; });
  return order;
}

std::vector<RunGroup> group_runs(const std::vector<RunResult>& runs, const TableLayout& layout,
                                 const std::vector<std::string>& fields) {
  RunGroups index(layout, fields);
  std::vector<RunGroup> groups;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::size_t g = index.add(runs[i], i);
    if (g == groups.size()) groups.push_back({index.key(g), {}});
    groups[g].runs.push_back(&runs[i]);
  }
  std::vector<RunGroup> ordered;
  for (std::size_t g : index.order()) ordered.push_back(std::move(groups[g]));
  return ordered;
}

struct SummaryBuilder::Impl {
  const TableLayout& layout;
  RunGroups groups;
  std::vector<RowFold> rows;  // per group
};

namespace {

// The summary's rows: scene and axes. Without sweep.json the axes are known only at the end: the rows
// are then the scene and the whole params (RunGroups' all_params).
RunGroups summary_groups(const TableLayout& layout) {
  std::vector<std::string> fields{"scene"};
  if (layout.axes_from_runs) return RunGroups(layout, fields, true);
  fields.insert(fields.end(), layout.axes.begin(), layout.axes.end());
  return RunGroups(layout, fields);
}

}  // namespace

SummaryBuilder::SummaryBuilder(const TableLayout& layout) : impl_(new Impl{layout, summary_groups(layout), {}}) {}
SummaryBuilder::~SummaryBuilder() = default;
SummaryBuilder::SummaryBuilder(SummaryBuilder&&) noexcept = default;
SummaryBuilder& SummaryBuilder::operator=(SummaryBuilder&&) noexcept = default;

void SummaryBuilder::add(const RunResult& run, std::size_t index) {
  const std::size_t g = impl_->groups.add(run, index);
  if (g == impl_->rows.size()) impl_->rows.emplace_back();
  impl_->rows[g].add(run);
}

SweepTable SummaryBuilder::finish() const {
  SweepTable table{impl_->layout.name, impl_->layout.axes, {}};
  for (std::size_t g : impl_->groups.order()) table.rows.push_back(impl_->rows[g].row(impl_->layout.axes));
  return table;
}

SweepTable aggregate(const std::vector<RunResult>& runs, const TableLayout& layout) {
  SummaryBuilder builder(layout);
  for (std::size_t i = 0; i < runs.size(); ++i) builder.add(runs[i], i);
  return builder.finish();
}

}  // namespace campo
