// Fixture: an ordinary shared library that happens to include campo/plugin.hpp,
// so it defines the plugin marker; not_a_plugin.so depends on it.
#include "campo/plugin.hpp"

extern "C" __attribute__((visibility("default"))) int fixture_marker_library_answer() { return 42; }
