// Mesh files read into TriangleMesh (scene/mesh_sources): every format gives
// the same box and cylinder, node transforms, up axis and scale place the
// triangles, and bad files are refused with what was wrong; the "mesh"
// object of a scene (scene_loader) with its keys and errors.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <sys/stat.h>
#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "scene/mesh_sources.hpp"
#include "tests/mesh_file_writers.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test_support::SimpleMesh;

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_mesh_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) const {
    test_support::write_file(dir_ / name, bytes);
    return dir_ / name;
  }
  static MeshReadResult read(const fs::path& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                             MeshUpAxis up = MeshUpAxis::from_format, const MeshLimits& limits = {}) {
    return read_triangle_mesh(path, scale, up, limits, limits.max_triangles);
  }
  // The message of the error reading `path` throws.
  static std::string error_of(const fs::path& path, const MeshLimits& limits = {}) {
    try {
      read(path, Eigen::Vector3d::Ones(), MeshUpAxis::from_format, limits);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "(no error)";
  }

  fs::path dir_;
};

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The total area of a mesh's triangles, an independent check of the surface.
double area_of(const TriangleMesh& m) {
  double area = 0.0;
  for (const auto& t : m.triangles) {
    area += 0.5 * (m.vertices_m[t[1]] - m.vertices_m[t[0]]).cross(m.vertices_m[t[2]] - m.vertices_m[t[0]]).norm();
  }
  return area;
}

// The volume enclosed (divergence theorem): positive when the triangles face outward.
double enclosed_volume(const TriangleMesh& m) {
  double six_v = 0.0;
  for (const auto& t : m.triangles) {
    six_v += m.vertices_m[t[0]].dot(m.vertices_m[t[1]].cross(m.vertices_m[t[2]]));
  }
  return six_v / 6.0;
}

struct Format {
  const char* name;
  std::string (*bytes)(const SimpleMesh&);
};
const Format kFormats[] = {
    {"box.obj", [](const SimpleMesh& m) { return test_support::obj_text(m); }},
    {"box.stl", [](const SimpleMesh& m) { return test_support::stl_ascii_text(m); }},
    {"box_binary.stl", [](const SimpleMesh& m) { return test_support::stl_binary_bytes(m); }},
    {"box.ply", [](const SimpleMesh& m) { return test_support::ply_ascii_text(m); }},
    {"box_binary.ply", [](const SimpleMesh& m) { return test_support::ply_binary_bytes(m); }},
    {"box.gltf", [](const SimpleMesh& m) { return test_support::gltf_bytes(m, false); }},
    {"box.glb", [](const SimpleMesh& m) { return test_support::gltf_bytes(m, true); }},
};

