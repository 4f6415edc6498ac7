#include "campo/json_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <fstream>
#include <iterator>
#include <tuple>
#include <unordered_map>
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

std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const auto continuation = [&](std::size_t i, unsigned char lo, unsigned char hi) {
    return i < text.size() && byte(i) >= lo && byte(i) <= hi;
  };
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    // The length of a well-formed UTF-8 sequence starting here (0: none), per
    // the Unicode table of well-formed byte sequences (no overlongs, no surrogates).
    std::size_t length = 0;
    if (c >= 0xc2 && c <= 0xdf) {
      length = continuation(i + 1, 0x80, 0xbf) ? 2 : 0;
    } else if (c >= 0xe0 && c <= 0xef) {
      const unsigned char lo = c == 0xe0 ? 0xa0 : 0x80, hi = c == 0xed ? 0x9f : 0xbf;
      length = continuation(i + 1, lo, hi) && continuation(i + 2, 0x80, 0xbf) ? 3 : 0;
    } else if (c >= 0xf0 && c <= 0xf4) {
      const unsigned char lo = c == 0xf0 ? 0x90 : 0x80, hi = c == 0xf4 ? 0x8f : 0xbf;
      length = continuation(i + 1, lo, hi) && continuation(i + 2, 0x80, 0xbf) && continuation(i + 3, 0x80, 0xbf) ? 4 : 0;
    }
    if (length == 2 && c == 0xc2 && byte(i + 1) <= 0x9f) {  // a C1 control character, U+0080..U+009F
      out += "\\u00";
      out += kHex[byte(i + 1) >> 4];
      out += kHex[byte(i + 1) & 0xf];
    } else if (length > 0) {
      out.append(text.substr(i, length));
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {  // another control character, DEL, or a byte that is not UTF-8
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    }
    i += std::max<std::size_t>(length, 1);
  }
  return out;
}

std::string InputIssue::describe() const {
  std::string out = file.empty() ? std::string("\"\" (empty path)") : file;
  if (line > 0) out += ":" + std::to_string(line) + ":" + std::to_string(column);
  out += ": ";
  if (!pointer.empty()) out += pointer + (aliases.empty() ? std::string() : " (" + aliases + ")") + ": ";
  return printable(out + message);
}

namespace {

std::string describe_all(const std::vector<InputIssue>& issues, std::size_t count) {
  if (issues.empty()) throw std::logic_error("InputError: no issue");
  std::string out;
  for (const InputIssue& issue : issues) {
    if (!out.empty()) out += '\n';
    out += issue.describe();
  }
  if (count > issues.size()) {
    const std::size_t more = count - issues.size();
    out += "\n... and " + std::to_string(more) + " more error" + (more == 1 ? "" : "s");
  }
  return out;
}

}  // namespace

InputError::InputError(std::string file, std::string pointer, const std::string& message)
    : InputError(std::vector<InputIssue>{InputIssue{std::move(file), std::move(pointer), message, "", 0, 0}}) {}

InputError::InputError(std::vector<InputIssue> issues, std::size_t total)
    : std::runtime_error(describe_all(issues, std::max(total, issues.size()))),
      issues_(std::move(issues)),
      count_(std::max(total, issues_.size())) {}

void InputErrors::add(const InputError& error) {
  for (const InputIssue& issue : error.issues()) {
    if (issues_.size() < max_kept_) issues_.push_back(issue);
  }
  count_ += error.count();
}

void InputErrors::throw_if_any() const {
  if (count_ > 0) throw InputError(issues_, count_);
}

namespace {

// A scanner of JSON text already accepted by the parser, for locating values by pointer.
class PointerScanner {
 public:
  explicit PointerScanner(const std::string& text) : text_(text) {}

  std::size_t skip_space(std::size_t p) const {
    while (p < text_.size() && (text_[p] == ' ' || text_[p] == '\t' || text_[p] == '\n' || text_[p] == '\r')) ++p;
    return p;
  }
  // Past the string starting at `p` (a quote).
  std::size_t skip_string(std::size_t p) const {
    for (++p; p < text_.size(); ++p) {
      if (text_[p] == '\\') ++p;
      else if (text_[p] == '"') return p + 1;
    }
    return p;
  }
  // Past the value starting at `p`.
  std::size_t skip_value(std::size_t p) const {
    if (p >= text_.size()) return p;
    if (text_[p] == '"') return skip_string(p);
    if (text_[p] == '{' || text_[p] == '[') {
      int depth = 0;
      while (p < text_.size()) {
        const char c = text_[p];
        if (c == '"') {
          p = skip_string(p);
          continue;
        }
        if (c == '{' || c == '[') ++depth;
        if (c == '}' || c == ']') {
          if (--depth == 0) return p + 1;
        }
        ++p;
      }
      return p;
    }
    while (p < text_.size() && std::string_view(",}] \t\r\n").find(text_[p]) == std::string_view::npos) ++p;
    return p;
  }
  // The text of the string starting at `p`, decoded.
  std::string string_at(std::size_t p) const {
    const std::size_t end = skip_string(p);
    const std::string_view raw(text_.data() + p + 1, end - p - 2);
    if (raw.find('\\') == std::string_view::npos) return std::string(raw);
    return nlohmann::json::parse(text_.substr(p, end - p)).get<std::string>();
  }

