// The quadrotor in wind: its drag acts on the airspeed (velocity - World::wind_mps), the
// controller is not told the wind. Expected values are worked out here from the drag model
// and the controller's gains, independently of the simulation.
#include "vehicles/quadrotor.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "tests/vehicles/quadrotor_flight.hpp"
#include "tests/vehicles/vehicle_test_support.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using test::at;
using test::parse;

using namespace campo::test_units;

// A ground plane and the world block given.
std::string scene_with_world(const std::string& world) {
  return R"j({"world": )j" + world + R"j(, "objects": [{"alias": "ground", "type": "plane"}]})j";
}

// A quadrotor flight starting 5 m up unless told otherwise.
struct WindFlight : test::QuadrotorFlight {
  explicit WindFlight(const std::string& scene_json, const Eigen::Isometry3d& start = at({0.0, 0.0, 5.0}),
                  const QuadrotorConfig& config = {})
      : QuadrotorFlight(scene_json, start, config) {}
  double g() const { return -scene.world.gravity_mps2.z(); }
  // The angle between body z and world z, radians.
  double tilt() const { return std::acos(std::clamp((s().orientation * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0)); }
};

// The linearised closed loop about hover along one horizontal axis, independent of the
// controller's code: position P (kp_p, target 0), velocity PI (kp_v, ki_v with the integral
// clamp), the commanded acceleration realised through the attitude loop's first-order lag
// (time constant 1 / attitude kp), and the drag -c/m (v - w(t)). Integrated with RK4.
struct LinearLoop {
  double kp_p, kp_v, ki_v, integral_limit, lag_s, drag_per_s;
  std::function<double(double)> wind;

