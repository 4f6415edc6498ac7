#pragma once
/// Checks of a scene beyond scene/'s loader, shared by `campo validate`,
/// `campo run` and `campo sweep` (so that each refuses what the others
/// refuse): the parameters that vehicles/ and planners/ interpret, and
/// whether a run can start.
#include <cstddef>
#include <limits>

#include "campo/scene.hpp"
#include "campo/scene_loader.hpp"

namespace campo {

/// Validates every vehicle's parameters but vehicle `skip`'s and creates its
/// planner once (which checks the planner's name and parameters); throws InputError.
void check_vehicles_and_planners(const Scene& scene, std::size_t skip = std::numeric_limits<std::size_t>::max());

/// What check_vehicles_and_planners checks of each vehicle's parameter blocks
/// alone (the planner's name and parameters, the vehicle's parameters), for
/// the loader to run on each vehicle as it reads it: their errors then come
/// with the scene's others, in one list. What needs the whole scene (a
/// planner's limits on its mission) is checked by check_vehicles_and_planners
/// once the scene loads.
SceneChecks parameter_checks();

/// Checks that a run of the scene can start: it has a vehicle, and every
/// vehicle (all run together) has a mission; throws InputError with `campo
/// run`'s message.
void check_runnable(const Scene& scene);

}  // namespace campo
