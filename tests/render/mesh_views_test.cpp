// Mesh shapes in the pictures: the map draws a mesh's footprint (the hull of
// its vertices seen from above) in its colour, the scene mesh holds its
// triangles facing out, snapshots frame it, and the 3D replay carries its
// triangles once however many shapes use it, clustered coarser past its limit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "campo/pose.hpp"
#include "render/map_figure.hpp"
#include "render/replay.hpp"
#include "render/run_files.hpp"
#include "render/snapshot.hpp"
#include "scene/scene_mesh.hpp"
#include "tests/cli_support.hpp"
#include "tests/render/figure_test_support.hpp"
#include "tests/render/silhouette_support.hpp"
#include "tests/triangle_meshes.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using figure::test::at;
using figure::test::colour_distance;
using figure::test::kBackground;

// A prism whose cross-section is the right triangle (0,0) (4,0) (0,4), 2 m
// tall: its footprint is that triangle, not its bounding square.
std::shared_ptr<TriangleMesh> prism() {
  TriangleMesh m;
  const Eigen::Vector2d corners[] = {{0, 0}, {4, 0}, {0, 4}};
  for (const double z : {0.0, 2.0}) {
    for (const auto& c : corners) m.vertices_m.emplace_back(c.x(), c.y(), z);
  }
  m.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  return test_support::finished(std::move(m), true);
}

TEST(MeshViews, MapDrawsTheMeshFootprintInItsColour) {
  Scene scene = figure::test::test_scene();
  const Color green{0.1, 0.7, 0.2};
  scene.shapes.push_back(test_support::mesh_shape(prism(), to_isometry(Pose{{2.0, -5.5, 0.0}, {0, 0, 0}}), green));
  const RunView run = figure::test::test_run();
  const FigureStyle style = figure::test::small_style();
  const FigureLayout layout = map_layout(scene, run, style);
  const cv::Mat image = draw_map(scene, run, style).raster();
  const cv::Vec3b bgr(51, 179, 26);  // green as BGR, 255 * (0.2, 0.7, 0.1)
  // Inside the triangle (2, -5.5) (6, -5.5) (2, -1.5): the mesh's colour.
  EXPECT_LT(colour_distance(at(image, layout.to_px({3.0, -4.5})), bgr), 6);
  EXPECT_LT(colour_distance(at(image, layout.to_px({2.5, -2.5})), bgr), 6);
  // Inside its bounding square but past the hypotenuse: not drawn.
  EXPECT_GT(colour_distance(at(image, layout.to_px({5.2, -2.3})), bgr), 60);
}

TEST(MeshViews, SceneMeshHoldsAClosedMeshOnceFacingOutAndAnOpenOneTwice) {
  Scene scene;
  // The cube with its triangles turned inside out: drawn once, turned back to face out.
  auto inside_out = std::make_shared<TriangleMesh>(*test_support::cuboid_mesh());
  for (auto& t : inside_out->triangles) std::swap(t[1], t[2]);
  scene.shapes.push_back(test_support::mesh_shape(inside_out, to_isometry(Pose{{5.0, 0.0, 1.0}, {0, 0, 0}})));
  TriangleMesh square;
  square.vertices_m = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.shapes.push_back(test_support::mesh_shape(test_support::finished(std::move(square), false),
                                                  to_isometry(Pose{{0.0, 0.0, 3.0}, {0, 0, 0}})));
  const SceneMesh mesh = build_scene_mesh(scene);
  ASSERT_EQ(mesh.parts.size(), 2u);
  EXPECT_EQ(mesh.parts[0].index_count, 36u);
  EXPECT_EQ(mesh.parts[1].index_count, 12u);  // both sides
  // Every cube triangle's normal and winding point away from the cube's centre.
  const Eigen::Vector3f centre(5.0f, 0.0f, 1.0f);
  for (std::uint32_t k = 0; k < 36; k += 3) {
    const Eigen::Vector3f a = mesh.positions[mesh.indices[k]], b = mesh.positions[mesh.indices[k + 1]],
                          c = mesh.positions[mesh.indices[k + 2]];
    const Eigen::Vector3f out = (a + b + c) / 3.0f - centre;
    EXPECT_GT((b - a).cross(c - a).dot(out), 0.0f) << k;
    EXPECT_GT(mesh.normals[mesh.indices[k]].dot(out), 0.0f) << k;
  }
  // The square: one triangle pair facing up, one facing down.
  int up = 0, down = 0;
  for (std::uint32_t k = 36; k < 48; k += 3) {
    const Eigen::Vector3f a = mesh.positions[mesh.indices[k]], b = mesh.positions[mesh.indices[k + 1]],
                          c = mesh.positions[mesh.indices[k + 2]];
    const float z = (b - a).cross(c - a).z();
    (z > 0 ? up : down) += 1;
    EXPECT_GT(z * mesh.normals[mesh.indices[k]].z(), 0.0f);
  }
  EXPECT_EQ(up, 2);
  EXPECT_EQ(down, 2);
}

