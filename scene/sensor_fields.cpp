#include "scene/sensor_fields.hpp"

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace campo {

namespace {

// A sensor's own rate_hz: 0 (world.sensor_rate_hz), or within world.sensor_rate_hz's range.
constexpr double kMinSensorRateHz = 0.01;
constexpr double kMaxSensorRateHz = 10000.0;

}  // namespace

double read_sensor_rate_hz(const JsonNode& node) {
  const double rate = node.as_number();
  if (!(rate == 0.0 || (rate >= kMinSensorRateHz && rate <= kMaxSensorRateHz))) {
    node.fail("0 (world.sensor_rate_hz) or a number in [0.01, 10000]");
  }
  return rate;
}

void read_range_m(const JsonNode& node, double& min_m, double& max_m) {
  const Eigen::Vector2d mm = node.as_vector2(Range::non_negative());
  if (!(mm.x() < mm.y()) || mm.y() > 1e5) node.fail("[min, max] with 0 <= min < max <= 100000");
  min_m = mm.x();
  max_m = mm.y();
}

const ConfigFields<Pose>& mount_fields() {
  static const ConfigFields<Pose> fields =
      ConfigFields<Pose>()
          .vector("position_m", &Pose::position_m, Range::closed(-100.0, 100.0), "m", "position on the vehicle body")
          .vector("rpy_deg", &Pose::rpy_deg, Range::closed(-360.0, 360.0), "deg", "roll, pitch, yaw on the body");
  return fields;
}

ConfigFields<RangeSensorConfig> range_sensor_config_fields(const SceneLimits& limits) {
  using C = RangeSensorConfig;
  const long max_beams = limits.max_beams;
  const std::string beam_limit = "at most " + std::to_string(max_beams) + " beams";
  return ConfigFields<C>()
      // First: a preset gives the starting values of every other field.
      .custom("preset", "", "`scanner3d`, `leddar_vu8` or `planar180`", "starting values, see below",
              [](const JsonNode& n, C& c) {
                const auto names = sensor_preset_names();
                const std::vector<std::string_view> choices(names.begin(), names.end());
                const RangeSensorKind kind = c.kind;  // the block's "type", not the preset's
                c = *sensor_preset(choices[n.as_choice(choices)]);
                c.kind = kind;
              },
              [](const C& c, nlohmann::json& j) { j["preset"] = c.preset; })
      // A grid given here replaces a preset's explicit beams; written for grid sensors only.
      .custom("fov_deg", "deg", "[horizontal (0, 360], vertical [0, 180)]", "field of view",
              [](const JsonNode& n, C& c) {
                c.beams.clear();
                const auto items = n.as_array(2, 2);
                c.fov_h_deg = items[0].as_number({0.0, 360.0, true, false});
                c.fov_v_deg = items[1].as_number({0.0, 180.0, false, true});
              },
              [](const C& c, nlohmann::json& j) {
                if (c.beams.empty()) j["fov_deg"] = {c.fov_h_deg, c.fov_v_deg};
              })
      .custom("resolution", "", "[cols, rows], each in [1, 65536], " + beam_limit + " (cols x rows)", "beam grid",
              [max_beams](const JsonNode& n, C& c) {
                c.beams.clear();
                const auto items = n.as_array(2, 2);
                c.cols = static_cast<int>(items[0].as_int(1, 65536));
                c.rows = static_cast<int>(items[1].as_int(1, 65536));
                if (static_cast<long>(c.cols) * c.rows > max_beams) {
                  n.fail("at most " + std::to_string(max_beams) + " beams (cols x rows)");
                }
              },
              [](const C& c, nlohmann::json& j) {
                if (c.beams.empty()) j["resolution"] = {c.cols, c.rows};
              })
      .custom("beams", "deg", "[[azimuth in [-180, 180], elevation in [-90, 90]], ...], " + beam_limit,
              "explicit beams instead of the grid",
              [max_beams](const JsonNode& n, C& c) {
                c.beams.clear();
                for (const JsonNode& b : n.as_array(1, static_cast<std::size_t>(max_beams))) {
                  const Eigen::Vector2d ae = b.as_vector2();
                  if (std::abs(ae.x()) > 180.0 || std::abs(ae.y()) > 90.0) {
                    b.fail("[azimuth_deg in [-180, 180], elevation_deg in [-90, 90]]");
                  }
                  c.beams.push_back({ae.x(), ae.y()});
                }
              },
              [](const C& c, nlohmann::json& j) {
                if (c.beams.empty()) return;
                nlohmann::json beams = nlohmann::json::array();
                for (const Beam& b : c.beams) beams.push_back({b.azimuth_deg, b.elevation_deg});
                j["beams"] = beams;
              })
      .custom("range_m", "m", "[min, max] with 0 <= min < max <= 100000",
              "nearer returns read 0 in the depth map; farther: no return",
              [](const JsonNode& n, C& c) { read_range_m(n, c.min_range_m, c.max_range_m); },
              [](const C& c, nlohmann::json& j) { j["range_m"] = {c.min_range_m, c.max_range_m}; })
      .number("noise_stddev_m", &C::noise_stddev_m, Range::closed(0.0, 100.0), "m", "Gaussian range noise")
      .number("dropout_probability", &C::dropout_probability, Range::closed(0.0, 1.0), "",
              "chance that a beam returns nothing")
      .number("quantization_m", &C::quantization_m, Range::closed(0.0, 100.0), "m",
              "ranges rounded to this step; 0 = off")
      // The range of world.sensor_rate_hz, or 0 for that rate: a slower rate would be a period of
      // more than 10^7 physics steps (dividing_rates_near() past 2^53 once made that a 4 GB error).
      .custom("rate_hz", "Hz", "0, or [0.01, 10000]",
              "scans per second, dividing the physics rate ([rates](#world)); 0 = `world.sensor_rate_hz`",
              [](const JsonNode& n, C& c) { c.rate_hz = read_sensor_rate_hz(n); },
              [](const C& c, nlohmann::json& j) { j["rate_hz"] = c.rate_hz; })
      .seed("seed", &C::seed, "noise stream, combined with `world.seed`")
      .nested("mount", &C::mount, mount_fields(), "pose on the vehicle body")
      // What a depth camera has of the fields above: one perspective render
      // covers a beam grid, well below 180 deg each way, without the LIDAR's
      // noise model. Checked on the values, which may come from the preset.
      .requirement([](const C& c) { return c.kind != RangeSensorKind::depth_camera || c.beams.empty(); },
                   "a depth camera with a beam grid (\"fov_deg\", \"resolution\"), not explicit beams")
      .requirement(
          [](const C& c) {
            return c.kind != RangeSensorKind::depth_camera ||
                   (c.noise_stddev_m == 0.0 && c.dropout_probability == 0.0);
          },
          "a depth camera without \"noise_stddev_m\" or \"dropout_probability\" (only the LIDAR models them)")
      .requirement(
          [](const C& c) {
            return c.kind != RangeSensorKind::depth_camera ||
                   (c.fov_h_deg <= kMaxDepthCameraFov_deg && c.fov_v_deg <= kMaxDepthCameraFov_deg);
          },
          "a depth camera field of view of at most " + std::to_string(static_cast<int>(kMaxDepthCameraFov_deg)) +
              " deg each way");
}

const ConfigFields<StateNoiseConfig>& state_noise_fields() {
  using C = StateNoiseConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .number("position_stddev_m", &C::position_stddev_m, Range::closed(0.0, 1e3), "m",
                  "horizontal (x, y) white noise, per axis")
          .number("altitude_stddev_m", &C::altitude_stddev_m, Range::closed(0.0, 1e3), "m", "vertical (z) white noise")
          .number("velocity_stddev_mps", &C::velocity_stddev_mps, Range::closed(0.0, 1e3), "m/s",
                  "velocity white noise, per axis")
          .number("heading_stddev_deg", &C::heading_stddev_deg, Range::closed(0.0, 180.0), "deg",
                  "yaw white noise (the estimated attitude turned about the vertical)")
          .number("bias_walk_m_per_sqrt_s", &C::bias_walk_m_per_sqrt_s, Range::closed(0.0, 1e3), "m/√s",
                  "position bias, a random walk per axis: each draw adds a step of standard deviation b √dt")
          .number("rate_hz", &C::rate_hz, Range::closed(0.0, 10000.0), "Hz",
                  "how often a new error is drawn; 0: at every planner call");
  return fields;
}

}  // namespace campo