  // Offset of the value under `token` in the container at `p` (and of its key), or npos.
  std::pair<std::size_t, std::size_t> child(std::size_t p, const std::string& token) const {
    constexpr auto npos = std::string::npos;
    if (p >= text_.size()) return {npos, npos};
    if (text_[p] == '{') {
      p = skip_space(p + 1);
      while (p < text_.size() && text_[p] == '"') {
        const std::size_t key = p;
        const std::string name = string_at(p);
        p = skip_space(skip_string(p));
        p = skip_space(p + 1);  // the colon
        if (name == token) return {p, key};
        p = skip_space(skip_value(p));
        if (p < text_.size() && text_[p] == ',') p = skip_space(p + 1);
      }
      return {npos, npos};
    }
    if (text_[p] == '[') {
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
      if (token.empty() || ec != std::errc() || end != token.data() + token.size()) return {npos, npos};
      p = skip_space(p + 1);
      for (std::size_t i = 0; p < text_.size() && text_[p] != ']'; ++i) {
        if (i == index) return {p, p};
        p = skip_space(skip_value(p));
        if (p < text_.size() && text_[p] == ',') p = skip_space(p + 1);
      }
    }
    return {npos, npos};
  }

 private:
  const std::string& text_;
};

// The reference tokens of a JSON pointer, unescaped.
std::vector<std::string> pointer_tokens(const std::string& pointer) {
  std::vector<std::string> tokens;
  if (pointer.empty() || pointer.front() != '/') return tokens;
  std::size_t start = 1;
  while (true) {
    const std::size_t end = pointer.find('/', start);
    std::string token = pointer.substr(start, end == std::string::npos ? std::string::npos : end - start);
    std::string unescaped;
    for (std::size_t i = 0; i < token.size(); ++i) {
      if (token[i] == '~' && i + 1 < token.size() && (token[i + 1] == '0' || token[i + 1] == '1')) {
        unescaped += token[++i] == '0' ? '~' : '/';
      } else {
        unescaped += token[i];
      }
    }
    tokens.push_back(std::move(unescaped));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return tokens;
}

}  // namespace

std::optional<std::pair<int, int>> locate_json_pointer(const std::string& text, const std::string& pointer) {
  if (!pointer.empty() && pointer.front() != '/') return std::nullopt;
  const PointerScanner scanner(text);
  std::size_t value = scanner.skip_space(0);
  std::size_t at = value;
  for (const std::string& token : pointer_tokens(pointer)) {
    std::tie(value, at) = scanner.child(value, token);
    if (value == std::string::npos) return std::nullopt;
  }
  if (at >= text.size()) return std::nullopt;
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
  const auto line_start = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
  const auto column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return std::pair{static_cast<int>(line), static_cast<int>(column)};
}

InputError with_locations(const InputError& error, const std::string& file, const std::string& text) {
  std::vector<InputIssue> issues = error.issues();
  for (InputIssue& issue : issues) {
    // An error of the whole file (its syntax, its size) says where it is itself.
    if (issue.file != file || issue.line > 0 || issue.pointer.empty()) continue;
    try {
      if (const auto place = locate_json_pointer(text, issue.pointer)) std::tie(issue.line, issue.column) = *place;
    } catch (const std::exception&) {
      // Not the text the error was found in: the error stays without its place.
    }
  }
  return InputError(std::move(issues), error.count());
}

InputError nested_error(const InputError& error, const std::string& file, const std::string& pointer,
                        const std::string& prefix) {
  std::vector<InputIssue> issues;
  for (const InputIssue& issue : error.issues()) issues.push_back({file, pointer, prefix + issue.describe(), "", 0, 0});
  return InputError(std::move(issues), error.count());
}

InputError with_aliases(const InputError& error, const std::string& file, const nlohmann::json& document,
                        std::string_view name_key) {
  std::vector<InputIssue> issues = error.issues();
  for (InputIssue& issue : issues) {
    if (issue.file != file || !issue.aliases.empty()) continue;
    const nlohmann::json* value = &document;
    std::string names;
    for (const std::string& token : pointer_tokens(issue.pointer)) {
      if (value->is_object()) {
        const auto it = value->find(token);
        if (it == value->end()) break;
        value = &*it;
      } else if (value->is_array()) {
        std::size_t index = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
        if (token.empty() || ec != std::errc() || end != token.data() + token.size() || index >= value->size()) break;
        value = &(*value)[index];
        const auto name = value->is_object() ? value->find(std::string(name_key)) : value->end();
        // A name with a '/' (refused as an alias) would make the path ambiguous.
        if (value->is_object() && name != value->end() && name->is_string() &&
            name->get_ref<const std::string&>().find('/') == std::string::npos) {
          (names += names.empty() ? "" : "/") += name->get<std::string>();
        }
      } else {
        break;
      }
    }
    issue.aliases = names;
  }
  return InputError(std::move(issues), error.count());
}

namespace {

/// 1-based line and column of byte `offset` of `text`, for messages.
std::string line_column(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
  const auto line_start = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
  const auto column = offset - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// A character iterator that publishes how far the parser has read, so the
/// SAX handler can say where a key is (nlohmann gives positions only to errors).
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator(const char* at, const char** cursor) : at_(at), cursor_(cursor) {}
  reference operator*() const { return *at_; }
  TrackingIterator& operator++() {
    *cursor_ = ++at_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const TrackingIterator& other) const { return at_ == other.at_; }
  bool operator!=(const TrackingIterator& other) const { return at_ != other.at_; }

 private:
  const char* at_;
  const char** cursor_;
};

/// Builds the document like nlohmann's DOM parser, in linear time (its callback
/// parser rescans a whole array at the end of every element object), and
/// rejects what nlohmann accepts silently: duplicate keys (the last would win)
/// and NUL characters in strings (they would truncate paths and expressions).
/// Every refusal names the JSON pointer of the value being read.
class DocumentBuilder {
 public:
  DocumentBuilder(const std::string& text, const std::string& source, const InputLimits& limits,
                  const char** cursor)
      : text_(text), source_(source), limits_(limits), cursor_(cursor) {}