  // The largest |x| over [0, t_end] and x at t_end.
  std::pair<double, double> fly(double t_end) const {
    // State: x, v, integral I, realised acceleration a.
    using S = std::array<double, 4>;
    const auto derivative = [&](double t, const S& s) {
      const double e_v = -kp_p * s[0] - s[1];
      const double a_cmd = kp_v * e_v + s[2];
      double di = ki_v * e_v;
      if ((s[2] >= integral_limit && di > 0) || (s[2] <= -integral_limit && di < 0)) di = 0.0;
      return S{s[1], s[3] - drag_per_s * (s[1] - wind(t)), di, (a_cmd - s[3]) / lag_s};
    };
    S s{0, 0, 0, 0};
    double t = 0.0, worst = 0.0;
    const double h = 1e-3;
    while (t < t_end - 1e-12) {
      const S k1 = derivative(t, s);
      S m;
      for (int i = 0; i < 4; ++i) m[i] = s[i] + h / 2 * k1[i];
      const S k2 = derivative(t + h / 2, m);
      for (int i = 0; i < 4; ++i) m[i] = s[i] + h / 2 * k2[i];
      const S k3 = derivative(t + h / 2, m);
      for (int i = 0; i < 4; ++i) m[i] = s[i] + h * k3[i];
      const S k4 = derivative(t + h, m);
      for (int i = 0; i < 4; ++i) s[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
      t += h;
      worst = std::max(worst, std::abs(s[0]));
    }
    return {worst, s[0]};
  }
};

// Hovering in a steady wind w (horizontal, the vehicle at rest), the rotor drag pushes
// downwind with c w; at equilibrium the thrust carries the weight and cancels the drag, so
// body z leans upwind by atan(c w / (m g)). The horizontal velocity loop's integral (limit
// 1 m/s²) takes the drag's c w / m = 0.2 w m/s² below w = 5 m/s, so the hold error ends at 0.
TEST(QuadrotorWind, SteadyWindTiltsByTheDragAngleAndThePositionHolds) {
  const double speed = 3.0;
  const double direction = 30.0 * kPi / 180.0;
  WindFlight f(scene_with_world(R"j({"wind": {"speed_mps": 3, "direction_deg": 30}})j"));
  const QuadrotorConfig& c = f.quad.config();
  const double drag_n = c.linear_drag_n_per_mps * speed;
  const double expected_tilt = std::atan(drag_n / (c.mass_kg * f.g()));  // 3.50 degrees
  const Eigen::Vector3d target(0.0, 0.0, 5.0);
  double worst_m = 0.0;
  f.fly(command::Hold{target, 0.0}, 60.0, [&] { worst_m = std::max(worst_m, (f.s().position_m - target).norm()); });

  EXPECT_NEAR(f.tilt(), expected_tilt, 0.002 * expected_tilt);
  // Leaning into the wind: body z's horizontal part points upwind.
  const Eigen::Vector3d z_body = f.s().orientation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector2d upwind(-std::cos(direction), -std::sin(direction));
  EXPECT_NEAR(z_body.head<2>().normalized().dot(upwind), 1.0, 1e-6);
  // The hold: back on target once the integral has the drag (slowest pole of the linear
  // loop 0.16 /s, 60 s = 9.6 time constants), and on the way never farther than the linear
  // loop's transient under the wind switched on at t = 0, within 5 % (as for the gust below;
  // 0.196 m against 0.199 m when written).
  const QuadrotorControllerConfig& k = c.controller;
  const LinearLoop loop{k.position.kp, k.velocity_xy.kp, k.velocity_xy.ki, k.velocity_xy.integral_limit,
                        1.0 / k.attitude_rp.kp, c.linear_drag_n_per_mps / c.mass_kg, [&](double) { return speed; }};
  const double predicted_worst_m = loop.fly(60.0).first;
  EXPECT_LT((f.s().position_m - target).norm(), 1e-3);
  EXPECT_NEAR(worst_m, predicted_worst_m, 0.05 * predicted_worst_m);
  RecordProperty("worst_hold_error_m", std::to_string(worst_m));
  RecordProperty("predicted_worst_hold_error_m", std::to_string(predicted_worst_m));
  RecordProperty("tilt_deg", std::to_string(f.tilt() * 180.0 / kPi));
}

// Beyond 5 m/s the velocity integral saturates at 1 m/s² and the rest of the drag must come
// from the proportional terms: at w = 8 the drag wants 1.6 m/s², the velocity loop's kp = 2.5
// gives the remaining 0.6 with a velocity error 0.24 m/s, which the position loop (kp = 1,
// P only) commands from a position error of 0.24 m, downwind. The tilt is the drag angle still.
TEST(QuadrotorWind, StrongWindLeavesTheOffsetTheSaturatedIntegralPredicts) {
  const double speed = 8.0;
  WindFlight f(scene_with_world(R"j({"wind": {"speed_mps": 8, "direction_deg": -90}})j"));
  const QuadrotorConfig& c = f.quad.config();
  const QuadrotorControllerConfig& k = c.controller;
  const double drag_accel = c.linear_drag_n_per_mps * speed / c.mass_kg;
  const double velocity_error = (drag_accel - k.velocity_xy.integral_limit) / k.velocity_xy.kp;
  const double offset = velocity_error / k.position.kp;
  ASSERT_GT(drag_accel, k.velocity_xy.integral_limit);
  const Eigen::Vector3d target(0.0, 0.0, 5.0);
  f.fly(command::Hold{target, 0.0}, 40.0);
  const Eigen::Vector3d error = f.s().position_m - target;
  EXPECT_NEAR(error.y(), -offset, 2e-3);  // downwind is -y
  EXPECT_NEAR(error.x(), 0.0, 1e-3);
  EXPECT_NEAR(error.z(), 0.0, 1e-3);
  EXPECT_NEAR(f.tilt(), std::atan(drag_accel / f.g()), 0.002 * std::atan(drag_accel / f.g()));
  RecordProperty("offset_m", std::to_string(-error.y()));
}

// Quadratic body drag with the same C_d A on every axis: the force -1/2 rho C_d A |v| v does
// not depend on the attitude, and the tilt is atan(1/2 rho C_d A w^2 / (m g)).
TEST(QuadrotorWind, QuadraticDragTiltsByItsAngle) {
  QuadrotorConfig config;
  config.linear_drag_n_per_mps = 0.0;
  config.drag_area_m2 = {0.05, 0.05, 0.05};
  const double speed = 6.0;
  WindFlight f(scene_with_world(R"j({"wind": {"speed_mps": 6, "direction_deg": 135}})j"), at({0.0, 0.0, 5.0}), config);
  const double drag_n = 0.5 * config.air_density_kgpm3 * 0.05 * speed * speed;  // 1.10 N
  f.fly(command::Hold{{0.0, 0.0, 5.0}, 0.0}, 60.0);
  const double expected = std::atan(drag_n / (config.mass_kg * f.g()));
  EXPECT_NEAR(f.tilt(), expected, 0.002 * expected);
  EXPECT_LT((f.s().position_m - Eigen::Vector3d(0.0, 0.0, 5.0)).norm(), 1e-3);
}

// Quadratic drag is per body axis: C_d A on body y alone. Heading 90 degrees, body y points
// along world -x, into a wind toward +x: the drag is along body y, of size D cos(theta) with
// D = 1/2 rho A w^2 as the body leans by theta (|v| = w, v_y = w cos(theta)). With the thrust
// T along body z the balance is T sin(theta) = D cos^2(theta) across and T cos(theta) +
// D cos(theta) sin(theta) = m g up (the tilted axis's drag lifts a little): together
// tan(theta) = D / (m g). Heading 0, the same wind is along body x, which has no drag: the
// quadrotor neither leans nor moves (a drag taken in world axes would fail both).
TEST(QuadrotorWind, QuadraticDragActsAlongTheBodyAxes) {
  QuadrotorConfig config;
  config.linear_drag_n_per_mps = 0.0;
  config.drag_area_m2 = {0.0, 0.05, 0.0};
  const std::string scene = scene_with_world(R"j({"wind": {"speed_mps": 6, "direction_deg": 0}})j");
  const double drag_n = 0.5 * config.air_density_kgpm3 * 0.05 * 6.0 * 6.0;
  {
    WindFlight f(scene, at({0.0, 0.0, 5.0}, kPi / 2), config);
    f.fly(command::Hold{{0.0, 0.0, 5.0}, kPi / 2}, 60.0);
    const double expected = std::atan(drag_n / (config.mass_kg * f.g()));
    EXPECT_NEAR(f.tilt(), expected, 0.002 * expected);
    EXPECT_LT((f.s().orientation * Eigen::Vector3d::UnitZ()).x(), 0.0);  // leaning upwind, toward -x
  }
  {
    WindFlight f(scene, at({0.0, 0.0, 5.0}, 0.0), config);
    double worst_m = 0.0;
    f.fly(command::Hold{{0.0, 0.0, 5.0}, 0.0}, 10.0,
          [&] { worst_m = std::max(worst_m, (f.s().position_m - Eigen::Vector3d(0.0, 0.0, 5.0)).norm()); });
    EXPECT_LT(f.tilt(), 1e-6);
    EXPECT_LT(worst_m, 1e-6);
  }
}

// With the controller off (the rotors held at hover speed: thrust m g along body z, no
// torque), a 1-cos gust along x moves the free body by m x'' = -c (x' - w(t)): integrated
// here with RK4 on a fine step, and in the end by the gust's integral A D / 2 (the drag's
// low-pass filter has unit gain at zero frequency), whatever the drag coefficient.
TEST(QuadrotorWind, GustDisplacesTheFreeBodyByTheIntegratedDrag) {
  const double amplitude = 3.0;
  const double start = 1.0;
  const double duration = 2.0;
  WindFlight f(scene_with_world(R"j({"wind": {"gust": "one_minus_cos", "gust_amplitude_mps": [3, 0, 0],
      "gust_start_s": 1, "gust_duration_s": 2}})j"));
  const QuadrotorConfig& c = f.quad.config();
  const double hover = hover_rotor_speed(model_of(c, f.scene.world.gravity_mps2));
  const double k = c.linear_drag_n_per_mps / c.mass_kg;

