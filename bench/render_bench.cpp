// OSMesa rendering: depth camera scans per second at 16..256 px square (the
// scanner3d frustum, read-back and range image included) on the trees
// scene, the scene-mesh build, and a reference: a plain draw of the whole
// mesh into a 256 x 256 depth buffer read back with glReadPixels.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "campo/scene_loader.hpp"
#include "scene/scene_mesh.hpp"
#include "sensors/depth_camera.hpp"
#include "sensors/osmesa_gl.hpp"

namespace campo {
namespace {

Scene bundled(const std::string& name) {
  return load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
}

SensorDef scanner(int n) {
  SensorDef def;
  def.alias = "camera";
  def.range = *sensor_preset("scanner3d");
  def.range.kind = RangeSensorKind::depth_camera;
  def.range.cols = n;
  def.range.rows = n;
  return def;
}

// The vehicle's sensor pose, turned a little each scan.
Eigen::Isometry3d sensor_pose(const Scene& scene, const RangeSensorConfig& config, std::int64_t scan) {
  Eigen::Isometry3d pose = scene.vehicles.front().pose * to_isometry(config.mount);
  pose.linear() = Eigen::AngleAxisd(0.05 * static_cast<double>(scan), Eigen::Vector3d::UnitZ()) * pose.linear();
  return pose;
}

void BM_DepthCameraScan(benchmark::State& state) {
  const Scene scene = bundled("trees_rolling_terrain");
  const SensorDef def = scanner(static_cast<int>(state.range(0)));
  const auto camera = make_depth_camera(scene, def);
  const std::vector<Eigen::Isometry3d> poses = scripted_poses(scene, 0.0);
  RangeScan scan;
  std::int64_t scans = 0, hits = 0;
  for (auto _ : state) {
    camera->scan(sensor_pose(scene, def.range, scans++), 0.0, poses, scan);
    hits += static_cast<std::int64_t>(scan.points.size());
  }
  state.SetItemsProcessed(scans);
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(scans * def.range.beam_count());
}

void BM_SceneMeshBuild(benchmark::State& state, const std::string& name) {
  const Scene scene = bundled(name);
  std::size_t triangles = 0;
  for (auto _ : state) {
    const SceneMesh mesh = build_scene_mesh(scene);
    triangles = mesh.triangle_count();
    benchmark::DoNotOptimize(mesh.indices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

// Reference for the camera: every triangle drawn with a position-only
// shader into a 256 x 256 depth buffer of the same 90 x 90 deg view, no
// culling of any kind, depth read back as floats.
void BM_RawOsmesaDraw256(benchmark::State& state) {
  const Scene scene = bundled("trees_rolling_terrain");
  const SceneMesh mesh = build_scene_mesh(scene);
  constexpr int kSize = 256;
  OsmesaContext context;
  const GlProgram program = make_program(R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 model_view_projection;
void main() { gl_Position = model_view_projection * vec4(position, 1.0); }
)",
                                         R"(#version 450 core
void main() {}
)");
  const GpuMesh gpu = upload_mesh(mesh, false);
  const Framebuffer target = make_framebuffer(kSize, kSize, 0, GL_DEPTH_COMPONENT32F);
  gl().Viewport(0, 0, kSize, kSize);
  gl().Enable(GL_DEPTH_TEST);
  gl().UseProgram(program.id());
  const RangeSensorConfig config = scanner(kSize).range;
  // 90 deg square frustum, near 0.05 m, far 10 m; eye looking along the sensor's x.
  constexpr double kNear = 0.05, kFar = 10.0;
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = 1.0;
  projection(1, 1) = 1.0;
  projection(2, 2) = -(kFar + kNear) / (kFar - kNear);
  projection(2, 3) = -2.0 * kFar * kNear / (kFar - kNear);
  projection(3, 2) = -1.0;
  Eigen::Isometry3d eye_from_sensor = Eigen::Isometry3d::Identity();
  eye_from_sensor.linear() << 0, -1, 0, 0, 0, 1, -1, 0, 0;
  std::vector<float> depth(kSize * kSize);
  std::int64_t scans = 0;
  for (auto _ : state) {
    const Eigen::Matrix4f mvp =
        (projection * (eye_from_sensor * sensor_pose(scene, config, scans++).inverse()).matrix()).cast<float>();
    gl().UniformMatrix4fv(0, 1, GL_FALSE, mvp.data());
    gl().Clear(GL_DEPTH_BUFFER_BIT);
    gl().DrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
    gl().ReadPixels(0, 0, kSize, kSize, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    benchmark::DoNotOptimize(depth.data());
  }
  state.SetItemsProcessed(scans);
  state.counters["triangles"] = static_cast<double>(mesh.triangle_count());
}

// Real time: llvmpipe rasterizes on its own threads.
BENCHMARK(BM_DepthCameraScan)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RawOsmesaDraw256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SceneMeshBuild, trees_rolling_terrain, std::string("trees_rolling_terrain"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneMeshBuild, vineyard, std::string("vineyard"))->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace campo
