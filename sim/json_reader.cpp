#include "sim/json_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <fstream>
#include <sstream>

namespace campo {

namespace {

std::string describe_value(const nlohmann::json& v) {
  std::string text = v.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

InputError::InputError(std::string file, std::string pointer, const std::string& message)
    : std::runtime_error(file + ": " + (pointer.empty() ? std::string() : pointer + ": ") + message),
      file_(std::move(file)),
      pointer_(std::move(pointer)) {}

nlohmann::json parse_json_text(const std::string& text, const std::string& source,
                               const InputLimits& limits) {
  if (text.size() > limits.max_file_bytes) {
    throw InputError(source, "", "file too large: " + std::to_string(text.size()) +
                                     " bytes, expected at most " +
                                     std::to_string(limits.max_file_bytes));
  }
  const auto depth_guard = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > limits.max_depth) {
      throw InputError(source, "", "nesting deeper than " + std::to_string(limits.max_depth) +
                                       " levels");
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, depth_guard);
  } catch (const nlohmann::json::parse_error& e) {
    // Report line and column rather than nlohmann's byte offset.
    const std::size_t offset = std::min<std::size_t>(e.byte, text.size());
    const std::size_t before = offset > 0 ? offset - 1 : 0;
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(before), '\n');
    const auto line_start = text.rfind('\n', before == 0 ? 0 : before - 1);
    const auto column = before - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
    std::string what = e.what();
    const auto colon = what.rfind(": ");
    throw InputError(source, "",
                     "invalid JSON at line " + std::to_string(line) + ", column " +
                         std::to_string(column) + ": " +
                         (colon == std::string::npos ? what : what.substr(colon + 2)));
  }
}

std::string read_text_file(const std::filesystem::path& path, const InputLimits& limits) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(name, "", "cannot read: not an existing regular file");
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > limits.max_file_bytes) {
    throw InputError(name, "", "file too large: " + std::to_string(size) +
                                   " bytes, expected at most " +
                                   std::to_string(limits.max_file_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name, "", "cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

nlohmann::json read_json_file(const std::filesystem::path& path, const InputLimits& limits) {
  return parse_json_text(read_text_file(path, limits), path.string(), limits);
}

std::string seed_expectation() {
  return "an integer seed in [0, " + std::to_string(std::numeric_limits<std::uint64_t>::max()) + "]";
}

std::uint64_t parse_seed(const std::string& text, const std::string& file, const std::string& where) {
  std::uint64_t seed = 0;
  const char* end = text.data() + text.size();
  // Digits only: no sign, no fraction, no exponent, no spaces; from_chars reports overflow.
  const auto [ptr, ec] = std::from_chars(text.data(), end, seed);
  const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits || ec != std::errc() || ptr != end) {
    throw InputError(file, where, "expected " + seed_expectation() + ", got \"" + text + "\"");
  }
  return seed;
}

std::string child_pointer(const std::string& parent, std::string_view key) {
  std::string out = parent + "/";
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string child_pointer(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (min_exclusive ? v <= min : v < min) return false;
  if (max_exclusive ? v >= max : v > max) return false;
  return true;
}

std::string Range::describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return "a number in " + std::string(min_exclusive ? "(" : "[") + format_number(min) + ", " +
           format_number(max) + (max_exclusive ? ")" : "]");
  }
  if (has_min) return "a number " + std::string(min_exclusive ? "> " : ">= ") + format_number(min);
  if (has_max) return "a number " + std::string(max_exclusive ? "< " : "<= ") + format_number(max);
  return "a finite number";
}

void JsonNode::fail(const std::string& expected) const {
  throw InputError(file_, pointer_, "expected " + expected + ", got " + describe_value(*value_));
}

double JsonNode::as_number(const Range& range) const {
  if (!value_->is_number()) fail(range.describe());
  const double v = value_->get<double>();
  if (!range.contains(v)) fail(range.describe());
  return v;
}

std::int64_t JsonNode::as_int(std::int64_t min, std::int64_t max) const {
  const std::string expected =
      "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (value_->is_number_unsigned()) {
    const auto u = value_->get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(max) || static_cast<std::int64_t>(u) < min) fail(expected);
    return static_cast<std::int64_t>(u);
  }
  if (!value_->is_number_integer()) fail(expected);
  const auto v = value_->get<std::int64_t>();
  if (v < min || v > max) fail(expected);
  return v;
}