  // The reference: x'' = -k (x' - w(t)), RK4 at 0.1 ms.
  const auto gust = [&](double t) {
    const double p = (t - start) / duration;
    return p < 0.0 || p > 1.0 ? 0.0 : amplitude * 0.5 * (1.0 - std::cos(2.0 * kPi * p));
  };
  const auto reference_at = [&](double t_end) {
    double x = 0.0, v = 0.0, t = 0.0;
    const double h = 1e-4;
    const auto accel = [&](double tt, double vv) { return -k * (vv - gust(tt)); };
    while (t < t_end - 1e-12) {
      const double k1v = accel(t, v), k1x = v;
      const double k2v = accel(t + h / 2, v + h / 2 * k1v), k2x = v + h / 2 * k1v;
      const double k3v = accel(t + h / 2, v + h / 2 * k2v), k3x = v + h / 2 * k2v;
      const double k4v = accel(t + h, v + h * k3v), k4x = v + h * k3v;
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t += h;
    }
    return x;
  };

  const command::Rotors rotors{{hover, hover, hover, hover}};
  for (const double t_check : {2.0, 3.0, 5.0, 10.0, 50.0}) {
    f.fly(rotors, t_check - f.t());
    const Eigen::Vector3d p = f.s().position_m;
    // Bullet's step holds the force of the step's start for 1/240 s: a first-order error of
    // about the gust's speed times half a step, well under 5 mm.
    EXPECT_NEAR(p.x(), reference_at(t_check), 5e-3) << "at " << t_check << " s";
    EXPECT_NEAR(p.y(), 0.0, 1e-6);  // the rotors' positions are symmetric to rounding only
    EXPECT_NEAR(p.z(), 5.0, 1e-6);
  }
  // 50 s is 9.4 drag time constants (m / c = 5 s) after the gust: the integral A D / 2 but
  // for the last e^-9.4 of the motion.
  EXPECT_NEAR(f.s().position_m.x(), amplitude * duration / 2.0, 5e-3);
  EXPECT_NEAR(reference_at(50.0), amplitude * duration / 2.0, 5e-4);
}

// A 1-cos gust of 4 m/s along +y for 3 s against the hovering quadrotor under its controller:
// it is pushed downwind and comes back. The peak displacement is the linear loop's within 5 %
// (0.226 m against 0.228 m when written; the linearisation leaves out that the attitude loop is
// more than a first-order lag, the rate loop and the motor lag); nothing moves across the gust.
TEST(QuadrotorWind, GustDisplacesTheHoveringQuadrotorAsTheLinearLoopPredicts) {
  const double amplitude = 4.0;
  WindFlight f(scene_with_world(R"j({"wind": {"gust": "one_minus_cos", "gust_amplitude_mps": [0, 4, 0],
      "gust_start_s": 2, "gust_duration_s": 3}})j"));
  const QuadrotorConfig& c = f.quad.config();
  const QuadrotorControllerConfig& k = c.controller;
  const LinearLoop loop{k.position.kp, k.velocity_xy.kp, k.velocity_xy.ki, k.velocity_xy.integral_limit,
                        1.0 / k.attitude_rp.kp, c.linear_drag_n_per_mps / c.mass_kg, [&](double t) {
                          const double p = (t - 2.0) / 3.0;
                          return p < 0.0 || p > 1.0 ? 0.0 : amplitude * 0.5 * (1.0 - std::cos(2.0 * kPi * p));
                        }};
  const auto [predicted_peak, predicted_end] = loop.fly(40.0);
  const Eigen::Vector3d target(0.0, 0.0, 5.0);
  double peak = 0.0;
  double peak_x = 0.0;
  f.fly(command::Hold{target, 0.0}, 40.0, [&] {
    peak = std::max(peak, f.s().position_m.y() - target.y());
    peak_x = std::max(peak_x, std::abs(f.s().position_m.x()));
  });
  EXPECT_NEAR(peak, predicted_peak, 0.05 * predicted_peak);
  EXPECT_LT(peak_x, 1e-6);  // nothing across the gust
  EXPECT_NEAR(f.s().position_m.y(), predicted_end, 5e-3);
  RecordProperty("peak_m", std::to_string(peak));
  RecordProperty("predicted_peak_m", std::to_string(predicted_peak));
}

