#include "scene/scene_overrides.hpp"

#include <charconv>

#include "campo/json_reader.hpp"

namespace campo {

namespace {

[[noreturn]] void fail(const std::string& assignment, const std::string& message) {
  throw InputError("command line", "--set " + assignment, message);
}

// JSON pointer escapes: "~1" is '/', "~0" is '~'.
std::string unescape(const std::string& segment) {
  std::string out;
  for (std::size_t i = 0; i < segment.size(); ++i) {
    if (segment[i] == '~' && i + 1 < segment.size()) {
      out += segment[i + 1] == '1' ? '/' : '~';
      ++i;
    } else {
      out += segment[i];
    }
  }
  return out;
}

}  // namespace

void apply_override(nlohmann::json& document, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0 || assignment[0] != '/') {
    fail(assignment, "expected PATH=VALUE with PATH a JSON pointer such as /world/seed");
  }
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;

  nlohmann::json* node = &document;
  std::string walked;
  std::size_t start = 1;
  while (true) {
    const std::size_t slash = path.find('/', start);
    const std::string segment = unescape(path.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    const bool last = slash == std::string::npos;
    walked += "/" + segment;
    if (node->is_object()) {
      // Missing keys are created (objects on the way); validation judges them after.
      if (!node->contains(segment) && !last) (*node)[segment] = nlohmann::json::object();
      node = &(*node)[segment];
    } else if (node->is_array()) {
      std::size_t index = 0;
      const auto [ptr, ec] = std::from_chars(segment.data(), segment.data() + segment.size(), index);
      if (ec == std::errc() && ptr == segment.data() + segment.size()) {
        if (index >= node->size()) fail(assignment, "index " + segment + " out of range at " + walked);
      } else {
        // An alias names the array element whose "alias" is the segment.
        index = node->size();
        for (std::size_t i = 0; i < node->size(); ++i) {
          const auto& e = (*node)[i];
          if (e.is_object() && e.contains("alias") && e["alias"] == segment) index = i;
        }
        if (index == node->size()) fail(assignment, "no element with alias \"" + segment + "\" at " + walked);
      }
      node = &(*node)[index];
    } else {
      fail(assignment, "cannot descend into a " + std::string(node->type_name()) + " at " + walked);
    }
    if (last) break;
    start = slash + 1;
  }
  *node = std::move(value);
}

}  // namespace campo
