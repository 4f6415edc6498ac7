#pragma once
// A quadrotor in a small inline world, flown as the episode loop flies it: the
// command re-sent at the control rate, pre_step and a world step every tick.
#include <cmath>
#include <functional>
#include <string>

#include <Eigen/Geometry>

#include "campo/world.hpp"
#include "tests/vehicles/vehicle_test_support.hpp"
#include "vehicles/quadrotor.hpp"

namespace campo::test {

struct QuadrotorFlight {
  QuadrotorFlight(const std::string& scene_json, const Eigen::Isometry3d& start, const QuadrotorConfig& config = {})
      : scene(parse(scene_json)), world(scene), quad(world, config, start) {}

  /// Flies `c` for `seconds`, calling `each` after every physics step.
  void fly(const Command& c, double seconds, const std::function<void()>& each = [] {}) {
    const double dt = scene.world.physics_step_s;
    const int control_period = static_cast<int>(std::lround(1.0 / (scene.world.control_rate_hz * dt)));
    const auto steps = static_cast<long>(std::lround(seconds / dt));
    for (long k = 0; k < steps; ++k) {
      if (k % control_period == 0) quad.command(c);
      quad.pre_step(dt);
      world.step();
      each();
    }
  }
  double t() const { return world.time_s(); }
  VehicleState s() const { return quad.state(); }

  Scene scene;
  World world;
  Quadrotor quad;
};

}  // namespace campo::test
