#include "sensors/scan_io.hpp"

#include <cstdio>

#include "scene/sensor_fields.hpp"

namespace campo {

namespace {

template <class Format>
std::string grid_csv(const RangeScan& scan, Format format) {
  std::string out;
  out.reserve(static_cast<std::size_t>(scan.rows) * scan.cols * 9);
  char buffer[32];
  for (int r = 0; r < scan.rows; ++r) {
    for (int c = 0; c < scan.cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * scan.cols + c;
      const int n = format(buffer, sizeof buffer, i);
      if (c > 0) out += ',';
      out.append(buffer, static_cast<std::size_t>(n));
    }
    out += '\n';
  }
  return out;
}

}  // namespace

std::string ranges_csv(const RangeScan& scan) {
  return grid_csv(scan, [&](char* buf, std::size_t size, std::size_t i) {
    return std::snprintf(buf, size, "%.4f", static_cast<double>(scan.ranges_m[i]));
  });
}

std::string hits_csv(const RangeScan& scan) {
  return grid_csv(scan, [&](char* buf, std::size_t size, std::size_t i) {
    return std::snprintf(buf, size, "%d", scan.hits[i] ? 1 : 0);
  });
}

std::string points_ply(const RangeScan& scan) {
  std::string out = "ply\nformat ascii 1.0\ncomment campo LIDAR scan, world frame, metres\n";
  out += "element vertex " + std::to_string(scan.points.size()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\nend_header\n";
  char buffer[96];
  for (const auto& p : scan.points) {
    const int n = std::snprintf(buffer, sizeof buffer, "%.4f %.4f %.4f\n", static_cast<double>(p.x()),
                                static_cast<double>(p.y()), static_cast<double>(p.z()));
    out.append(buffer, static_cast<std::size_t>(n));
  }
  return out;
}

nlohmann::json sensor_json(const SensorDef& sensor) {
  nlohmann::json j = range_sensor_config_fields().write(sensor.range);
  j["type"] = to_string(sensor.range.kind);
  if (!sensor.alias.empty()) j["alias"] = sensor.alias;
  return j;
}

}  // namespace campo