TEST(MeshViews, DefaultSnapshotFramesAMeshByItsVerticesNotItsOrigin) {
  // A mesh whose vertices lie 50 m from its file origin.
  TriangleMesh far = *test_support::cuboid_mesh();
  for (auto& v : far.vertices_m) v += Eigen::Vector3d(50.0, 0.0, 0.0);
  Scene scene;
  scene.shapes.push_back(test_support::mesh_shape(test_support::finished(std::move(far), true),
                                                  Eigen::Isometry3d::Identity()));
  const SnapshotCamera camera = default_snapshot_camera(scene, {});
  EXPECT_NEAR(camera.target_m.x(), 50.0, 1e-9);
}

class MeshReplay : public testing::CliTest {
 protected:
  // A recorded run of a bundled scene, its shapes then replaced by the test's.
  RecordedRun recorded(std::vector<Shape> shapes) {
    const fs::path out = dir_ / "run";
    const testing::Result r = campo("run " + std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json --out " +
                                    out.string() + " --no-figures");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    RecordedRun run = load_run_dir(out);
    run.scene.shapes = std::move(shapes);
    return run;
  }
};

TEST_F(MeshReplay, CarriesEachMeshsTrianglesOnceAndClustersLargeOnesWithinTheLimit) {
  RecordedRun run = recorded({});
  ASSERT_FALSE(HasFailure());
  // Two shapes share the cube; a third is a finely subdivided sphere.
  const auto cube = test_support::cuboid_mesh(Eigen::Vector3d(1.0, 2.0, 3.0));
  const auto ball = test_support::icosphere_mesh(1.5, 4);  // 5120 triangles
  run.scene.shapes.push_back(test_support::mesh_shape(cube, to_isometry(Pose{{1.0, 2.0, 1.5}, {0, 0, 30}})));
  run.scene.shapes.push_back(test_support::mesh_shape(cube, to_isometry(Pose{{-4.0, 2.0, 1.5}, {0, 0, 0}})));
  run.scene.shapes.push_back(test_support::mesh_shape(ball, to_isometry(Pose{{0.0, -6.0, 2.0}, {0, 0, 0}})));

  ReplayLimits limits;
  limits.max_mesh_triangles = 2000;
  const nlohmann::json scene = replay_data({run}, limits)["scene"];
  const nlohmann::json& shapes = scene["shapes"];
  const nlohmann::json& meshes = scene["meshes"];
  ASSERT_EQ(meshes.size(), 2u);
  std::size_t mesh_shapes = 0;
  for (const auto& s : shapes) mesh_shapes += s["type"] == "mesh";
  ASSERT_EQ(mesh_shapes, 3u);
  // Shapes keep scene order among the solids: the three meshes come last.
  const nlohmann::json& a = shapes[shapes.size() - 3];
  const nlohmann::json& b = shapes[shapes.size() - 2];
  const nlohmann::json& c = shapes[shapes.size() - 1];
  EXPECT_EQ(a["mesh"], b["mesh"]);
  EXPECT_NE(a["mesh"], c["mesh"]);

  // The cube exactly: its 12 triangles, its vertices in the shape frame (mm).
  const nlohmann::json& cube_json = meshes[a["mesh"].get<std::size_t>()];
  EXPECT_FALSE(cube_json["decimated"].get<bool>());
  ASSERT_EQ(cube_json["triangles"].size(), 36u);
  ASSERT_EQ(cube_json["vertices_m"].size(), 24u);
  for (std::size_t i = 0; i < 36; ++i) {
    EXPECT_EQ(cube_json["triangles"][i].get<std::uint32_t>(), cube->triangles[i / 3][i % 3]);
  }
  for (std::size_t i = 0; i < 24; ++i) {
    EXPECT_NEAR(cube_json["vertices_m"][i].get<double>(), cube->vertices_m[i / 3][static_cast<int>(i % 3)], 5e-4);
  }

  // The sphere: 5120 triangles of 5132 in all is over 2000, so it keeps its share and is clustered.
  const nlohmann::json& ball_json = meshes[c["mesh"].get<std::size_t>()];
  EXPECT_TRUE(ball_json["decimated"].get<bool>());
  EXPECT_EQ(ball_json["file_triangles"].get<std::size_t>(), 5120u);
  const std::size_t kept = ball_json["triangles"].size() / 3;
  const std::size_t share = 2000 * 5120 / 5132;
  EXPECT_LE(kept, share);
  EXPECT_GT(kept, share / 4);  // the finest grid that fits keeps a good part of it
  // Clustered vertices are means of the sphere's vertices: near the sphere, within the cell size.
  const nlohmann::json& v = ball_json["vertices_m"];
  const std::size_t count = v.size() / 3;
  for (std::size_t i = 0; i < count; ++i) {
    const double r = Eigen::Vector3d(v[3 * i].get<double>(), v[3 * i + 1].get<double>(), v[3 * i + 2].get<double>()).norm();
    EXPECT_GT(r, 1.2);
    EXPECT_LT(r, 1.501);
  }
  for (const auto& index : ball_json["triangles"]) EXPECT_LT(index.get<std::size_t>(), count);

  // The page's bounds take in the meshes' vertices.
  const nlohmann::json data = replay_data({run}, limits);
  EXPECT_LE(data["scene"]["bounds_m"]["min"][1].get<double>(), -7.5 + 1e-3);
}

