#pragma once
/// One declaration per configuration field. A ConfigFields<Config> lists the
/// fields of a config struct once, each with its JSON key, the member it sets,
/// the range it accepts, its unit and what it means; from that one list come
///   - strict reading of a JSON "params" block (unknown keys, wrong types and
///     values out of range are InputErrors naming the file and JSON pointer),
///   - writing the effective values (a planner's or vehicle's parameters(),
///     in the form the reader takes back),
///   - the Markdown table of the docs (markdown_table()).
/// The struct keeps its in-class defaults: the table's defaults are a
/// default-constructed struct's values. Planner plugins declare their
/// parameters the same way.
///
///   const ConfigFields<StraightConfig>& straight_config_fields() {
///     static const ConfigFields<StraightConfig> fields =
///         ConfigFields<StraightConfig>()
///             .number("speed_mps", &StraightConfig::speed_mps, Range::closed(0.01, 20.0), "m/s", "cruise speed")
///             .flag("horizontal", &StraightConfig::horizontal, "measure distance in x, y only");
///     return fields;
///   }
///
/// Fields are read in declaration order, so a bound may depend on fields
/// declared before it (DependentBound).
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "campo/json_reader.hpp"
#include "campo/params_block.hpp"

namespace campo {

/// One row of a configuration's table in the docs.
struct FieldDoc {
  std::string key;            ///< JSON key; the keys of a nested object as "object.key"
  std::string default_value;  ///< as written by ConfigFields::write (texts in backticks)
  std::string unit;           ///< empty for a dimensionless value
  std::string accepted;       ///< what the reader accepts, e.g. "[0.01, 20]", "> 0", "`square` or `disc`"
  std::string doc;            ///< what the field means (Markdown)
};

/// The Markdown table of `rows`: a header line | key | default | unit |
/// accepted | meaning |, its rule, then one line per row; every line ends in '\n'.
std::string markdown_table(const std::vector<FieldDoc>& rows);

/// A numeric range as the docs' tables state it: "[0.01, 20]", "(0.5, 1)",
/// "> 0", ">= 1", "<= 5", or "any" when unbounded.
std::string range_text(const Range& range);

/// A value as the docs' tables show it: numbers as JSON writes them, texts in
/// backticks ("none" for an empty one), arrays as "[0.3, 0.3, 0.06]".
std::string field_value_text(const nlohmann::json& value);

/// Inclusive bounds of an integer field.
struct IntRange {
  std::int64_t min = 0;
  std::int64_t max = 0;
};

/// Integer bounds as the docs' tables state them: "[1, 64]".
std::string range_text(const IntRange& range);

/// A bound computed from the values of the fields declared before this one
/// (they are read first), with how the docs state it, e.g. "[0, levels - 1]".
template <class Config, class Bound>
struct DependentBound {
  std::function<Bound(const Config&)> bound;
  std::string described;
  bool depends = true;  ///< false: the same bound whatever the other fields (ConfigFields::constant)
};

/// The declared fields of a config struct `Config` (default-constructible).
/// Declare with the chainable adders; the options omitted_when_default() and
/// only_when() apply to the field declared last, requirement() to the whole.
template <class Config>
class ConfigFields {
 public:
  /// A number in `range`; `unit` as the docs show it ("m/s", "" if none).
  ConfigFields& number(std::string key, double Config::*member, Range range, std::string unit, std::string doc) {
    return number(std::move(key), member, constant(range, range_text(range)), std::move(unit), std::move(doc));
  }
  ConfigFields& number(std::string key, double Config::*member, DependentBound<Config, Range> range,
                       std::string unit, std::string doc) {
    Field f = basic(key, member, std::move(unit), range.described, std::move(doc));
    f.read = [key, member, bound = range.bound, depends = range.depends](ObjectReader& r, Config& c) {
      if (depends && skip_dependent(r, key)) return;
      r.read(key, c.*member, bound(c));
    };
    return add(std::move(f));
  }

  /// An integer in `range`.
  ConfigFields& integer(std::string key, int Config::*member, IntRange range, std::string unit, std::string doc) {
    return integer(std::move(key), member, constant(range, range_text(range)), std::move(unit), std::move(doc));
  }
  ConfigFields& integer(std::string key, int Config::*member, DependentBound<Config, IntRange> range,
                        std::string unit, std::string doc) {
    Field f = basic(key, member, std::move(unit), range.described, std::move(doc));
    f.read = [key, member, bound = range.bound, depends = range.depends](ObjectReader& r, Config& c) {
      if (depends && skip_dependent(r, key)) return;
      const IntRange b = bound(c);
      r.read(key, c.*member, b.min, b.max);
    };
    return add(std::move(f));
  }

