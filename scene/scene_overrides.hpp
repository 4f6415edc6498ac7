#pragma once
/// `--set PATH=VALUE` overrides of a scene document before validation.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace campo {

/// One override of a scene field, read once where its text comes from (the
/// command line's --set, a sweep spec, Python's dict). `text` is what
/// run.json, the sweep's manifest and results record: "POINTER=JSON".
struct SceneOverride {
  /// JSON pointer, aliases allowed; empty when the text has no "PATH=" (refused when applied).
  std::string pointer;
  nlohmann::json value;
  std::string text;  ///< "PATH=VALUE" as given, or as make_override writes it
};

/// A "PATH=VALUE" assignment read: PATH before the first '=', VALUE after it
/// as JSON ("0.8", "[1,2,3]", "true", "\"text\""); a VALUE that does not parse
/// as JSON is taken as a string. Never throws: an assignment that is not
/// PATH=VALUE is refused by apply_override, among the run's other errors.
SceneOverride parse_override(const std::string& text);

/// An override given as pointer and value apart: its text is POINTER=JSON (the value dumped).
SceneOverride make_override(std::string pointer, nlohmann::json value);

/// The texts of `overrides`, in order (what run.json and results record).
std::vector<std::string> override_texts(const std::vector<SceneOverride>& overrides);

/// Applies one override to a scene document. PATH is a JSON
/// pointer ("/world/seed", "/objects/3/size_m/1"); inside an array of
/// objects a segment may also be an alias ("/objects/drone/planner/params/speed_mps").
/// Array indices and escapes are RFC 6901's: "0" or digits without a leading
/// zero ("04" is refused, "+4" or "-" name an alias), "~0" and "~1" only.
/// Missing object keys are created on the way (validation judges them
/// afterwards, like anything in the file). Errors are InputErrors naming
/// "--set " and the override's text. Returns the pointer assigned, array
/// elements by index (an alias resolved to the index it named then), segments
/// escaped as written.
std::string apply_override(nlohmann::json& document, const SceneOverride& override);

}  // namespace campo
