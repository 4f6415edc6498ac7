#pragma once
/// The IMU samples of a run and their files: imu.csv (one vehicle) or
/// imu_<alias>.csv (several), one row per sample of each of the vehicle's
/// IMUs, in the IMU's frame.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "campo/episode.hpp"
#include "campo/planner.hpp"
#include "campo/scene.hpp"

namespace campo {

/// One sample of one IMU of a vehicle.
struct RecordedImuSample {
  std::size_t imu = 0;  ///< index in VehicleDef::imus
  double time_s = 0.0;
  Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();
};

/// Every vehicle's IMU samples, in time order.
class ImuRecorder {
 public:
  explicit ImuRecorder(std::size_t vehicles) : samples_(vehicles) {}
  /// Keeps one sample of IMU `imu` of vehicle `vehicle` (EpisodeOptions::on_imu: every sample).
  void record(std::size_t vehicle, std::size_t imu, const ImuReading& reading);
  std::vector<std::vector<RecordedImuSample>>& samples() { return samples_; }

 private:
  std::vector<std::vector<RecordedImuSample>> samples_;
};

/// The header "time_s,alias,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps", then one
/// row per sample of `vehicle`'s IMUs (named by their aliases).
std::string imu_csv(const VehicleDef& vehicle, const std::vector<RecordedImuSample>& samples);

/// The name of vehicle `vehicle`'s IMU file in the run directory: imu.csv with one
/// vehicle, imu_<alias>.csv with several (as trajectory_file).
std::string imu_file(const EpisodeResult& result, std::size_t vehicle);

}  // namespace campo