  /// true or false.
  ConfigFields& flag(std::string key, bool Config::*member, std::string doc) {
    Field f = basic(key, member, "", "true or false", std::move(doc));
    f.read = [key, member](ObjectReader& r, Config& c) { r.read(key, c.*member); };
    return add(std::move(f));
  }

  /// A non-empty string.
  ConfigFields& text(std::string key, std::string Config::*member, std::string doc) {
    Field f = basic(key, member, "", "a non-empty string", std::move(doc));
    f.read = [key, member](ObjectReader& r, Config& c) { r.read(key, c.*member); };
    return add(std::move(f));
  }

  /// A random seed: an integer in [0, 2^64 - 1], read exactly.
  ConfigFields& seed(std::string key, std::uint64_t Config::*member, std::string doc) {
    Field f = basic(key, member, "", "an integer in [0, 2^64 - 1]", std::move(doc));
    f.read = [key, member](ObjectReader& r, Config& c) { r.read_seed(key, c.*member); };
    return add(std::move(f));
  }

  /// An array of 3 (or 2) numbers, each in `range`.
  ConfigFields& vector(std::string key, Eigen::Vector3d Config::*member, Range range, std::string unit,
                       std::string doc) {
    return vector_field(std::move(key), member, range, std::move(unit), std::move(doc), "3");
  }
  ConfigFields& vector(std::string key, Eigen::Vector2d Config::*member, Range range, std::string unit,
                       std::string doc) {
    return vector_field(std::move(key), member, range, std::move(unit), std::move(doc), "2");
  }

  /// One of the names of `choices` (one table for both directions).
  template <class Enum>
  ConfigFields& choice(std::string key, Enum Config::*member, std::vector<std::pair<std::string, Enum>> choices,
                       std::string doc) {
    std::string accepted;
    for (std::size_t i = 0; i < choices.size(); ++i) {
      accepted += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + ("`" + choices[i].first + "`");
    }
    Field f;
    f.key = key;
    f.read = [key, member, choices](ObjectReader& r, Config& c) {
      if (const auto node = r.optional(key)) {
        std::vector<std::string_view> names;
        for (const auto& [name, value] : choices) names.emplace_back(name);
        c.*member = choices[node->as_choice(names)].second;
      }
    };
    f.write = [key, member, choices](const Config& c, nlohmann::json& j) {
      for (const auto& [name, value] : choices) {
        if (value == c.*member) {
          j[key] = name;
          return;
        }
      }
      throw std::logic_error("ConfigFields: field \"" + key + "\" holds a value without a name");
    };
    f.same = [member](const Config& a, const Config& b) { return a.*member == b.*member; };
    f.document = [key, accepted, doc, write = f.write](const Config& defaults, const std::string& prefix,
                                                       std::vector<FieldDoc>& rows) {
      nlohmann::json j = nlohmann::json::object();
      write(defaults, j);
      rows.push_back({prefix + key, default_text(j[key]), "", accepted, doc});
    };
    return add(std::move(f));
  }

  /// A nested object with the fields of `fields`; its table rows follow this
  /// field's, keyed "key.field".
  template <class Nested>
  ConfigFields& nested(std::string key, Nested Config::*member, const ConfigFields<Nested>& fields, std::string doc) {
    Field f;
    f.key = key;
    f.read = [key, member, fields](ObjectReader& r, Config& c) {
      if (const auto node = r.optional(key)) fields.read(*node, c.*member);
    };
    f.write = [key, member, fields](const Config& c, nlohmann::json& j) { j[key] = fields.write(c.*member); };
    f.same = [member, fields](const Config& a, const Config& b) {
      return fields.write(a.*member) == fields.write(b.*member);
    };
    f.document = [key, member, fields, doc](const Config& defaults, const std::string& prefix,
                                            std::vector<FieldDoc>& rows) {
      rows.push_back({prefix + key, "", "", "an object", doc});
      const std::vector<FieldDoc> inner = fields.docs(defaults.*member, prefix + key + ".");
      rows.insert(rows.end(), inner.begin(), inner.end());
    };
    return add(std::move(f));
  }