TEST_F(MeshFiles, EveryFormatGivesTheSameClosedBox) {
  for (const Format& f : kFormats) {
    SCOPED_TRACE(f.name);
    const fs::path path = write(f.name, f.bytes(test_support::box_mesh()));
    const MeshReadResult r = read(path);
    const TriangleMesh& m = r.mesh;
    // STL repeats each corner per facet: welded, 8 corners remain.
    EXPECT_EQ(m.vertices_m.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_EQ(r.degenerate_triangles, 0u);
    EXPECT_TRUE(m.closed);
    EXPECT_TRUE(m.bounds_m.min().isApprox(Eigen::Vector3d::Constant(-0.5))) << m.bounds_m.min().transpose();
    EXPECT_TRUE(m.bounds_m.max().isApprox(Eigen::Vector3d::Constant(0.5))) << m.bounds_m.max().transpose();
    EXPECT_NEAR(area_of(m), 6.0, 1e-9);
    EXPECT_NEAR(enclosed_volume(m), 1.0, 1e-9);  // outward faces kept outward
    EXPECT_EQ(m.source_path, path.string());
    EXPECT_EQ(m.source_sha256, sha256_hex(file_bytes(path)));
    EXPECT_EQ(m.source_sha256.size(), 64u);
  }
}

TEST_F(MeshFiles, CylinderKeepsItsRadiusHeightAndVolume) {
  const int n = 256;
  const SimpleMesh cylinder = test_support::cylinder_mesh(0.5, 1.0, n);
  for (const Format& f : kFormats) {
    SCOPED_TRACE(f.name);
    // The file's axes as written (a glTF would otherwise be read Y-up).
    const TriangleMesh m =
        read(write(std::string("cyl_") + f.name, f.bytes(cylinder)), Eigen::Vector3d::Ones(), MeshUpAxis::z).mesh;
    EXPECT_EQ(m.vertices_m.size(), 2u * n + 2);
    EXPECT_EQ(m.triangles.size(), 4u * n);
    EXPECT_TRUE(m.closed);
    EXPECT_NEAR(m.bounds_m.max().z(), 0.5, 1e-7);
    EXPECT_NEAR(m.bounds_m.min().z(), -0.5, 1e-7);
    EXPECT_NEAR(m.bounds_m.max().x(), 0.5, 1e-7);
    for (const Eigen::Vector3d& v : m.vertices_m) {
      const double r = v.head<2>().norm();
      EXPECT_TRUE(std::abs(r - 0.5) < 1e-6 || r < 1e-9) << v.transpose();
    }
    // The inscribed 256-gon prism: n/2 r^2 sin(2 pi / n) h.
    EXPECT_NEAR(enclosed_volume(m), 0.5 * n * 0.25 * std::sin(2.0 * std::numbers::pi / n), 1e-6);
  }
}

TEST_F(MeshFiles, ScaleStretchesEachAxis) {
  const fs::path path = write("box.obj", test_support::obj_text(test_support::box_mesh()));
  const TriangleMesh m = read(path, {2.0, 3.0, 4.0}).mesh;
  EXPECT_TRUE(m.bounds_m.max().isApprox(Eigen::Vector3d(1.0, 1.5, 2.0)));
  EXPECT_TRUE(m.bounds_m.min().isApprox(Eigen::Vector3d(-1.0, -1.5, -2.0)));
  EXPECT_NEAR(enclosed_volume(m), 24.0, 1e-9);
}

TEST_F(MeshFiles, GltfIsYUpAndTheOthersZUpUnlessTold) {
  // A box 1 wide, 3 tall, 2 deep as a Y-up file writes it.
  const SimpleMesh tall_y = test_support::box_mesh({1.0, 3.0, 2.0});
  const fs::path glb = write("tall.glb", test_support::gltf_bytes(tall_y, true));
  const TriangleMesh by_format = read(glb).mesh;
  EXPECT_TRUE(by_format.bounds_m.max().isApprox(Eigen::Vector3d(0.5, 1.0, 1.5))) << by_format.bounds_m.max().transpose();
  const TriangleMesh as_z = read(glb, Eigen::Vector3d::Ones(), MeshUpAxis::z).mesh;
  EXPECT_TRUE(as_z.bounds_m.max().isApprox(Eigen::Vector3d(0.5, 1.5, 1.0)));
  const fs::path obj = write("tall.obj", test_support::obj_text(tall_y));
  EXPECT_TRUE(read(obj).mesh.bounds_m.max().isApprox(Eigen::Vector3d(0.5, 1.5, 1.0)));
  const TriangleMesh obj_y = read(obj, Eigen::Vector3d::Ones(), MeshUpAxis::y).mesh;
  EXPECT_TRUE(obj_y.bounds_m.max().isApprox(Eigen::Vector3d(0.5, 1.0, 1.5)));
  // A turn, not a mirror: the faces still face out.
  EXPECT_NEAR(enclosed_volume(obj_y), 6.0, 1e-9);
  // Scale applies along the shape's axes, after the turn.
  const TriangleMesh scaled = read(glb, {1.0, 1.0, 2.0}).mesh;
  EXPECT_NEAR(scaled.bounds_m.max().z(), 3.0, 1e-9);
}

TEST_F(MeshFiles, NodeTransformsPlaceEachPart) {
  // Two instances of a unit cube: a root moved 10 along x, with a child moved 5
  // up (glTF's +Y) and scaled by 2; the glTF Y-up turned to Z-up.
  const std::string nodes =
      R"([{"translation": [10, 0, 0], "children": [1], "mesh": 0},
          {"translation": [0, 5, 0], "scale": [2, 2, 2], "mesh": 0}])";
  const TriangleMesh m = read(write("parts.gltf", test_support::gltf_bytes(test_support::box_mesh(), false, nodes))).mesh;
  EXPECT_EQ(m.triangles.size(), 24u);
  EXPECT_EQ(m.vertices_m.size(), 16u);
  EXPECT_TRUE(m.closed);  // two closed boxes
  EXPECT_TRUE(m.bounds_m.min().isApprox(Eigen::Vector3d(9.0, -1.0, -0.5))) << m.bounds_m.min().transpose();
  EXPECT_TRUE(m.bounds_m.max().isApprox(Eigen::Vector3d(11.0, 1.0, 6.0))) << m.bounds_m.max().transpose();
  EXPECT_NEAR(enclosed_volume(m), 1.0 + 8.0, 1e-9);
}