// Determinism: Dryden turbulence from the same seeds flies the same to the bit; another wind
// seed flies otherwise.
TEST(QuadrotorWind, TurbulentFlightIsDeterministicPerSeed) {
  const auto final_state = [](int wind_seed) {
    WindFlight f(scene_with_world(R"j({"seed": 5, "wind": {"speed_mps": 4, "direction_deg": 60, "gust": "dryden",
        "turbulence_intensity_mps": 1.5, "turbulence_length_m": 30, "seed": )j" +
                              std::to_string(wind_seed) + "}}"));
    f.fly(command::Hold{{0.0, 0.0, 5.0}, 0.0}, 8.0);
    return f.s();
  };
  const VehicleState a = final_state(1);
  const VehicleState b = final_state(1);
  const VehicleState other = final_state(2);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.position_m(i)), std::bit_cast<std::uint64_t>(b.position_m(i)));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.linear_velocity_mps(i)),
              std::bit_cast<std::uint64_t>(b.linear_velocity_mps(i)));
  }
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_NE(a.position_m, other.position_m);
  // Turbulence of 1.5 m/s moves it, but it holds: within 0.5 m.
  EXPECT_GT((a.position_m - Eigen::Vector3d(0.0, 0.0, 5.0)).norm(), 1e-3);
  EXPECT_LT((a.position_m - Eigen::Vector3d(0.0, 0.0, 5.0)).norm(), 0.5);
}

}  // namespace
}  // namespace campo
