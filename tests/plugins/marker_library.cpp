// Fixture: an ordinary shared library that defines campo's plugin symbols (an entry point
// adding nothing); not_a_plugin.so depends on it, so dlsym on not_a_plugin finds them.
#include "campo/plugin.hpp"

CAMPO_REGISTER_PLANNERS(registrar) { static_cast<void>(registrar); }

extern "C" __attribute__((visibility("default"))) int fixture_marker_library_answer() { return 42; }
