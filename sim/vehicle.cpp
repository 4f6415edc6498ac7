#include "sim/vehicle.hpp"

#include <cmath>

namespace campo {

double VehicleState::yaw_rad() const {
  const Eigen::Vector3d x = orientation * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

Eigen::Isometry3d VehicleState::pose() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = orientation.toRotationMatrix();
  t.translation() = position_m;
  return t;
}

std::string_view command_name(const Command& c) {
  static constexpr std::string_view kNames[] = {"hold", "go_to", "face", "altitude", "twist"};
  return kNames[c.index()];
}

}  // namespace campo
