#include "physics/wind.hpp"

#include <bit>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "campo/world.hpp"
#include "scene/world_config.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;

Scene wind_scene(const std::string& text) {
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

// The 1-cos shape against its formula written out, its zero ends and slope, peak and integral.
TEST(Wind, OneMinusCosGustHasItsShapePeakAndIntegral) {
  const double start = 3.0;
  const double duration = 2.0;
  EXPECT_EQ(one_minus_cos_shape(start - 1e-9, start, duration), 0.0);
  EXPECT_EQ(one_minus_cos_shape(start + duration + 1e-9, start, duration), 0.0);
  EXPECT_NEAR(one_minus_cos_shape(start, start, duration), 0.0, 1e-15);
  EXPECT_NEAR(one_minus_cos_shape(start + duration, start, duration), 0.0, 1e-15);
  EXPECT_NEAR(one_minus_cos_shape(start + 0.5 * duration, start, duration), 1.0, 1e-15);
  // A quarter in: (1 - cos(pi/2)) / 2 = 1/2; an eighth: (1 - sqrt(2)/2) / 2.
  EXPECT_NEAR(one_minus_cos_shape(start + 0.25 * duration, start, duration), 0.5, 1e-15);
  EXPECT_NEAR(one_minus_cos_shape(start + 0.125 * duration, start, duration), 0.5 * (1.0 - std::sqrt(0.5)), 1e-15);
  // Symmetric about mid-gust.
  for (const double f : {0.1, 0.2, 0.3, 0.4}) {
    EXPECT_NEAR(one_minus_cos_shape(start + f * duration, start, duration),
                one_minus_cos_shape(start + (1.0 - f) * duration, start, duration), 1e-14);
  }
  // Zero slope at the ends: the first 1 % of the gust rises by (1 - cos(0.02 pi)) / 2 = 9.87e-4 only.
  EXPECT_NEAR(one_minus_cos_shape(start + 0.01 * duration, start, duration), 0.5 * (1.0 - std::cos(0.02 * kPi)),
              1e-15);
  EXPECT_LT(one_minus_cos_shape(start + 0.01 * duration, start, duration), 1e-3);
  // Integral over the gust: duration / 2 (midpoint rule, 20000 panels).
  const int n = 20000;
  double integral = 0.0;
  for (int i = 0; i < n; ++i) {
    integral += one_minus_cos_shape(start + (i + 0.5) * duration / n, start, duration) * duration / n;
  }
  EXPECT_NEAR(integral, 0.5 * duration, 1e-8);
}

TEST(Wind, GustVelocityIsTheAmplitudeTimesTheShapeOnlyForOneMinusCos) {
  WindConfig wind;
  wind.gust = GustModel::one_minus_cos;
  wind.gust_amplitude_mps = {3.0, -1.0, 0.5};
  wind.gust_start_s = 1.0;
  wind.gust_duration_s = 4.0;
  EXPECT_TRUE(one_minus_cos_gust_mps(wind, 3.0).isApprox(Eigen::Vector3d(3.0, -1.0, 0.5), 1e-15));
  EXPECT_TRUE(one_minus_cos_gust_mps(wind, 2.0).isApprox(Eigen::Vector3d(1.5, -0.5, 0.25), 1e-15));
  EXPECT_EQ(one_minus_cos_gust_mps(wind, 5.5), Eigen::Vector3d::Zero());
  wind.gust = GustModel::dryden;
  EXPECT_EQ(one_minus_cos_gust_mps(wind, 3.0), Eigen::Vector3d::Zero());
}

// direction_deg is where the wind blows toward, counter-clockwise from +x.
TEST(Wind, SteadyVectorAndAxesFollowTheDirection) {
  WindConfig wind;
  wind.speed_mps = 4.0;
  wind.direction_deg = 90.0;
  wind.vertical_mps = -0.5;
  EXPECT_NEAR((wind.steady_velocity_mps() - Eigen::Vector3d(0.0, 4.0, -0.5)).norm(), 0.0, 1e-15);
  wind.direction_deg = 210.0;
  EXPECT_NEAR((wind.steady_velocity_mps() - Eigen::Vector3d(-2.0 * std::sqrt(3.0), -2.0, -0.5)).norm(), 0.0, 1e-14);
  const auto axes = turbulence_axes(wind);
  EXPECT_NEAR((axes[0] - Eigen::Vector3d(-std::sqrt(3.0) / 2, -0.5, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(axes[0].dot(axes[1]), 0.0, 1e-15);
  EXPECT_NEAR((axes[0].cross(axes[1]) - axes[2]).norm(), 0.0, 1e-15);  // right-handed, v to the left of u
  // The turbulence's advection speed: the steady wind's magnitude, at least the floor.
  EXPECT_DOUBLE_EQ(turbulence_reference_speed_mps(wind), std::sqrt(16.0 + 0.25));
  wind.speed_mps = 0.0;
  wind.vertical_mps = 0.0;
  EXPECT_EQ(turbulence_reference_speed_mps(wind), kMinTurbulenceAdvectionSpeed_mps);
}

// Samples of each component of a Dryden stream at a step.
struct DrydenSamples {
  std::vector<double> u, v, w;
};

DrydenSamples sample(double sigma, double length, double speed, double step, std::uint64_t seed, std::size_t n) {
  DrydenTurbulence t(sigma, length, speed, step, seed);
  DrydenSamples s;
  s.u.reserve(n);
  s.v.reserve(n);
  s.w.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d x = t.velocity_mps();
    s.u.push_back(x.x());
    s.v.push_back(x.y());
    s.w.push_back(x.z());
    t.advance();
  }
  return s;
}

double mean(const std::vector<double>& x) {
  double m = 0.0;
  for (const double v : x) m += v;
  return m / static_cast<double>(x.size());
}

// The sample autocovariance at `lag` samples (zero mean known).
double autocovariance(const std::vector<double>& x, std::size_t lag) {
  double c = 0.0;
  for (std::size_t k = 0; k + lag < x.size(); ++k) c += x[k] * x[k + lag];
  return c / static_cast<double>(x.size() - lag);
}

// The continuous Dryden correlations (MIL-F-8785C), normalised, at lag tau for time constant T.
double longitudinal_correlation(double tau, double T) { return std::exp(-tau / T); }
double lateral_correlation(double tau, double T) { return (1.0 - tau / (2.0 * T)) * std::exp(-tau / T); }

// Long runs against the continuous process's statistics: variance sigma^2, the correlation
// functions of the spectra at several lags (the lateral one crosses zero at tau = 2T), and
// the longitudinal integral time scale T = L / V. The filters are discretised exactly, so a
// step of T / 4 has the same statistics as a small one; N = 400000 samples span 10^5 T, so
// the variance's relative sampling error is about sqrt(2 T / (N h)) = 0.45 % (u; the integral
// of its squared correlation is T), the correlations' about as small: 4 % and 0.02 are wide.
TEST(Wind, DrydenMatchesItsVarianceAndCorrelations) {
  const double sigma = 1.7;
  const double length = 40.0;
  const double speed = 8.0;
  const double T = length / speed;  // 5 s
  for (const double step : {T / 4.0, T / 40.0}) {
    SCOPED_TRACE("step " + std::to_string(step));
    const std::size_t n = step > T / 10.0 ? 400000 : 2000000;
    const DrydenSamples s = sample(sigma, length, speed, step, 42, n);
    for (const auto* x : {&s.u, &s.v, &s.w}) {
      EXPECT_NEAR(mean(*x), 0.0, 0.03 * sigma);
      EXPECT_NEAR(autocovariance(*x, 0) / (sigma * sigma), 1.0, 0.04);
    }
    for (const double tau : {T / 4.0, T, 2.0 * T, 3.0 * T}) {
      const auto lag = static_cast<std::size_t>(std::lround(tau / step));
      const double c0u = autocovariance(s.u, 0);
      EXPECT_NEAR(autocovariance(s.u, lag) / c0u, longitudinal_correlation(tau, T), 0.02) << "u at " << tau;
      for (const auto* x : {&s.v, &s.w}) {
        EXPECT_NEAR(autocovariance(*x, lag) / autocovariance(*x, 0), lateral_correlation(tau, T), 0.02)
            << "v/w at " << tau;
      }
    }
    // The integral time scale of u (its correlation integrated to 8 T, where exp(-8) is left): T.
    if (step < T / 10.0) {
      const double c0 = autocovariance(s.u, 0);
      double integral = 0.5 * step;  // trapezoid: half the lag-0 panel
      const auto lags = static_cast<std::size_t>(8.0 * T / step);
      for (std::size_t lag = 1; lag <= lags; ++lag) integral += autocovariance(s.u, lag) / c0 * step;
      EXPECT_NEAR(integral * speed, length * (1.0 - std::exp(-8.0)), 0.08 * length);
    }
  }
}

// The exact discretisation at a physics step much shorter than T (1/240 s against 50 s,
// where the direct form of the step's noise covariance cancels catastrophically): one
// sample's variance is still sigma^2, by the ensemble of many independent streams.
TEST(Wind, DrydenKeepsItsVarianceAtAShortStep) {
  const double sigma = 2.0;
  double su = 0.0, sv = 0.0, sw = 0.0;
  const int streams = 4000;
  for (int k = 0; k < streams; ++k) {
    DrydenTurbulence t(sigma, 50.0, 1.0, 1.0 / 240.0, static_cast<std::uint64_t>(k));
    for (int i = 0; i < 2400; ++i) t.advance();  // 10 s on
    const Eigen::Vector3d x = t.velocity_mps();
    su += x.x() * x.x();
    sv += x.y() * x.y();
    sw += x.z() * x.z();
  }
  // 4000 independent samples: the variance's relative error is sqrt(2/4000) = 2.2 %.
  for (const double s : {su, sv, sw}) EXPECT_NEAR(s / streams / (sigma * sigma), 1.0, 0.1);
}

TEST(Wind, DrydenIsDeterministicPerSeed) {
  const DrydenSamples a = sample(1.0, 30.0, 5.0, 1.0 / 240.0, 7, 1000);
  const DrydenSamples b = sample(1.0, 30.0, 5.0, 1.0 / 240.0, 7, 1000);
  const DrydenSamples c = sample(1.0, 30.0, 5.0, 1.0 / 240.0, 8, 1000);
  for (std::size_t k = 0; k < a.u.size(); ++k) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a.u[k]), std::bit_cast<std::uint64_t>(b.u[k]));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a.v[k]), std::bit_cast<std::uint64_t>(b.v[k]));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a.w[k]), std::bit_cast<std::uint64_t>(b.w[k]));
  }
  EXPECT_NE(a.u.back(), c.u.back());
  EXPECT_NE(a.v.back(), c.v.back());
  // The world seed and the wind's seed both change the stream; a LIDAR's seed label does not collide.
  EXPECT_NE(turbulence_seed(0, 0), turbulence_seed(1, 0));
  EXPECT_NE(turbulence_seed(0, 0), turbulence_seed(0, 1));
  EXPECT_NE(turbulence_seed(0, 0), Rng::derive_seed(0, 0));
}

