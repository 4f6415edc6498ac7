#pragma once
/// Where the bundled scenes are: ./scenes when run from the repository root,
/// else the scenes folder beside the build directory holding the executable.
#include <filesystem>
#include <string>

namespace campo {

/// The file of the bundled scene `name` (e.g. "two_barriers"); when it cannot
/// be found, scenes/NAME.json, so that loading it reports the missing file.
std::filesystem::path bundled_scene(const std::string& name);

}  // namespace campo
