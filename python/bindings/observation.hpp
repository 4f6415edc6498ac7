#pragma once
/// What Python sees of an observation (campo.Observation): a snapshot of the
/// light parts (time, state) and shared views of the heavy ones (each
/// sensor's scan buffer, the mission), so a step costs no copy of a scan.
#include <memory>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "campo/planner.hpp"

namespace campo::python {

/// One sensor's latest reading.
struct SensorView {
  std::string alias;
  std::shared_ptr<const RangeScan> scan;  ///< the sensor's buffer; null before the first scan
  double min_range_m = 0.0;               ///< for the normalised depth map
  double max_range_m = 0.0;
  bool fresh = false;
};

/// One colour camera's latest image.
struct ImageView {
  std::string alias;
  std::shared_ptr<const RgbImage> image;  ///< the camera's buffer; null before the first image
  bool fresh = false;
};

/// One IMU's latest sample, copied (six numbers).
struct ImuView {
  std::string alias;
  double time_s = 0.0;
  Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();
  bool valid = false;
  bool fresh = false;
};

struct ObservationView {
  double time_s = 0.0;
  VehicleType vehicle = VehicleType::quadrotor;
  VehicleState state;  ///< as the planner is told it (estimated when the scene has state noise)
  bool stable = false;
  std::vector<SensorView> sensors;
  std::vector<ImageView> images;
  std::vector<ImuView> imus;
  std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_m;  ///< the mission's waypoints, world frame
};

/// The view of `observation`; `mission_m` is the mission's waypoints, made once per run.
ObservationView view_of(const Observation& observation, std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_m);

/// The mission's waypoint positions.
std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_positions(std::span<const Waypoint> mission);

/// Binds campo.State, campo.SensorReading and campo.Observation.
void bind_observation(pybind11::module_& m);

}  // namespace campo::python
