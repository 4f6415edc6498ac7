#include "tools/scene_checks.hpp"

#include "campo/json_reader.hpp"
#include "planners/registry.hpp"
#include "vehicles/factory.hpp"

namespace campo::cli {

void check_vehicles_and_planners(const Scene& scene, std::size_t skip) {
  for (std::size_t i = 0; i < scene.vehicles.size(); ++i) {
    if (i == skip) continue;
    const VehicleDef& vehicle = scene.vehicles[i];
    validate_vehicle_params(vehicle);
    create_planner(vehicle.planner, {vehicle.type, &scene, &vehicle});
  }
}

void check_runnable(const Scene& scene, std::size_t vehicle_index) {
  if (scene.vehicles.empty()) throw InputError(scene.source_path, "/objects", "expected a scene with a vehicle to run");
  if (vehicle_index < scene.vehicles.size() && scene.vehicles[vehicle_index].mission.empty()) {
    throw InputError(scene.source_path, "/objects",
                     "expected vehicle \"" + scene.vehicles[vehicle_index].alias + "\" to have a mission");
  }
}

}  // namespace campo::cli
