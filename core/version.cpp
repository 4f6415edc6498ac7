#include "campo/version.hpp"

// Generated on every build (cmake/git_revision.cmake) and included here alone, so a new
// commit recompiles one file rather than every file that sees the version.
#include "core/git_revision.hpp"

namespace campo {

std::string_view library_version() { return CAMPO_VERSION_STRING; }

int library_plugin_abi_version() { return CAMPO_PLUGIN_ABI_VERSION; }

std::string_view library_git_revision() { return CAMPO_GIT_REV; }

}  // namespace campo