// The World: steady wind as given, a gust at the world's time, turbulence that moves with
// the steps and is the same for the same seeds.
TEST(Wind, WorldReturnsSteadyPlusGustAtItsTime) {
  const Scene scene = wind_scene(R"j({"world": {"wind": {"speed_mps": 5, "direction_deg": 180, "vertical_mps": 0.5,
      "gust": "one_minus_cos", "gust_amplitude_mps": [0, 2, 0], "gust_start_s": 0.5, "gust_duration_s": 1}},
      "objects": []})j");
  World world(scene);
  const Eigen::Vector3d steady = scene.world.wind.steady_velocity_mps();
  EXPECT_NEAR((steady - Eigen::Vector3d(-5.0, 0.0, 0.5)).norm(), 0.0, 1e-14);
  EXPECT_EQ(world.wind_mps({0, 0, 0}), steady);
  while (world.time_s() < 1.0 - 1e-12) world.step();
  EXPECT_NEAR((world.wind_mps({10, -3, 2}) - steady - Eigen::Vector3d(0, 2, 0)).norm(), 0.0, 1e-12);
  while (world.time_s() < 1.25 - 1e-12) world.step();
  EXPECT_NEAR(world.wind_mps({0, 0, 0}).y() - steady.y(), 1.0, 1e-12);  // three quarters in: half the peak
  while (world.time_s() < 2.0) world.step();
  EXPECT_EQ(world.wind_mps({0, 0, 0}), steady);
}

