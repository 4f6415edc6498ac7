#pragma once
/// A block of parameters that another module validates (vehicle presets,
/// planners), kept with where it came from. Its own header so that
/// config_fields.hpp (core) reads one without the whole scene description.
#include <string>

#include <nlohmann/json.hpp>

namespace campo {

/// Parameters that another module validates (vehicle presets, planners),
/// kept with where they came from so its errors can name file and pointer.
struct ParamsBlock {
  nlohmann::json values = nlohmann::json::object();
  std::string file;     ///< scene file
  std::string pointer;  ///< JSON pointer of the block (where it would be, when absent)
};

}  // namespace campo
