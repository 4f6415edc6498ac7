#pragma once
/// The replay viewer's files (web/replay), embedded in campo when it is built.
#include <optional>
#include <string_view>

namespace campo {

struct ReplayAssets {
  std::string_view page;     ///< web/replay/replay.html: the template with its markers
  std::string_view script;   ///< web/replay/replay.js: the viewer
  std::string_view three;    ///< three.js (build/three.min.js), from the npm registry
  std::string_view orbit;    ///< three.js's orbit controls (examples/js/controls/OrbitControls.js)
};

/// The embedded files; nullopt when campo was built without them
/// (web/replay/node_modules missing: tools/setup.sh installs it).
std::optional<ReplayAssets> replay_assets();

}  // namespace campo
