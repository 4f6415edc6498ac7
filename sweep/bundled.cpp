#include "sweep/bundled.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <mutex>
#include <optional>

#include "campo/json_reader.hpp"

// From the folder of the installed library to the installed scenes, set by CMakeLists.txt from the install
// layout (CMAKE_INSTALL_LIBDIR and DATADIR: "../share/campo/scenes" for P/lib and P/share).
#ifndef CAMPO_LIBDIR_TO_SCENES
#define CAMPO_LIBDIR_TO_SCENES "../share/campo/scenes"
#endif

namespace campo {

namespace {

namespace fs = std::filesystem;

// The pip-installed package's data folder (set_package_bundled_folder), set once on import and
// read by every lookup, possibly from several threads.
std::mutex package_folder_mutex;
std::optional<fs::path> package_folder;

// The file of the library holding this code (libcampo), symbolic links resolved; empty if unknown.
// The program, its tests and the Python module all load libcampo, so bundled files are found from
// it the same way by each (the executable, /proc/self/exe, is the interpreter in Python).
fs::path library_file() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&library_file), &info) == 0 || info.dli_fname == nullptr ||
      info.dli_fname[0] == '\0') {
    return {};
  }
  std::error_code ec;
  fs::path file = fs::canonical(info.dli_fname, ec);
  if (ec) return {};
  return file;
}

// `relative` (e.g. "sweeps/x.json") in the first bundled folder that holds it; else an InputError
// naming `what` and listing the folders searched.
fs::path bundled_file(const fs::path& relative, const std::string& what) {
  const std::vector<fs::path> folders = bundled_folders();
  std::error_code ec;
  for (const fs::path& folder : folders) {
    const fs::path candidate = folder / relative;
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  std::string searched;
  for (const fs::path& folder : folders) {
    searched += (searched.empty() ? "" : ", ") + folder.string();
    if (folder.is_relative()) searched += " (from the working directory)";
  }
  throw InputError(relative.stem().string(), "",
                   "no bundled " + what + " of that name: looked for " + relative.string() + " in " + searched);
}

}  // namespace

void set_package_bundled_folder(const fs::path& folder) {
  const std::lock_guard<std::mutex> lock(package_folder_mutex);
  package_folder = folder;
}

std::vector<fs::path> bundled_folders() {
  std::vector<fs::path> folders{"scenes"};
  {
    const std::lock_guard<std::mutex> lock(package_folder_mutex);
    if (package_folder) {
      // Beside the package's libcampo (site-packages/campo), the prefix and source-tree candidates name nothing.
      folders.push_back(*package_folder);
      return folders;
    }
  }
  const fs::path library = library_file();
  if (library.empty()) return folders;
  const fs::path library_dir = library.parent_path();
  // Installed: P/lib/libcampo.so -> P/share/campo/scenes; a build directory in the source tree: build/libcampo.so -> scenes.
  for (const fs::path& folder : {(library_dir / CAMPO_LIBDIR_TO_SCENES).lexically_normal(),
                                 library_dir.parent_path() / "scenes"}) {
    if (std::find(folders.begin(), folders.end(), folder) == folders.end()) folders.push_back(folder);
  }
  return folders;
}

fs::path bundled_scene(const std::string& name) { return bundled_file(name + ".json", "scene"); }

fs::path bundled_sweep_spec(const std::string& name) {
  return bundled_file(fs::path("sweeps") / (name + ".json"), "sweep spec");
}

fs::path file_or_bundled(const std::string& argument, fs::path (*bundled)(const std::string& name)) {
  std::error_code ec;
  const bool bare_name = !argument.empty() && argument.find('/') == std::string::npos &&
                         fs::path(argument).extension() != ".json";
  if (!bare_name || fs::exists(argument, ec)) return argument;
  return bundled(argument);
}

}  // namespace campo
