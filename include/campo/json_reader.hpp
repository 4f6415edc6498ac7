#pragma once
/// Strict reading of JSON input files. Every error names the file, the JSON
/// pointer of the offending value and what was expected; unknown keys are
/// errors. All user-input parsing in campo goes through this reader.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace campo {

/// `text` fit to quote in a one-line message: control characters (C0, DEL and
/// the C1 range) and bytes that are not UTF-8 become escapes (\n, \r,
/// \t, \x1b, \u0085); every other character, UTF-8 included, stays as it is.
std::string printable(std::string_view text);

/// Bad user input: which file, where in it (JSON pointer, "" for the whole
/// file) and what was expected. what() is the full one-line message, passed
/// through printable(); an empty `file` reads as `"" (empty path)`.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string pointer, const std::string& message);
  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  /// What was expected, as given: what() without the file and the pointer.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::string pointer_;
  std::string message_;
};

/// Limits that stop hostile input from exhausting memory or time.
struct InputLimits {
  std::uintmax_t max_file_bytes = 16u << 20;  ///< bytes of one JSON file
  int max_depth = 32;                          ///< nesting of JSON arrays/objects
};

/// Reads a whole file, refusing files over the size limit before reading them.
std::string read_text_file(const std::filesystem::path& path, const InputLimits& limits = {});
/// Reads and parses a JSON file; syntax errors report line and column.
nlohmann::json read_json_file(const std::filesystem::path& path, const InputLimits& limits = {});
/// Parses JSON text; `source` names it in errors.
nlohmann::json parse_json_text(const std::string& text, const std::string& source,
                               const InputLimits& limits = {});

/// What a seed must be, for messages: "an integer seed in [0, 18446744073709551615]".
std::string seed_expectation();
/// A seed given as text (a command-line option): decimal digits only, in
/// [0, 2^64-1]; otherwise an InputError naming `file` and `where`.
std::uint64_t parse_seed(const std::string& text, const std::string& file, const std::string& where);

/// JSON pointer of `parent` extended by an object key or array index.
std::string child_pointer(const std::string& parent, std::string_view key);
std::string child_pointer(const std::string& parent, std::size_t index);

/// A closed or open numeric interval for validation messages.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  bool contains(double v) const;
  std::string describe() const;  ///< e.g. "a number > 0", "a number in [0, 1]"
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0}; }
  static Range closed(double lo, double hi) { return {lo, hi}; }
};

/// A view of one JSON value in one file, with its pointer.
class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string file, std::string pointer)
      : value_(&value), file_(std::move(file)), pointer_(std::move(pointer)) {}

  const nlohmann::json& value() const { return *value_; }
  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }

  [[noreturn]] void fail(const std::string& expected) const;

  double as_number(const Range& range = {}) const;
  std::int64_t as_int(std::int64_t min, std::int64_t max) const;
  /// A seed: a JSON integer (no fraction or exponent) in [0, 2^64-1], read exactly.
  std::uint64_t as_seed() const;
  bool as_bool() const;
  std::string as_string() const;  ///< a non-empty string
  /// One of `choices`; returns its index.
  std::size_t as_choice(const std::vector<std::string_view>& choices) const;
  Eigen::Vector3d as_vector3(const Range& range = {}) const;
  Eigen::Vector2d as_vector2(const Range& range = {}) const;
  /// An array of `min_size`..`max_size` elements.
  std::vector<JsonNode> as_array(std::size_t min_size, std::size_t max_size) const;

 private:
  const nlohmann::json* value_;
  std::string file_;
  std::string pointer_;
};

/// Strict reader of one JSON object: read keys with their defaults, then
/// finish(), which rejects any key that was not read.
class ObjectReader {
 public:
  explicit ObjectReader(const JsonNode& node);

  bool has(std::string_view key) const;
  /// The value under `key`; throws if missing. Marks the key as known.
  JsonNode required(std::string_view key);
  /// The value under `key` if present. Marks the key as known.
  std::optional<JsonNode> optional(std::string_view key);

  // Overwrite `out` if the key is present (the struct keeps its default otherwise).
  void read(std::string_view key, double& out, const Range& range = {});
  void read(std::string_view key, int& out, std::int64_t min, std::int64_t max);
  void read(std::string_view key, bool& out);
  void read(std::string_view key, std::string& out);
  void read_seed(std::string_view key, std::uint64_t& out);
  void read(std::string_view key, Eigen::Vector3d& out, const Range& range = {});
  void read(std::string_view key, Eigen::Vector2d& out, const Range& range = {});

  /// Marks keys as known without reading them (handled elsewhere).
  void accept(std::string_view key);
  /// Rejects unknown keys, naming the allowed ones.
  void finish() const;

  const JsonNode& node() const { return node_; }
  [[noreturn]] void fail(const std::string& expected) const { node_.fail(expected); }

 private:
  JsonNode node_;
  std::vector<std::string> known_;
};

}  // namespace campo
