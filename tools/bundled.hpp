#pragma once
/// Where the bundled scenes are: ./scenes when run from the repository root,
/// else the scenes folder beside the build directory holding the executable.
#include <filesystem>
#include <string>

namespace campo::cli {

std::filesystem::path bundled_scene(const std::string& name);

}  // namespace campo::cli
