#pragma once
/// One declaration per recorded field. A component that records more than the
/// generic fields (a planner's own decisions, its metrics) declares each of
/// its fields once in a RecordFields, as ConfigFields declares parameters:
/// its JSON name, its type, its unit and what it means. Declaring returns a
/// typed handle, RecordField<T>, the one way to write the field into a record
/// (a JSON object) and to read it back; readers never spell the key. From the
/// same list come the check of a record read from a file (a key not declared,
/// or a value not of its declared type, is an InputError at its pointer) and
/// the docs' table (markdown()).
///
///   struct GapRecord {
///     RecordFields fields;
///     RecordField<int> gaps = fields.declare<int>("gaps", "", "how many gaps the scan had");
///   };
///   const GapRecord& gap_record() { static const GapRecord r; return r; }
///
///   gap_record().gaps.set(decisions.own, 3);                 // writes {"gaps": 3}
///   std::optional<int> n = gap_record().gaps.get(decisions.own);
#include <concepts>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/json_reader.hpp"

namespace campo {

/// What a field's JSON value is.
enum class RecordType {
  flag,     ///< true or false
  integer,  ///< a whole number
  number,   ///< any number (an integer too)
  text,     ///< a string
  array,    ///< a JSON array (its elements as the field's meaning says)
  object,   ///< a JSON object (its keys as the field's meaning says)
};
/// "flag", "integer", "number", "text", "array", "object".
std::string_view to_string(RecordType type);
/// Whether `value` is of `type` (an integer is a number too).
bool has_record_type(const nlohmann::json& value, RecordType type);

/// A declared field, as the docs show it.
struct RecordFieldInfo {
  std::string name;  ///< its key in the record
  RecordType type = RecordType::number;
  std::string unit;     ///< "m", "deg", ...; "" if none
  std::string meaning;  ///< one line

  bool operator==(const RecordFieldInfo&) const = default;
};

/// A typed handle to one declared field of a RecordFields (made only by
/// RecordFields::declare): writes the field into a record and reads it back.
template <class T>
class RecordField {
 public:
  using Write = std::function<nlohmann::json(const T&)>;
  /// Reads the value at `node`, already checked to be of the declared type;
  /// InputError (JsonNode::fail) when its content is not what the field holds.
  using Read = std::function<T(const JsonNode&)>;

  const RecordFieldInfo& info() const { return info_; }
  const std::string& name() const { return info_.name; }

  /// Writes `value` under the field's name into `record` (an object; null
  /// becomes one). std::logic_error when its JSON is not of the declared type:
  /// the declaration and its writer disagree.
  void set(nlohmann::json& record, const T& value) const {
    nlohmann::json j = write_(value);
    if (!has_record_type(j, info_.type)) {
      throw std::logic_error("record field \"" + info_.name + "\" is declared " + std::string(to_string(info_.type)) +
                             " but was written as " + j.dump());
    }
    if (record.is_null()) record = nlohmann::json::object();
    record[info_.name] = std::move(j);
  }
  /// The field's value in `record`, nullopt when absent (or `record` is null).
  /// InputError naming `file` and the value's pointer (under `pointer`, that of
  /// the record) when it is not of the declared type or not what the field holds.
  std::optional<T> get(const nlohmann::json& record, const std::string& file = "",
                       const std::string& pointer = "") const {
    if (!record.is_object()) return std::nullopt;
    const auto it = record.find(info_.name);
    if (it == record.end()) return std::nullopt;
    const JsonNode node(*it, file, child_pointer(pointer, info_.name));
    if (!has_record_type(*it, info_.type)) node.fail(expected());
    return read_(node);
  }
  /// Whether `record` holds the field.
  bool in(const nlohmann::json& record) const { return record.is_object() && record.contains(info_.name); }
  /// Takes the field out of `record`.
  void erase(nlohmann::json& record) const {
    if (record.is_object()) record.erase(info_.name);
  }

 private:
  friend class RecordFields;
  RecordField(RecordFieldInfo info, Write write, Read read)
      : info_(std::move(info)), write_(std::move(write)), read_(std::move(read)) {}
  std::string expected() const { return std::string(to_string(info_.type)) + " (" + info_.meaning + ")"; }

  RecordFieldInfo info_;
  Write write_;
  Read read_;
};

/// The declared fields of one record (a planner's decisions, or its metrics),
/// in declaration order.
class RecordFields {
 public:
  /// Declares a field of a plain type: bool (flag), an integer type
  /// (integer), a floating-point type (number) or std::string (text).
  template <class T>
    requires std::same_as<T, bool> || std::integral<T> || std::floating_point<T> || std::same_as<T, std::string>
  RecordField<T> declare(std::string name, std::string unit, std::string meaning) {
    RecordType type = std::same_as<T, bool>      ? RecordType::flag
                      : std::integral<T>         ? RecordType::integer
                      : std::floating_point<T>   ? RecordType::number
                                                 : RecordType::text;
    return declare<T>({std::move(name), type, std::move(unit), std::move(meaning)},
                      [](const T& v) { return nlohmann::json(v); },
                      [](const JsonNode& n) { return n.value().template get<T>(); });
  }
  /// Declares a field whose value `write` turns into JSON of `info.type` and
  /// `read` reads back (InputError through JsonNode::fail when malformed).
  template <class T>
  RecordField<T> declare(RecordFieldInfo info, typename RecordField<T>::Write write,
                         typename RecordField<T>::Read read) {
    add(info, [read](const JsonNode& n) { read(n); });
    return RecordField<T>(std::move(info), std::move(write), std::move(read));
  }

  /// Declares a field whose value is JSON of `info.type`, written and read as
  /// it is (its structure as `info.meaning` says).
  RecordField<nlohmann::json> declare_json(RecordFieldInfo info) {
    return declare<nlohmann::json>(
        std::move(info), [](const nlohmann::json& v) { return v; }, [](const JsonNode& n) { return n.value(); });
  }

  const std::vector<RecordFieldInfo>& fields() const { return fields_; }
  /// The field named `name`, or null.
  const RecordFieldInfo* find(std::string_view name) const;
  bool empty() const { return fields_.empty(); }

  /// Writes the JSON `value` under the declared field `name` into `record`
  /// (for writers that hold JSON already, e.g. a Python planner's dict).
  /// InputError at `file` and `pointer` when `name` is not declared, or the
  /// value is not of its type or not what the field holds.
  void set(nlohmann::json& record, std::string_view name, nlohmann::json value, const std::string& file,
           const std::string& pointer) const;

  /// Checks a record read back: InputError, with every problem at once, when
  /// it is not an object (null is none), a key is not declared, or a value is
  /// not of its field's type or not what the field holds. `pointer` is the
  /// record's; each problem is at its key's pointer under it.
  void check(const nlohmann::json& record, const std::string& file, const std::string& pointer) const;

  /// The docs' Markdown table: field, type, unit, meaning.
  std::string markdown() const;

 private:
  void add(const RecordFieldInfo& info, std::function<void(const JsonNode&)> read);

  std::vector<RecordFieldInfo> fields_;
  std::vector<std::function<void(const JsonNode&)>> reads_;  ///< each field's reader, to check a value
};

}  // namespace campo
