/// Hostile mesh files through the `campo` program, as a user would meet them:
/// each scene names one bad mesh; `campo validate` and `campo run` end within
/// the time and memory limits of the hostile corpus (hostile_test.cpp) with
/// exit 2 and an error naming the scene file, the mesh object's "file"
/// pointer and what was wrong, or (an open mesh) with exit 0.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "tests/cli_support.hpp"
#include "tests/hostile/hostile_support.hpp"
#include "tests/mesh_file_writers.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using hostile::Outcome;

class HostileMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_hostile_mesh_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Outcome campo(const std::string& args) const { return hostile::run_campo(args, dir_); }

  // A scene with a ground, the mesh `file` as object 1 and a drone; returns its path.
  fs::path scene_with(const std::string& file) const {
    const fs::path scene = dir_ / "scene.json";
    test_support::write_file(scene, R"({"campo_scene": 1, "world": {"time_limit_s": 1}, "objects": [
      {"alias": "ground", "type": "plane"},
      {"alias": "building", "type": "mesh", "file": ")" + file + R"(", "pose": {"position_m": [5, 0, 0]}},
      {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]}, "planner": {"name": "straight"},
       "mission": {"waypoints": [{"position_m": [2, 0, 1.5]}]}}]})");
    return scene;
  }

  // validate and run both refuse the scene naming the file, the pointer and `why`.
  void expect_refused(const std::string& mesh_name, const std::string& why) const {
    const fs::path scene = scene_with(mesh_name);
    for (const std::string command : {"validate", "run"}) {
      const std::string out = command == "run" ? " --out '" + (dir_ / "out").string() + "'" : "";
      const Outcome o = campo(command + " '" + scene.string() + "'" + out);
      SCOPED_TRACE(command + " " + mesh_name);
      EXPECT_EQ(o.exit_code, 2) << o.err;
      EXPECT_THAT(o.err, HasSubstr("error: "));
      EXPECT_THAT(o.err, HasSubstr(scene.string()));
      EXPECT_THAT(o.err, HasSubstr("/objects/1/file"));
      EXPECT_THAT(o.err, HasSubstr(why));
      EXPECT_FALSE(fs::exists(dir_ / "out"));
    }
  }
  void write(const std::string& name, const std::string& bytes) const { test_support::write_file(dir_ / name, bytes); }

  fs::path dir_;
};

TEST_F(HostileMesh, AHeaderClaimingFiftyMillionTrianglesIsRefusedFromTheHeader) {
  // 84 + 3 x 50 bytes, a header that claims 50,000,000 triangles (2.5 GB of records).
  write("claims.stl", test_support::stl_binary_bytes(test_support::box_mesh(), 50'000'000).substr(0, 84 + 150));
  expect_refused("claims.stl", "declares 50000000 triangles, more than the limit of 2000000");
}

TEST_F(HostileMesh, MillionsOfFacesAreCountedBeforeParsing) {
  // 2.1 million faces over three vertices (17 MB): refused by the count of "f" lines, before assimp.
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  obj.reserve(obj.size() + 2'100'000 * 8);
  for (int i = 0; i < 2'100'000; ++i) obj += "f 1 2 3\n";
  write("many.obj", obj);
  expect_refused("many.obj", "more than the limit of 2000000");
}

TEST_F(HostileMesh, NotANumberDegenerateTruncatedAndEmptyFiles) {
  test_support::SimpleMesh nan = test_support::box_mesh();
  nan.vertices[5].y() = std::nan("");
  write("nan.stl", test_support::stl_binary_bytes(nan));
  expect_refused("nan.stl", "not a number or infinite");

  test_support::SimpleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  flat.triangles = {{0, 1, 2}, {2, 1, 0}, {0, 0, 1}};
  write("flat.obj", test_support::obj_text(flat));
  expect_refused("flat.obj", "zero area");

  write("short.stl", test_support::stl_binary_bytes(test_support::box_mesh(), 12).substr(0, 84 + 50 * 7 + 13));
  expect_refused("short.stl", "truncated binary STL");
  const std::string glb = test_support::gltf_bytes(test_support::box_mesh(), true);
  write("short.glb", glb.substr(0, glb.size() / 2));
  expect_refused("short.glb", "complete GLB");
  const std::string ply = test_support::ply_binary_bytes(test_support::cylinder_mesh(1, 1, 64));
  write("short.ply", ply.substr(0, ply.size() - 100));
  expect_refused("short.ply", "assimp");
  write("empty.stl", "");
  expect_refused("empty.stl", "is empty");
  fs::create_directories(dir_ / "folder.obj");
  expect_refused("folder.obj", "folder.obj");
  write("garbage.ply", std::string("ply\nformat ascii 1.0\nelement vertex 3\n") + std::string(5000, '\x01'));
  expect_refused("garbage.ply", "end_header");
}

TEST_F(HostileMesh, ADeepOrCyclicNodeGraphIsRefused) {
  std::string nodes = "[";
  for (int i = 0; i < 400; ++i) {
    nodes += std::string(i ? ", " : "") + R"({"mesh": 0)" + (i + 1 < 400 ? R"(, "children": [)" + std::to_string(i + 1) + "]" : "") + "}";
  }
  nodes += "]";
  write("deep.gltf", test_support::gltf_bytes(test_support::box_mesh(), false, nodes));
  expect_refused("deep.gltf", "nest at most 256 deep");
}

TEST_F(HostileMesh, AnOpenMeshIsAccepted) {
  test_support::SimpleMesh wall = test_support::box_mesh({0.2, 4, 3});
  wall.triangles.resize(2);  // one face: a single open surface
  write("wall.stl", test_support::stl_ascii_text(wall));
  const fs::path scene = scene_with("wall.stl");
  const Outcome validate = campo("validate '" + scene.string() + "'");
  EXPECT_EQ(validate.exit_code, 0) << validate.err;
  const Outcome run = campo("run '" + scene.string() + "' --out '" + (dir_ / "out").string() + "'");
  EXPECT_EQ(run.exit_code == 0 || run.exit_code == 3, true) << "exit " << run.exit_code << "\n" << run.err;
}

}  // namespace
}  // namespace campo
