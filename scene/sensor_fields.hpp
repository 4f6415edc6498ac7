#pragma once
/// The fields of a sensor block's RangeSensorConfig (everything but its "alias" and
/// "type", the config's kind, which the block's reader sets first) and of a
/// vehicle's "state_noise", declared once: the loader reads them (parse_sensor,
/// the vehicle reader), run.json and `campo scan` write them, and
/// docs/scene-format.md's tables are generated from them.
#include "campo/config_fields.hpp"
#include "campo/range_sensor_config.hpp"
#include "campo/scene_loader.hpp"
#include "campo/state_noise.hpp"

namespace campo {

/// `limits` bounds the beams a "resolution" or "beams" may give. What each
/// kind accepts is declared with them (requirements on the kind set before).
ConfigFields<RangeSensorConfig> range_sensor_config_fields(const SceneLimits& limits = {});

/// A vehicle's state-estimation noise (every field 0 = none).
const ConfigFields<StateNoiseConfig>& state_noise_fields();

}  // namespace campo
