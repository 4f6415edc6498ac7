#pragma once
/// Where the bundled scenes and sweep specs are, for the program, the Python
/// module and the sweeps alike (one lookup: it starts from libcampo, which all
/// of them load, not from the executable, which for Python is the interpreter).
/// The folders searched, in order:
///   1. scenes/ of the working directory (the repository root);
///   2. the installed prefix's: beside libcampo in P/lib, P/share/campo/scenes
///      (the install layout, CMakeLists.txt);
///   3. the source tree's: libcampo in a build directory inside the source tree
///      (build/libcampo.so), the source tree's scenes/.
/// A Python package installed by pip (pyproject.toml) carries its own copy
/// (site-packages/campo/data/scenes, beside the libcampo it loads, where 2 and
/// 3 name nothing): its campo/__init__.py names that folder through
/// set_package_bundled_folder, which then replaces 2 and 3. The program never
/// calls it, so its search is the one above.
#include <filesystem>
#include <string>
#include <vector>

namespace campo {

/// The folders searched for bundled files, in the order above; the first one
/// relative to the working directory ("scenes"), the others absolute.
std::vector<std::filesystem::path> bundled_folders();

/// Makes `folder` (absolute) the one searched after the working directory's
/// scenes/, instead of the installed prefix's and the source tree's: what the
/// pip-installed Python package calls on import with its data folder. Only a
/// process that loaded that package calls it.
void set_package_bundled_folder(const std::filesystem::path& folder);

/// The file of the bundled scene `name` (e.g. "two_barriers"), NAME.json in
/// the first folder of bundled_folders() that holds it; none holding it, an
/// InputError naming `name` and listing the folders searched.
std::filesystem::path bundled_scene(const std::string& name);

/// The file of the bundled sweep spec `name` (e.g. "resolution_000"),
/// sweeps/NAME.json in the first folder that holds it; else an InputError as
/// for bundled_scene.
std::filesystem::path bundled_sweep_spec(const std::string& name);

/// A scene or sweep spec named on the command line: an existing file, or a
/// path, as it is; a bare name (no '/', no ".json") names a bundled file
/// through `bundled` (bundled_scene or bundled_sweep_spec).
std::filesystem::path file_or_bundled(const std::string& argument,
                                      std::filesystem::path (*bundled)(const std::string& name));

}  // namespace campo
