#pragma once
/// Provenance block stamped into every output: what produced it, from what.
#include <nlohmann/json.hpp>

#include "campo/scene.hpp"

namespace campo {

/// "campo x.y.z (git abcdef123456)".
std::string campo_version_string();

/// {campo_version, git_revision, scene: {name, file, sha256}, world_seed}.
/// Holds no wall-clock time, so identical runs give identical files.
nlohmann::json provenance(const Scene& scene);

}  // namespace campo
