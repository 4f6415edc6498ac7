#include "scene/sensor_fields.hpp"

namespace campo {

namespace {

// The widest horizontal field a pinhole image covers without stretching its
// edges beyond use (tan(85 deg) = 11.4 times the centre's scale).
constexpr double kMaxRgbFov_deg = 170.0;
// Pixels a side: a 4096 x 4096 image is 48 MiB, rendered at the sensor rate.
constexpr int kMaxRgbPixels = 4096;

}  // namespace

const ConfigFields<RgbCameraConfig>& rgb_camera_config_fields() {
  using C = RgbCameraConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .number("fov_deg", &C::fov_h_deg, Range{0.0, kMaxRgbFov_deg, true, false}, "deg",
                  "horizontal field of view; the vertical one follows from the aspect: "
                  "2 atan(tan(fov_deg / 2) rows / cols)")
          .custom("resolution", "px", "[cols, rows], each in [1, 4096]", "image width and height",
                  [](const JsonNode& n, C& c) {
                    const auto items = n.as_array(2, 2);
                    c.cols = static_cast<int>(items[0].as_int(1, kMaxRgbPixels));
                    c.rows = static_cast<int>(items[1].as_int(1, kMaxRgbPixels));
                  },
                  [](const C& c, nlohmann::json& j) { j["resolution"] = {c.cols, c.rows}; })
          .custom("range_m", "m", "[min, max] with 0 <= min < max <= 100000",
                  "distances along each pixel's ray: nearer surfaces are not drawn (what lies behind shows), "
                  "farther ones show the sky",
                  [](const JsonNode& n, C& c) { read_range_m(n, c.min_range_m, c.max_range_m); },
                  [](const C& c, nlohmann::json& j) { j["range_m"] = {c.min_range_m, c.max_range_m}; })
          .custom("sky", "", "[r, g, b], each in [0, 1]", "background colour where nothing lies within range",
                  [](const JsonNode& n, C& c) {
                    const Eigen::Vector3d rgb = n.as_vector3(Range::closed(0.0, 1.0));
                    c.sky = {rgb.x(), rgb.y(), rgb.z()};
                  },
                  [](const C& c, nlohmann::json& j) { j["sky"] = {c.sky.r, c.sky.g, c.sky.b}; })
          .number("noise_stddev", &C::noise_stddev, Range::closed(0.0, 1.0), "",
                  "Gaussian noise added to each channel of each pixel, as a fraction of full scale (255); "
                  "0 = none")
          .custom("rate_hz", "Hz", "0, or [0.01, 10000]",
                  "images per second, dividing the physics rate ([rates](#world)); 0 = `world.sensor_rate_hz`",
                  [](const JsonNode& n, C& c) { c.rate_hz = read_sensor_rate_hz(n); },
                  [](const C& c, nlohmann::json& j) { j["rate_hz"] = c.rate_hz; })
          .seed("seed", &C::seed, "pixel noise stream, combined with `world.seed`")
          .nested("mount", &C::mount, mount_fields(), "pose on the vehicle body");
  return fields;
}

}  // namespace campo
