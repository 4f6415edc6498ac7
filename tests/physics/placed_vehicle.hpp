#pragma once
// The first vehicle of a scene, placed in its world (no step taken): the
// physics tests measure clearance and contacts on it.
#include <memory>

#include "campo/scene.hpp"
#include "campo/vehicle.hpp"
#include "campo/vehicle_factory.hpp"
#include "campo/world.hpp"

namespace campo::test {

struct PlacedVehicle {
  explicit PlacedVehicle(Scene scene_in)
      : scene(std::move(scene_in)), world(scene), vehicle(make_vehicle(world, scene.vehicles.front())) {}
  Scene scene;
  World world;
  std::unique_ptr<Vehicle> vehicle;
};

}  // namespace campo::test
