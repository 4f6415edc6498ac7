#pragma once
/// The fields of a scene's "world" block (WorldConfig, its geo reference and wind),
/// declared once: the loader reads them and run.json writes them from here.
#include "campo/config_fields.hpp"
#include "campo/scene.hpp"

namespace campo {

const ConfigFields<GeoReference>& geo_reference_fields();
const ConfigFields<WindConfig>& wind_config_fields();
const ConfigFields<WorldConfig>& world_config_fields();

}  // namespace campo
