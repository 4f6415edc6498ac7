#pragma once
/// `--set PATH=VALUE` overrides of a scene document before validation.
#include <string>

#include <nlohmann/json.hpp>

namespace campo {

/// Applies one "PATH=VALUE" assignment to a scene document. PATH is a JSON
/// pointer ("/world/seed", "/objects/3/size_m/1"); inside an array of
/// objects a segment may also be an alias ("/objects/drone/planner/params/speed_mps").
/// Array indices and escapes are RFC 6901's: "0" or digits without a leading
/// zero ("04" is refused, "+4" or "-" name an alias), "~0" and "~1" only.
/// Missing object keys are created on the way (validation judges them
/// afterwards, like anything in the file). VALUE is JSON
/// ("0.8", "[1,2,3]", "true", "\"text\""); anything that does not parse as
/// JSON is taken as a string. Errors are InputErrors naming "--set".
/// Returns the pointer assigned, array elements by index (an alias resolved
/// to the index it named then), segments escaped as written.
std::string apply_override(nlohmann::json& document, const std::string& assignment);

/// The VALUE of a "PATH=VALUE" assignment, read as apply_override reads it.
nlohmann::json override_value(const std::string& assignment);

}  // namespace campo
