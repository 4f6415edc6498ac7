#include "run/provenance.hpp"

#include <set>
#include <string>

#include "campo/version.hpp"

namespace campo {

std::string campo_version_string() {
  return "campo " + std::string(library_version()) + " (git " + std::string(library_git_revision()) + ")";
}

nlohmann::json provenance(const Scene& scene) {
  nlohmann::json record = {
      {"campo_version", library_version()},
      {"git_revision", library_git_revision()},
      {"scene", {{"name", scene.name}, {"file", scene.source_path}, {"sha256", scene.source_sha256}}},
      {"world_seed", scene.world.seed},
  };
  // The mesh files the scene read, each once: a run is the scene file and these.
  nlohmann::json meshes = nlohmann::json::array();
  std::set<std::string> seen;
  for (const Shape& shape : scene.shapes) {
    if (!shape.mesh || !seen.insert(shape.mesh->source_path).second) continue;
    meshes.push_back({{"file", shape.mesh->source_path}, {"sha256", shape.mesh->source_sha256}});
  }
  for (const Mover& mover : scene.movers) {
    if (!mover.shape.mesh || !seen.insert(mover.shape.mesh->source_path).second) continue;
    meshes.push_back({{"file", mover.shape.mesh->source_path}, {"sha256", mover.shape.mesh->source_sha256}});
  }
  if (!meshes.empty()) record["meshes"] = std::move(meshes);
  return record;
}

}  // namespace campo
