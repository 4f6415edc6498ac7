#include "run/provenance.hpp"

namespace campo {

std::string campo_version_string() {
  return std::string("campo ") + CAMPO_VERSION + " (git " + CAMPO_GIT_REV + ")";
}

nlohmann::json provenance(const Scene& scene) {
  return {
      {"campo_version", CAMPO_VERSION},
      {"git_revision", CAMPO_GIT_REV},
      {"scene", {{"name", scene.name}, {"file", scene.source_path}, {"sha256", scene.source_sha256}}},
      {"world_seed", scene.world.seed},
  };
}

}  // namespace campo
