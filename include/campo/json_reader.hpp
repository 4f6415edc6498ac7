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
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace campo {

/// `text` fit to quote in a one-line message: control characters (C0, DEL and
/// the C1 range) and bytes that are not UTF-8 become escapes (\n, \r,
/// \t, \x1b, \u0085); every other character, UTF-8 included, stays as it is.
std::string printable(std::string_view text);

/// One error in user input: which file, where in it and what was expected.
struct InputIssue {
  std::string file;
  std::string pointer;  ///< JSON pointer of the offending value, "" for the whole file
  std::string message;  ///< what was expected
  /// The objects along `pointer` named as the user named them ("forest/tree4"
  /// for /objects/0/children/4); empty when none has a name.
  std::string aliases;
  int line = 0;    ///< 1-based line of the value (of its key, for a member) in `file`; 0: unknown
  int column = 0;  ///< 1-based column (bytes), with `line`

  /// "file:line:column: /pointer (aliases): message", the parts that are known,
  /// passed through printable(); an empty `file` reads as `"" (empty path)`.
  std::string describe() const;
};

/// Bad user input: one error or several found at once (all of a scene or a
/// sweep spec, up to a bound). what() is one line per error (InputIssue::
/// describe) and, if more were found than are kept, a last line
/// "... and N more errors". file(), pointer() and message() are the first error's.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string pointer, const std::string& message);
  /// `issues` (at least one) of `total` errors found (total < issues.size(): as many as given).
  explicit InputError(std::vector<InputIssue> issues, std::size_t total = 0);
  const std::string& file() const { return issues_.front().file; }
  const std::string& pointer() const { return issues_.front().pointer; }
  /// What was expected, as given: the first error without the file and the pointer.
  const std::string& message() const { return issues_.front().message; }
  /// The errors kept, in the order they were found.
  const std::vector<InputIssue>& issues() const { return issues_; }
  /// The errors found, issues().size() of them kept.
  std::size_t count() const { return count_; }

 private:
  std::vector<InputIssue> issues_;
  std::size_t count_ = 1;
};

/// Collects the errors of one input so that all of them are reported at once:
/// the first `max_kept` are kept, the others only counted.
class InputErrors {
 public:
  static constexpr std::size_t kMaxKept = 20;
  explicit InputErrors(std::size_t max_kept = kMaxKept) : max_kept_(max_kept) {}

  /// Adds every error of `error`.
  void add(const InputError& error);
  /// Runs `check`; an InputError it throws is added, and then false is returned.
  template <class Check>
  bool check(Check&& check) {
    try {
      check();
      return true;
    } catch (const InputError& e) {
      add(e);
      return false;
    }
  }
  std::size_t count() const { return count_; }
  bool empty() const { return count_ == 0; }
  /// Throws one InputError holding every error added, if any.
  void throw_if_any() const;

 private:
  std::size_t max_kept_;
  std::vector<InputIssue> issues_;
  std::size_t count_ = 0;
};

/// 1-based line and column of the value at JSON `pointer` in the JSON `text`
/// (of its key, for an object member); nullopt if the text has no such value.
/// `text` must be valid JSON (as parse_json_text accepted it).
std::optional<std::pair<int, int>> locate_json_pointer(const std::string& text, const std::string& pointer);

/// `error` with the line and column of each of its errors in `file` whose
/// pointer is found in `text`, the content of `file`.
InputError with_locations(const InputError& error, const std::string& file, const std::string& text);

/// `error` with, for each of its errors in `file`, the names of the objects
/// along its pointer in `document`: an array element that is an object with a
/// string `name_key` ("alias") is named by it, e.g. "forest/tree4".
InputError with_aliases(const InputError& error, const std::string& file, const nlohmann::json& document,
                        std::string_view name_key = "alias");

/// The errors of `error` (another file's, read for this one) reported at
/// `pointer` of `file`, each as `prefix` followed by its own line
/// (InputIssue::describe), e.g. "cannot load the scene: scenes/a.json:4:7: ...".
InputError nested_error(const InputError& error, const std::string& file, const std::string& pointer,
                        const std::string& prefix);

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
///
/// Given an InputErrors, the reader goes on past errors: read() of a key with a
/// bad value adds the error and leaves `out` as it was, check() adds what its
/// callable throws, and finish() adds every unknown key; ok() then says whether
/// anything was added since the reader was made. Without one, the first error
/// is thrown (finish() throws every unknown key in one InputError).
class ObjectReader {
 public:
  explicit ObjectReader(const JsonNode& node, InputErrors* errors = nullptr);

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

  /// Runs `check`: with an InputErrors, an InputError it throws is added
  /// (false is returned); without, it is thrown.
  template <class Check>
  bool check(Check&& check) {
    if (!errors_) {
      check();
      return true;
    }
    return errors_->check(std::forward<Check>(check));
  }
  /// No error added to the reader's InputErrors since the reader was made (always true without one).
  bool ok() const { return !errors_ || errors_->count() == errors_at_start_; }
  /// The InputErrors given, or null: for the readers of nested objects.
  InputErrors* errors() const { return errors_; }

  const JsonNode& node() const { return node_; }
  [[noreturn]] void fail(const std::string& expected) const { node_.fail(expected); }

 private:
  JsonNode node_;
  std::vector<std::string> known_;
  InputErrors* errors_ = nullptr;
  std::size_t errors_at_start_ = 0;
};

}  // namespace campo