TEST_F(MeshFiles, OpenMeshIsAcceptedAndNotClosed) {
  SimpleMesh open = test_support::box_mesh();
  open.triangles.resize(10);  // the last face missing
  const TriangleMesh m = read(write("open.stl", test_support::stl_binary_bytes(open))).mesh;
  EXPECT_EQ(m.triangles.size(), 10u);
  EXPECT_FALSE(m.closed);
}

TEST_F(MeshFiles, ZeroAreaTrianglesAreDroppedAndCounted) {
  SimpleMesh m = test_support::box_mesh();
  m.vertices.emplace_back(0.0, 0.0, 0.5);  // on the top face's diagonal: collinear with corners 4 and 7
  m.triangles.push_back({4, 7, 8});
  m.triangles.push_back({1, 1, 2});  // a repeated corner
  const MeshReadResult r = read(write("degenerate.obj", test_support::obj_text(m)));
  EXPECT_EQ(r.degenerate_triangles, 2u);
  EXPECT_EQ(r.mesh.triangles.size(), 12u);
  EXPECT_EQ(r.mesh.vertices_m.size(), 8u);  // the unused vertex is not kept
  EXPECT_TRUE(r.mesh.closed);
}

TEST_F(MeshFiles, BadFilesAreRefusedSayingWhy) {
  SimpleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_THAT(error_of(write("flat.stl", test_support::stl_binary_bytes(flat))), HasSubstr("zero area"));

  SimpleMesh nan = test_support::box_mesh();
  nan.vertices[3].x() = std::nan("");
  EXPECT_THAT(error_of(write("nan.stl", test_support::stl_binary_bytes(nan))), HasSubstr("not a number or infinite"));
  EXPECT_THAT(error_of(write("nan.ply", test_support::ply_binary_bytes(nan))), HasSubstr("not a number or infinite"));

  SimpleMesh far = test_support::box_mesh();
  far.vertices[0].x() = 3e6;
  EXPECT_THAT(error_of(write("far.obj", test_support::obj_text(far))), HasSubstr("within 1e6 m"));

  // A header that claims 50 million triangles: refused from the header, before reading.
  EXPECT_THAT(error_of(write("claims.stl", test_support::stl_binary_bytes(test_support::box_mesh(), 50'000'000))),
              HasSubstr("declares 50000000 triangles, more than the limit of 2000000"));
  // A header that claims more records than the file holds.
  EXPECT_THAT(error_of(write("short.stl", test_support::stl_binary_bytes(test_support::box_mesh(), 20))),
              HasSubstr("truncated binary STL"));
  const std::string glb = test_support::gltf_bytes(test_support::box_mesh(), true);
  EXPECT_THAT(error_of(write("short.glb", glb.substr(0, glb.size() - 30))), HasSubstr("complete GLB"));
  const std::string gltf = test_support::gltf_bytes(test_support::box_mesh(), false);
  EXPECT_THAT(error_of(write("short.gltf", gltf.substr(0, gltf.size() / 2))), HasSubstr("glTF whose JSON reads"));
  const std::string ply = test_support::ply_binary_bytes(test_support::box_mesh());
  EXPECT_THAT(error_of(write("short.ply", ply.substr(0, ply.size() - 40))), HasSubstr("assimp"));

  EXPECT_THAT(error_of(write("empty.obj", "")), HasSubstr("is empty"));
  EXPECT_THAT(error_of(write("comments.obj", "# nothing\n")), HasSubstr("assimp"));
  EXPECT_THAT(error_of(write("box.dae", "<xml/>")), HasSubstr("ending .obj, .stl, .ply, .gltf or .glb"));
  fs::create_directories(dir_ / "folder.obj");
  EXPECT_THAT(error_of(dir_ / "folder.obj"), HasSubstr("is not a file"));

  // Files a mesh names that assimp would open: a FIFO (which would block the read) and a folder.
  ASSERT_EQ(::mkfifo((dir_ / "pipe.mtl").c_str(), 0600), 0);
  EXPECT_THAT(error_of(write("pipe.obj", "mtllib pipe.mtl\n" + test_support::obj_text(test_support::box_mesh()))),
              HasSubstr("material library (mtllib) is a regular file"));
  fs::create_directories(dir_ / "buffer.bin");
  std::string external = test_support::gltf_bytes(test_support::box_mesh(), false);
  const std::size_t uri = external.find("data:application");
  external.replace(uri, external.find('"', uri) - uri, "buffer.bin");
  EXPECT_THAT(error_of(write("external.gltf", external)), HasSubstr("buffer file is a regular file"));

  // A node graph with a cycle.
  const std::string cycle = R"([{"children": [1], "mesh": 0}, {"children": [0]}])";
  EXPECT_THAT(error_of(write("cycle.gltf", test_support::gltf_bytes(test_support::box_mesh(), false, cycle))),
              HasSubstr("or in a cycle"));
}

