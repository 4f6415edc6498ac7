#include "session/imu_record.hpp"

#include <charconv>
#include <cstdio>

namespace campo {

void ImuRecorder::record(std::size_t vehicle, std::size_t imu, const ImuReading& reading) {
  samples_.at(vehicle).push_back({imu, reading.time_s, reading.specific_force_mps2, reading.angular_rate_radps});
}

namespace {

// ",%.9g" as trajectory.csv writes its numbers.
void append(std::string& out, double v) {
  out += ',';
  char buffer[32];
  const auto written = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 9);
  out.append(buffer, written.ptr);
}

}  // namespace

std::string imu_csv(const VehicleDef& vehicle, const std::vector<RecordedImuSample>& samples) {
  std::string out = "time_s,alias,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps\n";
  out.reserve(out.size() + samples.size() * 96);
  for (const RecordedImuSample& s : samples) {
    char time[32];
    out.append(time, static_cast<std::size_t>(std::snprintf(time, sizeof time, "%.6f", s.time_s)));
    out += ',';
    out += vehicle.imus.at(s.imu).alias;
    for (int i = 0; i < 3; ++i) append(out, s.specific_force_mps2[i]);
    for (int i = 0; i < 3; ++i) append(out, s.angular_rate_radps[i]);
    out += '\n';
  }
  return out;
}

std::string imu_file(const EpisodeResult& result, std::size_t vehicle) {
  return result.vehicles.size() == 1 ? "imu.csv" : "imu_" + result.vehicles.at(vehicle).alias + ".csv";
}

}  // namespace campo
