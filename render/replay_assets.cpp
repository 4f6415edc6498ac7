#include "render/replay_assets.hpp"

// The viewer's files are assembled into the library by the assembler (.incbin), each
// followed by a NUL so it reads as a C string; CMake defines their paths when
// web/replay/node_modules was installed (tools/setup.sh) and rebuilds this file when
// they change.
#ifdef CAMPO_REPLAY_VIEWER
#define CAMPO_EMBED(symbol, path)                                                           \
  asm(".section .rodata\n.global " #symbol "\n.type " #symbol ", @object\n" #symbol ":\n" \
      ".incbin \"" path "\"\n.byte 0\n.previous\n");
CAMPO_EMBED(campo_replay_template, CAMPO_REPLAY_HTML)
CAMPO_EMBED(campo_replay_script, CAMPO_REPLAY_JS)
CAMPO_EMBED(campo_replay_three, CAMPO_REPLAY_THREE)
CAMPO_EMBED(campo_replay_orbit, CAMPO_REPLAY_ORBIT)
extern "C" const char campo_replay_template[], campo_replay_script[], campo_replay_three[], campo_replay_orbit[];
#endif

namespace campo {

std::optional<ReplayAssets> replay_assets() {
#ifdef CAMPO_REPLAY_VIEWER
  return ReplayAssets{campo_replay_template, campo_replay_script, campo_replay_three, campo_replay_orbit};
#else
  return std::nullopt;
#endif
}

}  // namespace campo