// The page draws the meshes where campo's own render (the scene mesh through
// OSMesa) has them: Chromium's silhouette of the replay against the snapshot.
TEST_F(MeshReplay, PageDrawsTheMeshesWhereCamposRenderHasThem) {
  std::vector<Shape> shapes;
  shapes.push_back(test_support::mesh_shape(test_support::cuboid_mesh(Eigen::Vector3d(3.0, 2.0, 2.5)),
                                            to_isometry(Pose{{-3.0, 2.0, 1.25}, {0, 0, 35}})));
  shapes.push_back(test_support::mesh_shape(test_support::cylinder_mesh(1.0, 4.0, 64),
                                            to_isometry(Pose{{3.0, 3.0, 2.0}, {20, 0, 0}})));
  shapes.push_back(test_support::mesh_shape(test_support::icosphere_mesh(1.5, 3),
                                            to_isometry(Pose{{1.0, -3.0, 1.5}, {0, 0, 0}})));
  // An open mesh: a single wall, seen from its back.
  TriangleMesh wall;
  wall.vertices_m = {{0, -2, 0}, {0, 2, 0}, {0, 2, 3}, {0, -2, 3}};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  shapes.push_back(test_support::mesh_shape(test_support::finished(std::move(wall), false),
                                            to_isometry(Pose{{-4.0, -4.0, 0.0}, {0, 0, 20}})));
  const RecordedRun run = recorded(shapes);
  ASSERT_FALSE(HasFailure());
  const fs::path page_file = dir_ / "replay.html";
  {
    std::ofstream page(page_file);
    page << replay_html(replay_data({run}));
  }
  const fs::path shot = dir_ / "shot.png";
  const std::string command =
      "chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--enable-logging=stderr --v=0 --virtual-time-budget=5000 --window-size=640,480 --screenshot=" + shot.string() +
      " 'file://" + page_file.string() + "#view=silhouette&fov=50&camera=-8,-9,8,0,0,1' >" +
      (dir_ / "chromium.out").string() + " 2>" + (dir_ / "chromium.err").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << testing::slurp(dir_ / "chromium.err");
  for (const std::string& line : testing::lines_of(testing::slurp(dir_ / "chromium.err"))) {
    EXPECT_EQ(line.find("CONSOLE"), std::string::npos) << line;
    EXPECT_EQ(line.find("Uncaught"), std::string::npos) << line;
  }
  const cv::Mat page = cv::imread(shot.string(), cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(page.size(), cv::Size(640, 480));
  SnapshotCamera camera;
  camera.eye_m = {-8.0, -9.0, 8.0};
  camera.target_m = {0.0, 0.0, 1.0};
  camera.fov_deg = 50.0;
  camera.width_px = 640;
  camera.height_px = 480;
  const cv::Mat own = render_snapshot(run.scene, build_scene_mesh(run.scene), camera, {}, std::nullopt,
                                      VehicleType::quadrotor);
  const test::SilhouetteComparison c = test::compare_silhouettes(own, page);
  EXPECT_GT(c.solid, 640 * 480 / 8);
  // The silhouettes agree but for edge pixels (0.989 here).
  const double overlap = c.overlap();
  EXPECT_GT(overlap, 0.98) << c.both << " / " << c.either;
  RecordProperty("silhouette_overlap", std::to_string(overlap));
}

}  // namespace
}  // namespace campo