TEST(Wind, WorldWithoutWindHasStillAir) {
  const Scene scene = wind_scene(R"j({"objects": []})j");
  World world(scene);
  world.step();
  EXPECT_EQ(world.wind_mps({1, 2, 3}), Eigen::Vector3d::Zero());
}

TEST(Wind, WorldTurbulenceIsSeededAndMovesEachStep) {
  const auto scene_text = [](int world_seed, int wind_seed) {
    return R"j({"world": {"seed": )j" + std::to_string(world_seed) +
           R"j(, "wind": {"speed_mps": 6, "direction_deg": 30, "gust": "dryden",
           "turbulence_intensity_mps": 1.5, "turbulence_length_m": 20, "seed": )j" +
           std::to_string(wind_seed) + "}}, \"objects\": []}";
  };
  const auto history = [](const Scene& scene) {
    World world(scene);
    std::vector<Eigen::Vector3d> out;
    for (int k = 0; k < 500; ++k) {
      out.push_back(world.wind_mps({0, 0, 0}));
      world.step();
    }
    return out;
  };
  const Scene a = wind_scene(scene_text(3, 9));
  const std::vector<Eigen::Vector3d> h = history(a);
  EXPECT_EQ(h, history(a));
  EXPECT_NE(h, history(wind_scene(scene_text(4, 9))));
  EXPECT_NE(h, history(wind_scene(scene_text(3, 10))));
  EXPECT_NE(h[0], h[1]);
  // The mean over 500 steps (2 s, T = 20/6 s) is near the steady wind: within a few sigma.
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& v : h) m += v / static_cast<double>(h.size());
  EXPECT_LT((m - a.world.wind.steady_velocity_mps()).norm(), 4.0 * 1.5);
}

