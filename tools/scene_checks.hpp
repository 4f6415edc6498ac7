#pragma once
/// Checks of a scene beyond scene/'s loader, shared by `campo validate` and
/// `campo sweep`: the parameters that vehicles/ and planners/ interpret.
#include "campo/scene.hpp"

namespace campo::cli {

/// Validates every vehicle's parameters and creates its planner once (which
/// checks the planner's name and parameters); throws InputError.
void check_vehicles_and_planners(const Scene& scene);

/// Checks that a run of the scene can start: its first vehicle (the one
/// `campo run` drives by default) exists and has a mission; throws InputError.
void check_runnable(const Scene& scene);

}  // namespace campo::cli
