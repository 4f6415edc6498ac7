#include "render/sensors.hpp"

#include "render/depth_camera.hpp"

namespace campo {

std::unique_ptr<RangeSensor> make_range_sensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed) {
  if (def.type == SensorType::depth_camera) return make_depth_camera(scene, def);
  return make_lidar_sensor(scene, def, world_seed);
}

}  // namespace campo