std::string error_of(const std::string& world) {
  try {
    wind_scene(R"j({"world": )j" + world + R"j(, "objects": []})j");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The "wind" block as the loader reads it: every field, and the errors naming the pointer.
TEST(WindBlock, IsReadWithItsFieldsAndWrittenBack) {
  const Scene scene = wind_scene(R"j({"world": {"seed": 4, "wind": {"speed_mps": 7.5, "direction_deg": -45,
      "vertical_mps": 1, "gust": "dryden", "turbulence_intensity_mps": 2, "turbulence_length_m": 120,
      "seed": 11}}, "objects": []})j");
  const WindConfig& w = scene.world.wind;
  EXPECT_EQ(w.speed_mps, 7.5);
  EXPECT_EQ(w.direction_deg, -45.0);
  EXPECT_EQ(w.vertical_mps, 1.0);
  EXPECT_EQ(w.gust, GustModel::dryden);
  EXPECT_EQ(w.turbulence_intensity_mps, 2.0);
  EXPECT_EQ(w.turbulence_length_m, 120.0);
  EXPECT_EQ(w.seed, 11u);
  // run.json writes the world from the same declaration: the wind with the fields of its gust model.
  const nlohmann::json written = world_config_fields().write(scene.world);
  EXPECT_EQ(written.at("wind").at("speed_mps"), 7.5);
  EXPECT_EQ(written.at("wind").at("gust"), "dryden");
  EXPECT_EQ(written.at("wind").at("seed"), 11);
  EXPECT_FALSE(written.at("wind").contains("gust_amplitude_mps"));
  // Without a wind block: still air, and run.json says so.
  const Scene still = wind_scene(R"j({"objects": []})j");
  EXPECT_EQ(still.world.wind.steady_velocity_mps(), Eigen::Vector3d::Zero());
  EXPECT_EQ(world_config_fields().write(still.world).at("wind").at("speed_mps"), 0.0);
}

