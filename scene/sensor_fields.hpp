#pragma once
/// The fields of a sensor block's RangeSensorConfig (everything but its "alias" and
/// "type", the config's kind, which the block's reader sets first) and of a
/// vehicle's "state_noise", declared once: the loader reads them (parse_sensor,
/// the vehicle reader), run.json and `campo scan` write them, and
/// docs/scene-format.md's tables are generated from them.
#include "campo/config_fields.hpp"
#include "campo/range_sensor_config.hpp"
#include "campo/scene.hpp"
#include "campo/scene_loader.hpp"
#include "campo/state_noise.hpp"

namespace campo {

/// `limits` bounds the beams a "resolution" or "beams" may give. What each
/// kind accepts is declared with them (requirements on the kind set before).
ConfigFields<RangeSensorConfig> range_sensor_config_fields(const SceneLimits& limits = {});

/// A sensor's own "rate_hz": 0 (world.sensor_rate_hz) or in [0.01, 10000] (a
/// slower rate would be a period of more than 10^7 physics steps).
double read_sensor_rate_hz(const JsonNode& node);
/// A sensor's "range_m" [min, max], 0 <= min < max <= 100000, into min_m and max_m.
void read_range_m(const JsonNode& node, double& min_m, double& max_m);
/// A sensor's "mount": its pose on the vehicle body (every sensor type shares it).
const ConfigFields<Pose>& mount_fields();

/// An "imu" sensor block's fields (all but "alias" and "type"; scene/imu_fields.cpp).
const ConfigFields<ImuConfig>& imu_config_fields();
/// An "rgb_camera" sensor block's fields (all but "alias" and "type"; scene/rgb_camera_fields.cpp).
const ConfigFields<RgbCameraConfig>& rgb_camera_config_fields();

/// A vehicle's state-estimation noise (every field 0 = none).
const ConfigFields<StateNoiseConfig>& state_noise_fields();

}  // namespace campo