TEST_F(MeshFiles, LimitsAreCheckedBeforeAndAfterParsing) {
  const fs::path box = write("box.obj", test_support::obj_text(test_support::box_mesh()));
  MeshLimits limits;
  limits.max_triangles = 11;
  EXPECT_THAT(error_of(box, limits), HasSubstr("declares 12 triangles, more than the limit of 11"));
  limits = {};
  limits.max_vertices = 7;
  EXPECT_THAT(error_of(box, limits), HasSubstr("declares 8 vertices"));
  limits = {};
  limits.max_file_bytes = 100;
  EXPECT_THAT(error_of(box, limits), HasSubstr("at most 100 bytes"));
  // What is left of a scene's budget.
  EXPECT_THAT(
      [&] {
        try {
          read_triangle_mesh(box, Eigen::Vector3d::Ones(), MeshUpAxis::z, MeshLimits{}, 5);
        } catch (const std::runtime_error& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      HasSubstr("what is left of the scene's 2000000 triangles"));
  // Instances multiply a mesh past the limit after parsing: 3 nodes x 12 triangles.
  const std::string nodes = R"([{"mesh": 0}, {"mesh": 0}, {"mesh": 0}])";
  limits = {};
  limits.max_triangles = 30;
  EXPECT_THAT(error_of(write("three.glb", test_support::gltf_bytes(test_support::box_mesh(), true, nodes, "[0, 1, 2]")),
                       limits),
              HasSubstr("at most 30 triangles"));
}

TEST(IsClosedSurface, CountsEdgeUses) {
  EXPECT_TRUE(is_closed_surface(test_support::box_mesh().triangles));
  auto triangles = test_support::box_mesh().triangles;
  triangles.push_back(triangles.front());  // an edge used three times
  EXPECT_FALSE(is_closed_surface(triangles));
  EXPECT_FALSE(is_closed_surface({}));
}

// ---------------------------------------------------------------------------
// The "mesh" object of a scene.

class MeshObjects : public MeshFiles {
 protected:
  Scene load(const std::string& objects, const SceneLimits& limits = {}) const {
    const fs::path scene = dir_ / "scene.json";
    test_support::write_file(scene, R"({"campo_scene": 1, "objects": [)" + objects + "]}");
    return load_scene(scene, limits);
  }
  std::string load_error(const std::string& objects, const SceneLimits& limits = {}) const {
    try {
      load(objects, limits);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
};

TEST_F(MeshObjects, FileScalePoseAndPropertiesAreRead) {
  fs::create_directories(dir_ / "meshes");
  write("meshes/box.stl", test_support::stl_ascii_text(test_support::box_mesh()));
  const Scene scene = load(R"({"alias": "house", "type": "mesh", "file": "meshes/box.stl", "scale": [2, 4, 6],
      "pose": {"position_m": [5, 1, 3], "rpy_deg": [0, 0, 90]}, "color": [0.2, 0.4, 0.6], "friction": 0.3},
      {"alias": "crate", "type": "mesh", "file": "meshes/box.stl", "scale": 0.5, "static": false, "mass_kg": 2})");
  ASSERT_EQ(scene.shapes.size(), 2u);
  const Shape& house = scene.shapes[0];
  EXPECT_EQ(house.type, ShapeType::mesh);
  ASSERT_TRUE(house.mesh);
  EXPECT_TRUE(house.mesh->bounds_m.max().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(house.pose.translation().isApprox(Eigen::Vector3d(5, 1, 3)));
  EXPECT_NEAR(house.pose.linear()(1, 0), 1.0, 1e-12);  // yaw 90: x -> y
  EXPECT_NEAR(house.color.b, 0.6, 0);
  EXPECT_NEAR(house.friction, 0.3, 0);
  EXPECT_TRUE(house.is_static);
  const Shape& crate = scene.shapes[1];
  EXPECT_FALSE(crate.is_static);
  EXPECT_EQ(crate.mass_kg, 2.0);
  EXPECT_TRUE(crate.mesh->bounds_m.max().isApprox(Eigen::Vector3d::Constant(0.25)));
}

TEST_F(MeshObjects, ErrorsNameTheFileAndPointer) {
  write("box.obj", test_support::obj_text(test_support::box_mesh()));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh"})"), HasSubstr("/objects/0"));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh"})"), HasSubstr("\"file\""));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh", "file": "box.obj", "scale": 0})"),
              HasSubstr("/objects/0/scale"));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh", "file": "box.obj", "scale": [1, -1, 1]})"),
              HasSubstr("/objects/0/scale/1"));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh", "file": "box.obj", "up_axis": "x"})"),
              HasSubstr("/objects/0/up_axis"));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh", "file": "box.obj", "static": false})"),
              HasSubstr("mass_kg"));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh", "file": "missing.obj"})"),
              HasSubstr("/objects/0/file"));
  write("nan.stl", [] {
    SimpleMesh m = test_support::box_mesh();
    m.vertices[0].z() = std::numeric_limits<double>::infinity();
    return test_support::stl_binary_bytes(m);
  }());
  const std::string nan = load_error(R"({"alias": "m", "type": "mesh", "file": "nan.stl"})");
  EXPECT_THAT(nan, HasSubstr("scene.json"));
  EXPECT_THAT(nan, HasSubstr("/objects/0/file"));
  EXPECT_THAT(nan, HasSubstr("not a number or infinite"));
  EXPECT_THAT(load_error(R"({"alias": "m", "type": "mesh", "file": "box.obj", "size_m": [1, 1, 1]})"),
              HasSubstr("size_m"));
}

TEST_F(MeshObjects, TheSceneHasOneTriangleBudgetForAllMeshes) {
  write("box.obj", test_support::obj_text(test_support::box_mesh()));
  SceneLimits limits;
  limits.max_mesh_triangles = 30;
  const std::string two = R"({"alias": "a", "type": "mesh", "file": "box.obj"},
                             {"alias": "b", "type": "mesh", "file": "box.obj"})";
  EXPECT_NO_THROW(load(two, limits));
  const std::string three = two + R"(, {"alias": "c", "type": "mesh", "file": "box.obj"})";
  const std::string error = load_error(three, limits);
  EXPECT_THAT(error, HasSubstr("/objects/2/file"));
  EXPECT_THAT(error, HasSubstr("what is left of the scene's 30 triangles"));
}

}  // namespace
}  // namespace campo
