#pragma once
/// Builds any range sensor: the ray-cast LIDAR, or the OSMesa depth camera.
#include <memory>

#include "sim/range_sensor.hpp"

namespace campo {

/// A RangeSensor for `def` of either type (a SensorFactory).
std::unique_ptr<RangeSensor> make_range_sensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed);

}  // namespace campo
