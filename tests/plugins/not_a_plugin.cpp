// Fixture: a shared library that does not include campo/plugin.hpp, so it has
// no campo_plugin_abi_version of its own; one of its dependencies
// (marker_library.so) has one, which the loader must not take for its own.
extern "C" int fixture_marker_library_answer();

extern "C" __attribute__((visibility("default"))) int fixture_not_a_plugin_answer() {
  return fixture_marker_library_answer();
}
