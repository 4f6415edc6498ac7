#include "tools/scene_checks.hpp"

#include "campo/json_reader.hpp"
#include "planners/registry.hpp"
#include "vehicles/factory.hpp"

namespace campo::cli {

void check_vehicles_and_planners(const Scene& scene) {
  for (const VehicleDef& vehicle : scene.vehicles) {
    validate_vehicle_params(vehicle);
    create_planner(vehicle.planner, {vehicle.type, &scene, &vehicle});
  }
}

void check_runnable(const Scene& scene) {
  if (scene.vehicles.empty() || scene.vehicles.front().mission.empty()) {
    throw InputError(scene.source_path, "/objects", "expected a vehicle with a mission to run (the first vehicle)");
  }
}

}  // namespace campo::cli
