// LIDAR throughput on the bundled scenes: rays per second on one core for
// scanner3d 256 x 256 scans from the scene's vehicle, cast by fan (what a
// Lidar does by default on an AVX2 CPU) and ray by ray through Embree, against
// a plain loop of Bullet ray tests over the same rays, and the cost of
// building the BVH.
#include <benchmark/benchmark.h>

#include <string>

#include "campo/scene_loader.hpp"
#include "campo/world.hpp"
#include "sensors/lidar.hpp"
#include "sensors/raycaster.hpp"

namespace campo {
namespace {

Scene bundled(const std::string& name) {
  return load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
}

RangeSensorConfig scanner() { return *sensor_preset("scanner3d"); }

// The vehicle's sensor pose, turned a little each scan so rays see new geometry.
Eigen::Isometry3d sensor_pose(const Scene& scene, const RangeSensorConfig& config, std::int64_t scan) {
  Eigen::Isometry3d pose = scene.vehicles.front().pose * to_isometry(config.mount);
  pose.linear() = Eigen::AngleAxisd(0.05 * static_cast<double>(scan), Eigen::Vector3d::UnitZ()) * pose.linear();
  return pose;
}

void BM_LidarScanner3d(benchmark::State& state, const std::string& name, CastMethod method) {
  const Scene scene = bundled(name);
  const RayCaster caster(scene, method);
  Lidar lidar(scanner(), scene.world.seed);
  RangeScan scan;
  std::int64_t scans = 0, hits = 0;
  for (auto _ : state) {
    lidar.scan(caster, sensor_pose(scene, lidar.config(), scans++), 0.0, scan);
    hits += static_cast<std::int64_t>(scan.points.size());
  }
  state.SetItemsProcessed(scans * lidar.config().beam_count());
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(scans * lidar.config().beam_count());
}

void BM_BulletRayTestLoop(benchmark::State& state, const std::string& name) {
  const Scene scene = bundled(name);
  const World world(scene);
  const RangeSensorConfig config = scanner();
  const Lidar lidar(config, 0);
  std::int64_t scans = 0, rays = 0;
  for (auto _ : state) {
    const Eigen::Isometry3d pose = sensor_pose(scene, config, scans++);
    for (const Eigen::Vector3f& d : lidar.directions()) {
      const Eigen::Vector3d dir = pose.linear() * d.cast<double>();
      benchmark::DoNotOptimize(world.ray_test(pose.translation(), pose.translation() + dir * config.max_range_m));
    }
    rays += static_cast<std::int64_t>(lidar.directions().size());
  }
  state.SetItemsProcessed(rays);
}

void BM_RayCasterBuild(benchmark::State& state, const std::string& name) {
  const Scene scene = bundled(name);
  for (auto _ : state) {
    RayCaster caster(scene);
    benchmark::DoNotOptimize(&caster);
  }
}

BENCHMARK_CAPTURE(BM_LidarScanner3d, trees_rolling_terrain, std::string("trees_rolling_terrain"), CastMethod::fan)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LidarScanner3d, vineyard, std::string("vineyard"), CastMethod::fan)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LidarScanner3d, trees_rolling_terrain_embree, std::string("trees_rolling_terrain"),
                  CastMethod::embree)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LidarScanner3d, vineyard_embree, std::string("vineyard"), CastMethod::embree)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BulletRayTestLoop, trees_rolling_terrain, std::string("trees_rolling_terrain"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BulletRayTestLoop, vineyard, std::string("vineyard"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCasterBuild, trees_rolling_terrain, std::string("trees_rolling_terrain"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCasterBuild, vineyard, std::string("vineyard"))->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace campo
