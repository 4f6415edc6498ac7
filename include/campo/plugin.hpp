#pragma once
/// Planner plugins (docs/extending.md): a shared library, built against an
/// installed campo (a CMake MODULE library linked to campo::campo), whose
/// planners campo loads at run time (`campo run --plugin PATH`, a sweep spec's
/// "plugins"). Include this header in the plugin's sources and register each
/// planner once, at namespace scope:
///
///     CAMPO_REGISTER_PLANNER("bug2", "go to goal, follow obstacles' edges", &make_bug2_planner);
///
/// Including the header marks the library as a campo plugin: it defines the
/// exported symbol campo_plugin_abi_version, the CAMPO_PLUGIN_ABI_VERSION the
/// plugin was compiled against, which campo checks before using it.
#include "campo/json_reader.hpp"
#include "campo/planner.hpp"
#include "campo/version.hpp"

/// Called by the registrars of CAMPO_REGISTER_PLANNER while campo loads the
/// plugin; `abi_version` is the CAMPO_PLUGIN_ABI_VERSION the plugin was
/// compiled against. C linkage keeps its symbol the same across ABI versions,
/// so that a mismatch is reported rather than failing to link.
extern "C" void campo_plugin_register_planner(int abi_version, const char* name, const char* description,
                                              campo::PlannerFactory factory) noexcept;

#ifndef CAMPO_PLUGIN_NO_MARKER
/// The plugin marker. Weak, so that every source file of a plugin may include
/// this header; exported whatever the plugin's default symbol visibility.
/// (libcampo's registry defines CAMPO_PLUGIN_NO_MARKER before including this
/// header: libcampo is no plugin.)
extern "C" __attribute__((weak, visibility("default"))) const int campo_plugin_abi_version = CAMPO_PLUGIN_ABI_VERSION;
#endif

namespace campo::plugin_detail {

/// Registers one planner when the plugin is loaded (static initialization).
struct PlannerRegistrar {
  PlannerRegistrar(const char* name, const char* description, PlannerFactory factory) noexcept {
    campo_plugin_register_planner(CAMPO_PLUGIN_ABI_VERSION, name, description, factory);
  }
};

}  // namespace campo::plugin_detail

#define CAMPO_PLUGIN_CONCAT_INNER(a, b) a##b
#define CAMPO_PLUGIN_CONCAT(a, b) CAMPO_PLUGIN_CONCAT_INNER(a, b)

/// Registers the planner `name` (a string literal: letters, digits, '_' and
/// '-'; the name scenes and --planner use) with a one-line `description`
/// (campo run --list-planners) and its `factory` (a campo::PlannerFactory).
/// Use it at namespace scope, once per planner; a plugin may register several.
#define CAMPO_REGISTER_PLANNER(name, description, factory)                                             \
  namespace {                                                                                           \
  const ::campo::plugin_detail::PlannerRegistrar CAMPO_PLUGIN_CONCAT(campo_planner_registrar_, __LINE__){ \
      name, description, factory};                                                                      \
  }                                                                                                     \
  static_assert(true, "CAMPO_REGISTER_PLANNER is used as a statement: end it with ';'")
