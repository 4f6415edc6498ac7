#include "sweep/bundled.hpp"

#include <array>

namespace campo {

namespace {

namespace fs = std::filesystem;

// `relative` (e.g. "sweeps/x.json") in the first bundled scenes folder that holds it.
fs::path bundled_file(const fs::path& relative) {
  const fs::path here = fs::path("scenes") / relative;
  std::error_code ec;
  if (fs::exists(here, ec)) return here;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path prefix = exe.parent_path().parent_path();
    // Installed: P/bin/campo -> P/share/campo/scenes; a build directory in the source tree: build/campo -> scenes.
    for (const fs::path& dir : std::array{prefix / "share" / "campo" / "scenes", prefix / "scenes"}) {
      const fs::path candidate = dir / relative;
      if (fs::exists(candidate, ec)) return candidate;
    }
  }
  return here;  // missing: the loader reports it
}

}  // namespace

fs::path bundled_scene(const std::string& name) { return bundled_file(name + ".json"); }

fs::path bundled_sweep_spec(const std::string& name) { return bundled_file(fs::path("sweeps") / (name + ".json")); }

fs::path file_or_bundled(const std::string& argument, fs::path (*bundled)(const std::string& name)) {
  std::error_code ec;
  const bool bare_name = !argument.empty() && argument.find('/') == std::string::npos &&
                         fs::path(argument).extension() != ".json";
  if (!bare_name || fs::exists(argument, ec)) return argument;
  return bundled(argument);
}

}  // namespace campo
