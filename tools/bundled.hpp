#pragma once
/// The bundled scenes, for the commands (the lookup lives in sweep/, which
/// resolves scene names in sweep specs too).
#include "sweep/bundled.hpp"

namespace campo::cli {

using campo::bundled_scene;
using campo::bundled_sweep_spec;
using campo::file_or_bundled;

}  // namespace campo::cli
