#include "campo/record_fields.hpp"

#include <array>
#include <utility>

namespace campo {

namespace {

// One table for both directions (STYLE 10).
constexpr std::array<std::pair<RecordType, std::string_view>, 6> kTypeNames{{
    {RecordType::flag, "flag"},
    {RecordType::integer, "integer"},
    {RecordType::number, "number"},
    {RecordType::text, "text"},
    {RecordType::array, "array"},
    {RecordType::object, "object"},
}};

// A Markdown table cell: no line break, no column separator.
std::string one_line_cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += "\\|";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out;
}

}  // namespace

std::string_view to_string(RecordType type) {
  for (const auto& [t, name] : kTypeNames) {
    if (t == type) return name;
  }
  return "unknown";
}

bool has_record_type(const nlohmann::json& value, RecordType type) {
  switch (type) {
    case RecordType::flag: return value.is_boolean();
    case RecordType::integer: return value.is_number_integer();
    case RecordType::number: return value.is_number();
    case RecordType::text: return value.is_string();
    case RecordType::array: return value.is_array();
    case RecordType::object: return value.is_object();
  }
  return false;
}

const RecordFieldInfo* RecordFields::find(std::string_view name) const {
  for (const RecordFieldInfo& f : fields_) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

void RecordFields::add(const RecordFieldInfo& info, std::function<void(const JsonNode&)> read) {
  if (info.name.empty()) throw std::logic_error("RecordFields: a field without a name");
  if (find(info.name)) throw std::logic_error("RecordFields: field \"" + info.name + "\" declared twice");
  fields_.push_back(info);
  reads_.push_back(std::move(read));
}

void RecordFields::set(nlohmann::json& record, std::string_view name, nlohmann::json value, const std::string& file,
                       const std::string& pointer) const {
  const nlohmann::json one = {{std::string(name), value}};
  check(one, file, pointer);
  if (record.is_null()) record = nlohmann::json::object();
  record[std::string(name)] = std::move(value);
}

void RecordFields::check(const nlohmann::json& record, const std::string& file, const std::string& pointer) const {
  if (record.is_null()) return;
  if (!record.is_object()) JsonNode(record, file, pointer).fail("an object of declared fields");
  InputErrors errors;
  for (const auto& item : record.items()) {
    // Named, not a structured binding: clang (the fuzz build) cannot capture one in a lambda.
    const std::string& key = item.key();
    const nlohmann::json& value = item.value();
    const JsonNode node(value, file, child_pointer(pointer, key));
    errors.check([&] {
      const RecordFieldInfo* info = find(key);
      if (!info) {
        std::string declared;
        for (std::size_t i = 0; i < fields_.size(); ++i) declared += (i == 0 ? "" : ", ") + fields_[i].name;
        throw InputError(file, node.pointer(),
                         "expected a declared field (" +
                             (declared.empty() ? std::string("none is declared") : declared) + "), got \"" +
                             printable(key) + "\"");
      }
      if (!has_record_type(value, info->type)) {
        node.fail(std::string(to_string(info->type)) + " (" + info->meaning + ")");
      }
      reads_[static_cast<std::size_t>(info - fields_.data())](node);
    });
  }
  errors.throw_if_any();
}

std::string RecordFields::markdown() const {
  std::string out = "| field | type | unit | meaning |\n| --- | --- | --- | --- |\n";
  for (const RecordFieldInfo& f : fields_) {
    out += "| `" + one_line_cell(f.name) + "` | " + std::string(to_string(f.type)) + " | " + one_line_cell(f.unit) + " | " +
           one_line_cell(f.meaning) + " |\n";
  }
  return out;
}

}  // namespace campo
