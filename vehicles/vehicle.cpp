#include "campo/vehicle.hpp"

#include <cmath>
#include <iterator>

namespace campo {

double VehicleState::yaw_rad() const {
  const Eigen::Vector3d x = orientation * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

VehicleState estimated(const VehicleState& truth, const StateError& error) {
  VehicleState s = truth;
  s.position_m += error.position_m;
  s.linear_velocity_mps += error.velocity_mps;
  if (error.heading_rad != 0.0) {
    s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(error.heading_rad, Eigen::Vector3d::UnitZ())) * s.orientation;
  }
  return s;
}

Eigen::Isometry3d VehicleState::pose() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = orientation.toRotationMatrix();
  t.translation() = position_m;
  return t;
}

std::string_view command_name(const Command& c) {
  static constexpr std::string_view kNames[] = {"hold",     "go_to",           "face",   "altitude", "twist",
                                                "velocity", "attitude_thrust", "rotors", "wheels"};
  static_assert(std::size(kNames) == std::variant_size_v<Command>);
  return kNames[c.index()];
}

}  // namespace campo
