#include "session/scene_checks.hpp"

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {

void check_vehicles_and_planners(const Scene& scene, std::size_t skip) {
  for (std::size_t i = 0; i < scene.vehicles.size(); ++i) {
    if (i == skip) continue;
    const VehicleDef& vehicle = scene.vehicles[i];
    validate_vehicle_params(vehicle);
    create_planner(vehicle.planner, {vehicle.type, &scene, &vehicle});
  }
}

SceneChecks parameter_checks() {
  SceneChecks checks;
  checks.vehicle_params = [](const VehicleDef& vehicle) { validate_vehicle_params(vehicle); };
  // No scene and no vehicle in the context: the planner checks its parameters alone.
  checks.planner = [](const VehicleDef& vehicle) { create_planner(vehicle.planner, {vehicle.type, nullptr, nullptr}); };
  return checks;
}

void check_runnable(const Scene& scene) {
  if (scene.vehicles.empty()) throw InputError(scene.source_path, "/objects", "expected a scene with a vehicle to run");
  // Every vehicle runs, each on its own mission.
  for (const VehicleDef& v : scene.vehicles) {
    const std::string& params = v.params.pointer;  // "<object>/params"
    const std::string object = params.substr(0, params.rfind('/'));
    if (v.mission.empty()) throw InputError(scene.source_path, object, "expected vehicle \"" + v.alias + "\" to have a mission");
    // Sweeps and tables name a vehicle's metrics "<alias>.<metric>".
    if (scene.vehicles.size() > 1 && v.alias.find('.') != std::string::npos) {
      throw InputError(scene.source_path, object + "/alias",
                       "expected a vehicle alias without '.' in a scene of several vehicles (their metrics are "
                       "named <alias>.<metric>), got \"" + v.alias + "\"");
    }
  }
}

}  // namespace campo
