#pragma once
/// Building vehicles from scene definitions: the VehicleFactory (episode.hpp)
/// that a program embedding campo passes to Episode or run_episode.
/// Implemented in vehicles/.
#include <memory>

#include "campo/scene.hpp"
#include "campo/vehicle.hpp"
#include "campo/world.hpp"

namespace campo {

/// Builds the vehicle of `def` in `world` at its start pose, with its
/// parameters from the preset overridden by def.params (validated strictly;
/// InputError naming def.params.pointer).
std::unique_ptr<Vehicle> make_vehicle(World& world, const VehicleDef& def);

/// Validates def.params without building anything (for `campo validate`).
void validate_vehicle_params(const VehicleDef& def);

}  // namespace campo
