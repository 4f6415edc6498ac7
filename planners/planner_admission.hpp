#pragma once
/// How the registry admits the planners of one source, shared by the
/// registry (planner_registry.cpp) and the plugin loader (plugin.cpp).
#include <string>
#include <vector>

#include "campo/plugin.hpp"

namespace campo {

/// Checks the planners of one source (a plugin's path with its SHA-256, or a
/// program embedding campo with an empty one) against each other and every
/// planner registered so far, and adds them: the problem ("" when they were
/// added; none is added otherwise), to follow the source's name in a message.
std::string admit_planners(const std::vector<PlannerRegistration>& planners, const std::string& source,
                           const std::string& sha256);

}  // namespace campo