  /// An interval "[min, max]" with min <= max, both ends in `range`.
  ConfigFields& interval(std::string key, Eigen::Vector2d Config::*member, Range range, std::string unit,
                         std::string doc) {
    const std::string bounds = range_text(range);
    return custom(
        key, std::move(unit), "[min, max], min <= max" + (bounds == "any" ? std::string() : ", each " + bounds),
        std::move(doc),
        [member, range](const JsonNode& n, Config& c) {
          const Eigen::Vector2d v = n.as_vector2(range);
          if (v.x() > v.y()) n.fail("[min, max] with min <= max");
          c.*member = v;
        },
        [key, member](const Config& c, nlohmann::json& j) { j[key] = {(c.*member).x(), (c.*member).y()}; });
  }

  /// A field whose JSON value is not one member (e.g. "range_m": [min, max]
  /// sets two): `read` takes its node when present, `write` adds it to the
  /// object (or leaves it out); `accepted` says what the reader takes.
  ConfigFields& custom(std::string key, std::string unit, std::string accepted, std::string doc,
                       std::function<void(const JsonNode&, Config&)> read,
                       std::function<void(const Config&, nlohmann::json&)> write) {
    Field f;
    f.key = key;
    f.read = [key, read = std::move(read)](ObjectReader& r, Config& c) {
      if (const auto node = r.optional(key)) read(*node, c);
    };
    f.write = std::move(write);
    f.same = [write = f.write](const Config& a, const Config& b) {
      nlohmann::json ja = nlohmann::json::object(), jb = nlohmann::json::object();
      write(a, ja);
      write(b, jb);
      return ja == jb;
    };
    f.document = [key, unit = std::move(unit), accepted = std::move(accepted), doc = std::move(doc),
                  write = f.write](const Config& defaults, const std::string& prefix, std::vector<FieldDoc>& rows) {
      nlohmann::json j = nlohmann::json::object();
      write(defaults, j);
      rows.push_back({prefix + key, j.contains(key) ? default_text(j[key]) : "none", unit, accepted, doc});
    };
    return add(std::move(f));
  }

  /// The field declared last is written only when it differs from a
  /// default-constructed Config's (and read back as that default when absent).
  ConfigFields& omitted_when_default() {
    Field& f = last();
    f.write = [write = std::move(f.write), same = f.same](const Config& c, nlohmann::json& j) {
      if (!same(c, Config{})) write(c, j);
    };
    return *this;
  }

  /// The field declared last applies only when `applies` holds for the fields
  /// read before it: otherwise giving it is an InputError at its pointer
  /// saying `requirement`, and it is not written.
  ConfigFields& only_when(std::function<bool(const Config&)> applies, std::string requirement) {
    Field& f = last();
    f.read = [key = f.key, read = std::move(f.read), applies, requirement](ObjectReader& r, Config& c) {
      if (skip_dependent(r, key)) return;
      if (!applies(c) && r.has(key)) {
        const JsonNode node = *r.optional(key);
        throw InputError(node.file(), node.pointer(), requirement);
      }
      read(r, c);
    };
    f.write = [write = std::move(f.write), applies](const Config& c, nlohmann::json& j) {
      if (applies(c)) write(c, j);
    };
    return *this;
  }

  /// A requirement on the configuration as a whole, for a rule that no one
  /// field's reader can check: one that holds for one kind of configuration
  /// only, or whose values may come from another field (e.g. a preset). Once
  /// every field is read without error, the requirements are checked in
  /// declaration order and the first one `holds` rejects is an InputError at
  /// the object saying `requirement`.
  ConfigFields& requirement(std::function<bool(const Config&)> holds, std::string requirement) {
    requirements_.push_back({std::move(holds), std::move(requirement)});
    return *this;
  }

  /// Overwrites the fields of `config` given in the object at `node`; throws
  /// InputError for a key not declared, a wrong type or a value out of range:
  /// one InputError with every error of the object (each field checked on its
  /// own, then every unknown key), so that a params block's errors come at once.
  void read(const JsonNode& node, Config& config) const {
    InputErrors errors;
    ObjectReader r(node, &errors);
    read_fields(r, config);
    r.finish();
    errors.throw_if_any();
  }
  /// Reads the declared fields from an object whose other keys the caller
  /// reads itself (and then calls r.finish()), then checks the requirements.
  /// A reader given an InputErrors reads every field, each on its own
  /// (ObjectReader::check).
  void read_fields(ObjectReader& r, Config& config) const {
    for (const Field& f : fields_) r.check([&] { f.read(r, config); });
    if (!r.ok()) return;
    r.check([&] {
      for (const Requirement& q : requirements_) {
        if (!q.holds(config)) r.fail(q.requirement);
      }
    });
  }
  /// The same for a params block (its file and pointer name the errors).
  void read(const ParamsBlock& params, Config& config) const {
    read(JsonNode(params.values, params.file, params.pointer), config);
  }
  /// A default-constructed Config overridden by `params`.
  Config read(const ParamsBlock& params) const {
    Config config;
    read(params, config);
    return config;
  }

