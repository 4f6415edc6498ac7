#pragma once
/// The fields of a sensor block's LidarConfig (everything but its "alias" and
/// "type"), declared once: the loader reads them (parse_sensor), run.json and
/// `campo scan` write them (sensor_json), and docs/scene-format.md's table is
/// generated from them.
#include "campo/config_fields.hpp"
#include "campo/lidar_config.hpp"
#include "campo/scene_loader.hpp"

namespace campo {

/// `limits` bounds the beams a "resolution" or "beams" may give.
ConfigFields<LidarConfig> lidar_config_fields(const SceneLimits& limits = {});

}  // namespace campo
