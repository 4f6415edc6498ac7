#include "campo/range_sensor_config.hpp"

#include <array>

namespace campo {

namespace {

// 000 §5.5: V-REP 3D laser scanner on the quadrotor, 10 m range, 90 x 90 deg,
// depth maps of 256 x 256 px; forward-looking (identity mount).
RangeSensorConfig scanner3d() {
  RangeSensorConfig c;
  c.preset = "scanner3d";
  c.fov_h_deg = 90.0;
  c.fov_v_deg = 90.0;
  c.cols = 256;
  c.rows = 256;
  c.min_range_m = 0.05;
  c.max_range_m = 10.0;
  return c;
}

// 001 §4.1, §4.2.4: Leddar Vu8, 8 segments over 48 x 0.3 deg, mounted 45 deg
// toward the direction of travel. With R = Rz Ry Rx (x forward, z up) a
// positive pitch turns +x toward -z, so pitch +45 deg points the beams down.
// 001 flies at 30 m, well inside the range; 100 m is the lower end of the
// ranges the Vu8 is sold with (roughly 100-215 m depending on optics).
RangeSensorConfig leddar_vu8() {
  RangeSensorConfig c;
  c.preset = "leddar_vu8";
  c.fov_h_deg = 48.0;
  c.fov_v_deg = 0.3;
  c.cols = 8;
  c.rows = 1;
  c.min_range_m = 0.05;
  c.max_range_m = 100.0;
  c.mount.rpy_deg = Eigen::Vector3d(0.0, 45.0, 0.0);
  return c;
}

// 003 §3.6: MATLAB rangeSensor, 180 deg field (-90..+90) sampled at the
// horizontal resolution, one reading per angle including both ends. Beams are
// listed leftmost first (+90 .. -90), like grid column 0. 003 does not state
// the range; 20 m comfortably covers a vineyard inter-row and headland.
RangeSensorConfig planar180() {
  RangeSensorConfig c;
  c.preset = "planar180";
  c.fov_h_deg = 180.0;
  c.fov_v_deg = 0.0;
  c.cols = 181;
  c.rows = 1;
  c.min_range_m = 0.05;
  c.max_range_m = 20.0;
  c.beams.reserve(181);
  for (int i = 0; i <= 180; ++i) c.beams.push_back(Beam{90.0 - i, 0.0});
  return c;
}

using PresetFactory = RangeSensorConfig (*)();
constexpr std::array<std::pair<std::string_view, PresetFactory>, 3> kPresets{{
    {"scanner3d", &scanner3d},
    {"leddar_vu8", &leddar_vu8},
    {"planar180", &planar180},
}};

}  // namespace

std::string_view to_string(RangeSensorKind kind) { return kind == RangeSensorKind::lidar ? "lidar" : "depth_camera"; }

std::vector<std::string_view> sensor_preset_names() {
  std::vector<std::string_view> names;
  for (const auto& [name, factory] : kPresets) names.push_back(name);
  return names;
}

std::optional<RangeSensorConfig> sensor_preset(std::string_view name) {
  for (const auto& [preset_name, factory] : kPresets) {
    if (preset_name == name) return factory();
  }
  return std::nullopt;
}

}  // namespace campo
