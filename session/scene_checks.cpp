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

void check_runnable(const Scene& scene, std::size_t vehicle_index) {
  if (scene.vehicles.empty()) throw InputError(scene.source_path, "/objects", "expected a scene with a vehicle to run");
  // One vehicle is simulated: another would be in the file, validated and
  // drawn, yet absent from the physics, and a run would go on as if it were not there.
  if (scene.vehicles.size() > 1) {
    const auto object_of = [](const VehicleDef& v) {
      const std::string& params = v.params.pointer;  // "<object>/params"
      return params.substr(0, params.rfind('/'));
    };
    std::string names;
    for (const VehicleDef& v : scene.vehicles) {
      names += (names.empty() ? "" : ", ") + ("\"" + v.alias + "\" (" + object_of(v) + ")");
    }
    throw InputError(scene.source_path, object_of(scene.vehicles[1]),
                     "expected one vehicle: campo simulates one vehicle per scene, and this scene has " +
                         std::to_string(scene.vehicles.size()) + ": " + names + "; keep the one to run");
  }
  if (vehicle_index < scene.vehicles.size() && scene.vehicles[vehicle_index].mission.empty()) {
    throw InputError(scene.source_path, "/objects",
                     "expected vehicle \"" + scene.vehicles[vehicle_index].alias + "\" to have a mission");
  }
}

}  // namespace campo
