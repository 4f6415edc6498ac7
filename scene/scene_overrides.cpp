#include "scene/scene_overrides.hpp"

#include <algorithm>
#include <charconv>

#include "campo/json_reader.hpp"

namespace campo {

namespace {

[[noreturn]] void fail(const std::string& assignment, const std::string& message) {
  throw InputError("command line", "--set " + assignment, message);
}

// JSON pointer escapes (RFC 6901): "~1" is '/', "~0" is '~'; any other '~' is an error.
std::string unescape(const std::string& segment, const std::string& assignment, const std::string& walked) {
  std::string out;
  for (std::size_t i = 0; i < segment.size(); ++i) {
    if (segment[i] != '~') {
      out += segment[i];
    } else if (i + 1 < segment.size() && (segment[i + 1] == '0' || segment[i + 1] == '1')) {
      out += segment[i + 1] == '1' ? '/' : '~';
      ++i;
    } else {
      fail(assignment, "expected '~' followed by 0 or 1 (RFC 6901: \"~0\" is '~', \"~1\" is '/') in \"" + segment +
                           "\" at " + walked + "/" + segment);
    }
  }
  return out;
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// An array index as RFC 6901 writes it: "0", or digits without a leading zero.
bool is_index(const std::string& segment) { return all_digits(segment) && (segment.size() == 1 || segment[0] != '0'); }

}  // namespace

SceneOverride parse_override(const std::string& text) {
  SceneOverride o;
  o.text = text;
  const auto eq = text.find('=');
  if (eq == std::string::npos) return o;  // no PATH: refused when applied
  o.pointer = text.substr(0, eq);
  const std::string value = text.substr(eq + 1);
  o.value = nlohmann::json::parse(value, nullptr, false);
  if (o.value.is_discarded()) o.value = value;
  return o;
}

SceneOverride make_override(std::string pointer, nlohmann::json value) {
  std::string text = pointer + "=" + value.dump();
  return {std::move(pointer), std::move(value), std::move(text)};
}

std::vector<std::string> override_texts(const std::vector<SceneOverride>& overrides) {
  std::vector<std::string> texts;
  texts.reserve(overrides.size());
  for (const SceneOverride& o : overrides) texts.push_back(o.text);
  return texts;
}

std::string apply_override(nlohmann::json& document, const SceneOverride& override) {
  const std::string& assignment = override.text;
  const std::string& path = override.pointer;
  if (path.empty() || path[0] != '/') {
    fail(assignment, "expected PATH=VALUE with PATH a JSON pointer such as /world/seed");
  }

  nlohmann::json* node = &document;
  std::string walked;  // the pointer so far, as written
  std::string resolved;  // the same with array elements by index
  std::size_t start = 1;
  while (true) {
    const std::size_t slash = path.find('/', start);
    const std::string raw = path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    const std::string segment = unescape(raw, assignment, walked);
    const bool last = slash == std::string::npos;
    const std::string parent = walked.empty() ? std::string("/") : walked;
    walked += "/" + raw;
    std::string resolved_segment = raw;
    if (node->is_object()) {
      // Missing keys are created (objects on the way); validation judges them after.
      if (!node->contains(segment) && !last) (*node)[segment] = nlohmann::json::object();
      node = &(*node)[segment];
    } else if (node->is_array()) {
      const std::string expected = "expected an array index in [0, " + std::to_string(node->size()) +
                                   ") without leading zeros (RFC 6901) or the alias of an element of " + parent;
      std::size_t index = node->size();
      if (is_index(segment)) {
        const auto [ptr, ec] = std::from_chars(segment.data(), segment.data() + segment.size(), index);
        if (ec != std::errc() || index >= node->size()) {
          fail(assignment, "index " + segment + " out of range at " + walked + "; " + expected);
        }
      } else if (all_digits(segment)) {
        fail(assignment, expected + ", got \"" + segment + "\" (a leading zero) at " + walked);
      } else {
        // An alias names the array element whose "alias" is the segment.
        for (std::size_t i = 0; i < node->size(); ++i) {
          const auto& e = (*node)[i];
          if (e.is_object() && e.contains("alias") && e["alias"] == segment) index = i;
        }
        if (index == node->size()) {
          fail(assignment, "no element with alias \"" + segment + "\" at " + walked + "; " + expected);
        }
      }
      node = &(*node)[index];
      resolved_segment = std::to_string(index);
    } else {
      fail(assignment, "cannot descend into a " + std::string(node->type_name()) + " at " + walked);
    }
    resolved += "/" + resolved_segment;
    if (last) break;
    start = slash + 1;
  }
  *node = override.value;
  return resolved;
}

}  // namespace campo
