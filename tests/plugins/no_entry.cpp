// Fixture: a library with campo's ABI marker but without the entry point that registers
// planners (written by hand rather than with CAMPO_REGISTER_PLANNERS): a missing symbol.
#include "campo/version.hpp"

extern "C" __attribute__((visibility("default"))) int campo_plugin_abi_version() noexcept {
  return CAMPO_PLUGIN_ABI_VERSION;
}