  /// Every field's value, in the form read() takes back.
  nlohmann::json write(const Config& config) const {
    nlohmann::json j = nlohmann::json::object();
    for (const Field& f : fields_) f.write(config, j);
    return j;
  }

  /// The docs' rows, defaults from `defaults`, keys prefixed by `prefix`.
  std::vector<FieldDoc> docs(const Config& defaults = Config{}, const std::string& prefix = "") const {
    std::vector<FieldDoc> rows;
    for (const Field& f : fields_) f.document(defaults, prefix, rows);
    return rows;
  }

  /// The docs' Markdown table (markdown_table of docs(defaults)).
  std::string markdown(const Config& defaults = Config{}) const { return markdown_table(docs(defaults)); }

  /// The declared keys, in declaration order.
  std::vector<std::string> keys() const {
    std::vector<std::string> out;
    for (const Field& f : fields_) out.push_back(f.key);
    return out;
  }

 private:
  struct Field {
    std::string key;
    std::function<void(ObjectReader&, Config&)> read;
    std::function<void(const Config&, nlohmann::json&)> write;
    std::function<bool(const Config&, const Config&)> same;  ///< the two hold the same value
    std::function<void(const Config&, const std::string&, std::vector<FieldDoc>&)> document;
  };

  struct Requirement {
    std::function<bool(const Config&)> holds;
    std::string requirement;
  };

  template <class Bound>
  static DependentBound<Config, Bound> constant(Bound bound, std::string described) {
    return {[bound](const Config&) { return bound; }, std::move(described), false};
  }

  // A field checked against the fields before it is not checked once one of
  // them (or anything else of the object) had an error: it would be checked
  // against a default the file did not give, and blame the wrong field.
  static bool skip_dependent(ObjectReader& r, const std::string& key) {
    if (r.ok()) return false;
    r.accept(key);
    return true;
  }

  static std::string default_text(const nlohmann::json& value) { return field_value_text(value); }

  // A field whose JSON value is the member itself (numbers, flags, texts, seeds); read set by the caller.
  template <class Value>
  static Field basic(const std::string& key, Value Config::*member, std::string unit, std::string accepted,
                     std::string doc) {
    Field f;
    f.key = key;
    f.write = [key, member](const Config& c, nlohmann::json& j) { j[key] = c.*member; };
    f.same = [member](const Config& a, const Config& b) { return a.*member == b.*member; };
    f.document = [key, member, unit = std::move(unit), accepted = std::move(accepted), doc = std::move(doc)](
                     const Config& defaults, const std::string& prefix, std::vector<FieldDoc>& rows) {
      const Value& value = defaults.*member;
      rows.push_back({prefix + key, default_text(nlohmann::json(value)), unit, accepted, doc});
    };
    return f;
  }

  template <class Vector>
  ConfigFields& vector_field(std::string key, Vector Config::*member, Range range, std::string unit,
                             std::string doc, const std::string& size) {
    Field f;
    f.key = key;
    f.read = [key, member, range](ObjectReader& r, Config& c) { r.read(key, c.*member, range); };
    f.write = [key, member](const Config& c, nlohmann::json& j) {
      const Vector& v = c.*member;
      j[key] = std::vector<double>(v.data(), v.data() + v.size());
    };
    f.same = [member](const Config& a, const Config& b) { return a.*member == b.*member; };
    const std::string bounds = range_text(range);
    const std::string accepted = size + " numbers" + (bounds == "any" ? "" : ", each " + bounds);
    f.document = [key, accepted, unit = std::move(unit), doc = std::move(doc), write = f.write](
                     const Config& defaults, const std::string& prefix, std::vector<FieldDoc>& rows) {
      nlohmann::json j = nlohmann::json::object();
      write(defaults, j);
      rows.push_back({prefix + key, default_text(j[key]), unit, accepted, doc});
    };
    return add(std::move(f));
  }

  ConfigFields& add(Field f) {
    for (const Field& g : fields_) {
      if (g.key == f.key) throw std::logic_error("ConfigFields: key \"" + f.key + "\" declared twice");
    }
    fields_.push_back(std::move(f));
    return *this;
  }

  Field& last() {
    if (fields_.empty()) throw std::logic_error("ConfigFields: an option before any field");
    return fields_.back();
  }

  std::vector<Field> fields_;
  std::vector<Requirement> requirements_;
};

}  // namespace campo