  nlohmann::json& document() { return document_; }

  bool null() { return add(nullptr); }
  bool boolean(bool v) { return add(v); }
  bool number_integer(std::int64_t v) { return add(v); }
  bool number_unsigned(std::uint64_t v) { return add(v); }
  bool number_float(double v, const std::string&) { return add(v); }
  bool string(std::string& v) {
    reject_nul(v, current_pointer());
    return add(std::move(v));
  }
  bool binary(nlohmann::json::binary_t&) { return false; }  // never produced by JSON text

  bool start_object(std::size_t) { return open(nlohmann::json::object()); }
  bool start_array(std::size_t) { return open(nlohmann::json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    Frame& frame = frames_.back();
    // The cursor is just past the key's closing quote; its opening quote is
    // the key's length further back (exact unless the key has escapes).
    const std::size_t end = offset();
    const std::size_t here = end >= k.size() + 2 ? end - k.size() - 2 : 0;
    const auto [first, inserted] = frame.key_offsets.emplace(k, here);
    if (!inserted) {
      throw InputError(source_, child_pointer(frame.pointer, k),
                       "duplicate key \"" + k + "\" at " + line_column(text_, here) + "; first at " +
                           line_column(text_, first->second) + " (expected each key once per object)");
    }
    reject_nul(k, frame.pointer);
    frame.key = k;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& token, const nlohmann::json::exception& e) {
    const std::size_t at = position > 0 ? position - 1 : 0;
    if (dynamic_cast<const nlohmann::json::out_of_range*>(&e) != nullptr) {
      // nlohmann reports a number beyond the range of a double this way, once
      // it has read the whole number (`position` is just past it).
      std::string shown = token.size() > 40 ? token.substr(0, 37) + "..." : token;
      const std::size_t start = position >= token.size() ? position - token.size() : 0;
      throw InputError(source_, current_pointer(),
                       "number out of range at " + line_column(text_, start) +
                           ": expected a finite number (magnitude below 1.8e308), got " + shown + " (" +
                           std::to_string(token.size()) + " characters)");
    }
    // Report line and column rather than nlohmann's byte offset.
    const std::string what = e.what();
    const auto colon = what.rfind(": ");
    throw InputError(source_, "",
                     "invalid JSON at " + line_column(text_, at) + ": " +
                         (colon == std::string::npos ? what : what.substr(colon + 2)));
  }

 private:
  struct Frame {
    nlohmann::json* value = nullptr;
    std::string pointer;  ///< of this array or object
    std::string key;      ///< the key being read (objects)
    std::unordered_map<std::string, std::size_t> key_offsets;
  };

  std::size_t offset() const { return static_cast<std::size_t>(*cursor_ - text_.data()); }

  /// Pointer of the value about to be added to the innermost open container.
  std::string current_pointer() const {
    if (frames_.empty()) return "";
    const Frame& top = frames_.back();
    return top.value->is_array() ? child_pointer(top.pointer, top.value->size())
                                 : child_pointer(top.pointer, top.key);
  }

  void reject_nul(const std::string& s, const std::string& pointer) const {
    if (s.find('\0') != std::string::npos) {
      throw InputError(source_, pointer, "expected text without NUL characters (\\u0000)");
    }
  }

  template <typename Value>
  nlohmann::json* insert(Value&& v) {
    if (frames_.empty()) {
      document_ = nlohmann::json(std::forward<Value>(v));
      return &document_;
    }
    Frame& top = frames_.back();
    if (top.value->is_array()) {
      top.value->emplace_back(std::forward<Value>(v));
      return &top.value->back();
    }
    nlohmann::json& slot = (*top.value)[top.key];
    slot = nlohmann::json(std::forward<Value>(v));
    return &slot;
  }

  template <typename Value>
  bool add(Value&& v) {
    insert(std::forward<Value>(v));
    return true;
  }

  bool open(nlohmann::json empty) {
    if (static_cast<int>(frames_.size()) >= limits_.max_depth) {
      throw InputError(source_, current_pointer(),
                       "nesting deeper than " + std::to_string(limits_.max_depth) + " levels");
    }
    std::string pointer = current_pointer();
    nlohmann::json* value = insert(std::move(empty));
    frames_.push_back(Frame{value, std::move(pointer), {}, {}});
    return true;
  }

  bool close() {
    frames_.pop_back();
    return true;
  }

  const std::string& text_;
  const std::string& source_;
  const InputLimits& limits_;
  const char** cursor_;
  nlohmann::json document_;
  std::vector<Frame> frames_;
};

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& source,
                               const InputLimits& limits) {
  if (text.size() > limits.max_file_bytes) {
    throw InputError(source, "", "file too large: " + std::to_string(text.size()) +
                                     " bytes, expected at most " +
                                     std::to_string(limits.max_file_bytes));
  }
  const char* cursor = text.data();
  DocumentBuilder builder(text, source, limits, &cursor);
  const TrackingIterator first(text.data(), &cursor);
  const TrackingIterator last(text.data() + text.size(), &cursor);
  nlohmann::json::sax_parse(first, last, &builder);
  return std::move(builder.document());
}

std::string read_text_file(const std::filesystem::path& path, const InputLimits& limits) {
  const std::string name = path.string();
  if (name.empty()) throw InputError(name, "", "expected the path of a file, got an empty string");
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec && status.type() != std::filesystem::file_type::not_found) {
    throw InputError(name, "", "cannot read: " + ec.message());  // e.g. a loop of symbolic links
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(name, "", std::string("cannot read: ") +
                                   (std::filesystem::exists(status) ? "not a regular file" : "not an existing regular file"));
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

ObjectReader::ObjectReader(const JsonNode& node, InputErrors* errors)
    : node_(node), errors_(errors), errors_at_start_(errors ? errors->count() : 0) {
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
  if (auto v = optional(key)) check([&] { out = v->as_number(range); });
}

void ObjectReader::read(std::string_view key, int& out, std::int64_t min, std::int64_t max) {
  if (auto v = optional(key)) check([&] { out = static_cast<int>(v->as_int(min, max)); });
}

void ObjectReader::read(std::string_view key, bool& out) {
  if (auto v = optional(key)) check([&] { out = v->as_bool(); });
}

void ObjectReader::read(std::string_view key, std::string& out) {
  if (auto v = optional(key)) check([&] { out = v->as_string(); });
}

void ObjectReader::read_seed(std::string_view key, std::uint64_t& out) {
  if (auto v = optional(key)) check([&] { out = v->as_seed(); });
}

void ObjectReader::read(std::string_view key, Eigen::Vector3d& out, const Range& range) {
  if (auto v = optional(key)) check([&] { out = v->as_vector3(range); });
}

void ObjectReader::read(std::string_view key, Eigen::Vector2d& out, const Range& range) {
  if (auto v = optional(key)) check([&] { out = v->as_vector2(range); });
}

void ObjectReader::accept(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
}

void ObjectReader::finish() const {
  std::vector<InputIssue> unknown;
  for (const auto& [key, value] : node_.value().items()) {
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::vector<std::string> allowed = known_;
    std::sort(allowed.begin(), allowed.end());
    std::string list;
    for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
    unknown.push_back({node_.file(), child_pointer(node_.pointer(), key),
                       "unknown key \"" + key + "\"; expected one of: " + list, "", 0, 0});
  }
  if (unknown.empty()) return;
  const InputError error(std::move(unknown));
  if (!errors_) throw error;
  errors_->add(error);
}

}  // namespace campo
