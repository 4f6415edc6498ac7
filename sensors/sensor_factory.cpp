#include "campo/sensor_factory.hpp"

#include "sensors/depth_camera.hpp"
#include "sensors/rgb_camera.hpp"

#include <optional>

namespace campo {

std::unique_ptr<RangeSensor> make_range_sensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed) {
  if (def.range.kind == RangeSensorKind::depth_camera) return make_depth_camera(scene, def);
  return make_lidar_sensor(scene, def, world_seed);
}

SensorFactory range_sensor_factory() {
  auto mesh = std::make_shared<std::optional<SceneMesh>>();
  return [mesh](const Scene& scene, const SensorDef& def, std::uint64_t world_seed) -> std::unique_ptr<RangeSensor> {
    if (def.range.kind != RangeSensorKind::depth_camera) return make_lidar_sensor(scene, def, world_seed);
    if (!*mesh) mesh->emplace(build_scene_mesh(scene));
    return make_depth_camera(scene, **mesh, def);
  };
}

RgbCameraFactory rgb_camera_factory() {
  auto mesh = std::make_shared<std::optional<SceneMesh>>();
  return [mesh](const Scene& scene, const RgbCameraDef& def, std::uint64_t world_seed) -> std::unique_ptr<RgbCamera> {
    if (!*mesh) mesh->emplace(build_scene_mesh(scene));
    return make_rgb_camera(**mesh, def, world_seed);
  };
}

}  // namespace campo
