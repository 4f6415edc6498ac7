// run.json's provenance names every file a run read: the scene and, for a scene
// with mesh objects, each mesh file once with its SHA-256 (checked against
// coreutils' sha256sum, a second implementation).
#include "run/provenance.hpp"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"

namespace campo {
namespace {

std::string sha256sum(const std::string& path) {
  std::FILE* pipe = popen(("sha256sum '" + path + "'").c_str(), "r");
  if (!pipe) return "";
  char digest[65] = {};
  const std::size_t read = std::fread(digest, 1, 64, pipe);
  pclose(pipe);
  return std::string(digest, read);
}

TEST(Provenance, ListsEachMeshFileOnceWithItsHash) {
  Scene scene = load_scene("scenes/mesh_buildings.json");
  // A second shape of the same file is listed once.
  scene.shapes.push_back(scene.shapes.back());
  const nlohmann::json record = provenance(scene);
  ASSERT_TRUE(record.contains("meshes"));
  const nlohmann::json& meshes = record.at("meshes");
  ASSERT_EQ(meshes.size(), 3u);
  for (const nlohmann::json& mesh : meshes) {
    const std::string file = mesh.at("file").get<std::string>();
    EXPECT_EQ(mesh.at("sha256").get<std::string>(), sha256sum(file)) << file;
  }
}

TEST(Provenance, ScenesWithoutMeshesHaveNoMeshList) {
  const Scene scene = load_scene("scenes/two_barriers.json");
  EXPECT_FALSE(provenance(scene).contains("meshes"));
  EXPECT_EQ(provenance(scene).at("scene").at("sha256").get<std::string>(), sha256sum(scene.source_path));
}

}  // namespace
}  // namespace campo
