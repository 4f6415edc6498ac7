#include "campo/config_fields.hpp"

#include <cmath>
#include <sstream>

namespace campo {

namespace {

// As Range::describe() writes bounds, so the docs and the error messages agree.
std::string format_bound(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A table cell: a '|' would end the cell early.
std::string escape_pipes(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string range_text(const Range& range) {
  const bool has_min = std::isfinite(range.min);
  const bool has_max = std::isfinite(range.max);
  if (has_min && has_max) {
    return std::string(range.min_exclusive ? "(" : "[") + format_bound(range.min) + ", " + format_bound(range.max) +
           (range.max_exclusive ? ")" : "]");
  }
  if (has_min) return std::string(range.min_exclusive ? "> " : ">= ") + format_bound(range.min);
  if (has_max) return std::string(range.max_exclusive ? "< " : "<= ") + format_bound(range.max);
  return "any";
}

std::string range_text(const IntRange& range) {
  std::string out = "[";
  out += std::to_string(range.min);
  out += ", ";
  out += std::to_string(range.max);
  out += "]";
  return out;
}

std::string field_value_text(const nlohmann::json& value) {
  if (value.is_string()) {
    const auto& s = value.get_ref<const std::string&>();
    return s.empty() ? "none" : "`" + s + "`";
  }
  if (value.is_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < value.size(); ++i) out += (i == 0 ? "" : ", ") + field_value_text(value[i]);
    return out + "]";
  }
  return value.dump();
}

std::string markdown_table(const std::vector<FieldDoc>& rows) {
  std::string out = "| key | default | unit | accepted | meaning |\n| --- | --- | --- | --- | --- |\n";
  for (const FieldDoc& row : rows) {
    out += "| `" + escape_pipes(row.key) + "` | " + escape_pipes(row.default_value) + " | " + escape_pipes(row.unit) + " | " +
           escape_pipes(row.accepted) + " | " + escape_pipes(row.doc) + " |\n";
  }
  return out;
}

}  // namespace campo