// "velocity_mps" gives the steady wind as a vector; it is recorded as the three fields.
TEST(WindBlock, VelocityVectorIsTheSteadyWind) {
  const Scene scene = wind_scene(R"j({"world": {"wind": {"velocity_mps": [-3, 4, 0.5]}}, "objects": []})j");
  const WindConfig& w = scene.world.wind;
  EXPECT_DOUBLE_EQ(w.speed_mps, 5.0);
  EXPECT_NEAR(w.direction_deg, 180.0 - std::atan(4.0 / 3.0) * 180.0 / kPi, 1e-12);
  EXPECT_EQ(w.vertical_mps, 0.5);
  EXPECT_NEAR((w.steady_velocity_mps() - Eigen::Vector3d(-3.0, 4.0, 0.5)).norm(), 0.0, 1e-14);
  const nlohmann::json written = world_config_fields().write(scene.world).at("wind");
  EXPECT_FALSE(written.contains("velocity_mps"));
  EXPECT_EQ(written.at("speed_mps"), 5.0);
  // Read back from what run.json writes, the same wind.
  const Scene again = wind_scene(R"j({"world": {"wind": )j" + written.dump() + R"j(}, "objects": []})j");
  EXPECT_EQ(again.world.wind.steady_velocity_mps(), w.steady_velocity_mps());
}

TEST(WindBlock, BadValuesNameTheirPointer) {
  using ::testing::HasSubstr;
  EXPECT_THAT(error_of(R"j({"wind": {"speed_mps": -1}})j"), HasSubstr("inline.json: /world/wind/speed_mps:"));
  EXPECT_THAT(error_of(R"j({"wind": {"speed_mps": 101}})j"), HasSubstr("/world/wind/speed_mps:"));
  EXPECT_THAT(error_of(R"j({"wind": {"gust": "sine"}})j"), HasSubstr("/world/wind/gust: expected one of"));
  EXPECT_THAT(error_of(R"j({"wind": {"velocity": [1, 0, 0]}})j"), HasSubstr("/world/wind/velocity: unknown key"));
  // A gust model's fields belong to it.
  EXPECT_THAT(error_of(R"j({"wind": {"gust_amplitude_mps": [1, 0, 0]}})j"),
              HasSubstr("/world/wind/gust_amplitude_mps: a field of \"gust\": \"one_minus_cos\" only"));
  EXPECT_THAT(error_of(R"j({"wind": {"gust": "one_minus_cos", "turbulence_length_m": 10}})j"),
              HasSubstr("/world/wind/turbulence_length_m: a field of \"gust\": \"dryden\" only"));
  EXPECT_THAT(error_of(R"j({"wind": {"gust": "one_minus_cos", "gust_duration_s": 0}})j"),
              HasSubstr("/world/wind/gust_duration_s:"));
  EXPECT_THAT(error_of(R"j({"wind": {"gust": "dryden", "turbulence_length_m": 0.5}})j"),
              HasSubstr("/world/wind/turbulence_length_m:"));
  EXPECT_THAT(error_of(R"j({"wind": {"gust": "one_minus_cos", "gust_amplitude_mps": [1, 0]}})j"),
              HasSubstr("/world/wind/gust_amplitude_mps:"));
  EXPECT_THAT(error_of(R"j({"wind": {"speed_mps": 2, "velocity_mps": [1, 0, 0]}})j"),
              HasSubstr("/world/wind/velocity_mps: expected either velocity_mps or speed_mps, direction_deg and "
                        "vertical_mps, not both, got [1,0,0]"));
  EXPECT_THAT(error_of(R"j({"wind": {"velocity_mps": [80, 80, 0]}})j"),
              HasSubstr("/world/wind/velocity_mps: expected a horizontal speed within 100 m/s"));
  EXPECT_THAT(error_of(R"j({"wind": {"velocity_mps": [1, 0]}})j"), HasSubstr("/world/wind/velocity_mps:"));
}

}  // namespace
}  // namespace campo
