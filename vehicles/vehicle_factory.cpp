#include "campo/vehicle_factory.hpp"
#include "vehicles/quadrotor.hpp"
#include "vehicles/rover.hpp"

namespace campo {

std::unique_ptr<Vehicle> make_vehicle(World& world, const VehicleDef& def) {
  switch (def.type) {
    case VehicleType::quadrotor:
      return std::make_unique<Quadrotor>(world, parse_quadrotor_config(def.params), def.pose);
    case VehicleType::rover:
      return std::make_unique<Rover>(world, parse_rover_config(def.params), def.pose);
  }
  throw std::logic_error("unhandled vehicle type");
}

void validate_vehicle_params(const VehicleDef& def) {
  switch (def.type) {
    case VehicleType::quadrotor:
      parse_quadrotor_config(def.params);
      return;
    case VehicleType::rover:
      parse_rover_config(def.params);
      return;
  }
}

}  // namespace campo
