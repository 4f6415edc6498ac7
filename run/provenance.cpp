#include "run/provenance.hpp"

#include "campo/version.hpp"

namespace campo {

std::string campo_version_string() {
  return "campo " + std::string(library_version()) + " (git " + std::string(library_git_revision()) + ")";
}

nlohmann::json provenance(const Scene& scene) {
  return {
      {"campo_version", library_version()},
      {"git_revision", library_git_revision()},
      {"scene", {{"name", scene.name}, {"file", scene.source_path}, {"sha256", scene.source_sha256}}},
      {"world_seed", scene.world.seed},
  };
}

}  // namespace campo
