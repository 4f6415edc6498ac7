#include "campo/range_sensor.hpp"

#include <stdexcept>

#include "sensors/lidar.hpp"
#include "sensors/raycaster.hpp"

namespace campo {

namespace {

class LidarSensor final : public RangeSensor {
 public:
  LidarSensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed)
      : def_(def), caster_(scene), lidar_(def.range, world_seed) {}
  const SensorDef& def() const override { return def_; }
  void scan(const Eigen::Isometry3d& sensor_pose, double time_s, std::span<const Eigen::Isometry3d> body_poses,
            RangeScan& out) override {
    caster_.set_poses(body_poses);
    lidar_.scan(caster_, sensor_pose, time_s, out);
  }

 private:
  const SensorDef& def_;
  RayCaster caster_;
  Lidar lidar_;
};

}  // namespace

std::unique_ptr<RangeSensor> make_lidar_sensor(const Scene& scene, const SensorDef& def, std::uint64_t world_seed) {
  if (def.range.kind != RangeSensorKind::lidar) {
    throw std::invalid_argument("sensor " + def.alias + ": a " + std::string(to_string(def.range.kind)) +
                                " is built by render/ (make_range_sensor)");
  }
  return std::make_unique<LidarSensor>(scene, def, world_seed);
}

}  // namespace campo
