#pragma once
/// Where the bundled scenes and sweep specs are: ./scenes when run from the
/// repository root; else, beside the executable, share/campo/scenes of the
/// prefix campo is installed in (P/bin/campo -> P/share/campo/scenes), or the
/// source tree's scenes folder for a build directory inside it (build/campo ->
/// scenes).
#include <filesystem>
#include <string>

namespace campo {

/// The file of the bundled scene `name` (e.g. "two_barriers"); when it cannot
/// be found, scenes/NAME.json, so that loading it reports the missing file.
std::filesystem::path bundled_scene(const std::string& name);

/// The file of the bundled sweep spec `name` (e.g. "resolution_000", in
/// scenes/sweeps/); when it cannot be found, scenes/sweeps/NAME.json.
std::filesystem::path bundled_sweep_spec(const std::string& name);

/// A scene or sweep spec named on the command line: an existing file, or a
/// path, as it is; a bare name (no '/', no ".json") names a bundled file
/// through `bundled` (bundled_scene or bundled_sweep_spec).
std::filesystem::path file_or_bundled(const std::string& argument,
                                      std::filesystem::path (*bundled)(const std::string& name));

}  // namespace campo
