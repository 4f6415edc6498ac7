#pragma once
/// Building any range sensor (the ray-cast LIDAR or the OSMesa depth camera)
/// and the OSMesa colour camera.
/// range_sensor_factory() is the SensorFactory (range_sensor.hpp) that a
/// program embedding campo puts in EpisodeOptions::make_sensor to have
/// depth cameras too. Implemented in sensors/.
#include <cstdint>
#include <memory>

#include "campo/range_sensor.hpp"
#include "campo/rgb_camera.hpp"
#include "campo/scene.hpp"

namespace campo {

/// A RangeSensor for `def` of either type.
std::unique_ptr<RangeSensor> make_range_sensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed);

/// A SensorFactory for the sensors of one scene: its depth cameras share one
/// scene mesh, built when the first of them is made.
SensorFactory range_sensor_factory();

/// An RgbCameraFactory (rgb_camera.hpp) for the colour cameras of one scene,
/// for EpisodeOptions::make_camera: they share one scene mesh, built when
/// the first of them is made.
RgbCameraFactory rgb_camera_factory();

}  // namespace campo
