#include "campo/version.hpp"

// CAMPO_GIT_REV is defined for this file alone (CMakeLists.txt), so a new commit
// recompiles one file rather than every file that sees the version.
#ifndef CAMPO_GIT_REV
#error "CAMPO_GIT_REV must be defined by the build"
#endif

namespace campo {

std::string_view library_version() { return CAMPO_VERSION_STRING; }

int library_plugin_abi_version() { return CAMPO_PLUGIN_ABI_VERSION; }

std::string_view library_git_revision() { return CAMPO_GIT_REV; }

}  // namespace campo