std::uint64_t JsonNode::as_seed() const {
  // nlohmann reads integers exactly (as int64 or uint64); larger ones, fractions and exponents are doubles.
  if (value_->is_number_unsigned()) return value_->get<std::uint64_t>();
  if (value_->is_number_integer() && value_->get<std::int64_t>() >= 0) {
    return static_cast<std::uint64_t>(value_->get<std::int64_t>());
  }
  fail(seed_expectation());
}

bool JsonNode::as_bool() const {
  if (!value_->is_boolean()) fail("true or false");
  return value_->get<bool>();
}

std::string JsonNode::as_string() const {
  if (!value_->is_string() || value_->get_ref<const std::string&>().empty()) {
    fail("a non-empty string");
  }
  return value_->get<std::string>();
}

std::size_t JsonNode::as_choice(const std::vector<std::string_view>& choices) const {
  std::string expected = "one of";
  for (std::size_t i = 0; i < choices.size(); ++i) {
    expected += (i == 0 ? " \"" : ", \"") + std::string(choices[i]) + "\"";
  }
  if (!value_->is_string()) fail(expected);
  const auto& s = value_->get_ref<const std::string&>();
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (s == choices[i]) return i;
  }
  fail(expected);
}

std::vector<JsonNode> JsonNode::as_array(std::size_t min_size, std::size_t max_size) const {
  const std::string expected =
      min_size == max_size
          ? "an array of " + std::to_string(min_size) + " elements"
          : "an array of " + std::to_string(min_size) + " to " + std::to_string(max_size) +
                " elements";
  if (!value_->is_array() || value_->size() < min_size || value_->size() > max_size) {
    fail(expected);
  }
  std::vector<JsonNode> out;
  out.reserve(value_->size());
  for (std::size_t i = 0; i < value_->size(); ++i) {
    out.emplace_back((*value_)[i], file_, child_pointer(pointer_, i));
  }
  return out;
}

Eigen::Vector3d JsonNode::as_vector3(const Range& range) const {
  const auto items = as_array(3, 3);
  return {items[0].as_number(range), items[1].as_number(range), items[2].as_number(range)};
}

Eigen::Vector2d JsonNode::as_vector2(const Range& range) const {
  const auto items = as_array(2, 2);
  return {items[0].as_number(range), items[1].as_number(range)};
}

ObjectReader::ObjectReader(const JsonNode& node) : node_(node) {
  if (!node_.value().is_object()) node_.fail("an object");
}

bool ObjectReader::has(std::string_view key) const {
  return node_.value().contains(std::string(key));
}

JsonNode ObjectReader::required(std::string_view key) {
  accept(key);
  const auto it = node_.value().find(std::string(key));
  if (it == node_.value().end()) {
    throw InputError(node_.file(), node_.pointer(),
                     "missing required key \"" + std::string(key) + "\"");
  }
  return JsonNode(*it, node_.file(), child_pointer(node_.pointer(), key));
}

std::optional<JsonNode> ObjectReader::optional(std::string_view key) {
  accept(key);
  const auto it = node_.value().find(std::string(key));
  if (it == node_.value().end()) return std::nullopt;
  return JsonNode(*it, node_.file(), child_pointer(node_.pointer(), key));
}

void ObjectReader::read(std::string_view key, double& out, const Range& range) {
  if (auto v = optional(key)) out = v->as_number(range);
}

void ObjectReader::read(std::string_view key, int& out, std::int64_t min, std::int64_t max) {
  if (auto v = optional(key)) out = static_cast<int>(v->as_int(min, max));
}

void ObjectReader::read(std::string_view key, bool& out) {
  if (auto v = optional(key)) out = v->as_bool();
}

void ObjectReader::read(std::string_view key, std::string& out) {
  if (auto v = optional(key)) out = v->as_string();
}

void ObjectReader::read_seed(std::string_view key, std::uint64_t& out) {
  if (auto v = optional(key)) out = v->as_seed();
}

void ObjectReader::read(std::string_view key, Eigen::Vector3d& out, const Range& range) {
  if (auto v = optional(key)) out = v->as_vector3(range);
}

void ObjectReader::read(std::string_view key, Eigen::Vector2d& out, const Range& range) {
  if (auto v = optional(key)) out = v->as_vector2(range);
}

void ObjectReader::accept(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
}

void ObjectReader::finish() const {
  for (const auto& [key, value] : node_.value().items()) {
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::vector<std::string> allowed = known_;
    std::sort(allowed.begin(), allowed.end());
    std::string list;
    for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
    throw InputError(node_.file(), child_pointer(node_.pointer(), key),
                     "unknown key \"" + key + "\"; expected one of: " + list);
  }
}

}  // namespace campo
