#include "metrics/mission_metrics.hpp"

#include <vector>

#include "metrics/route_metrics.hpp"

namespace campo {

LegMetricFields::LegMetricFields(std::size_t k)
    : path_length_m(fields.declare<double>("leg" + std::to_string(k) + "_path_length_m", "m",
                                           "path flown along mission leg " + std::to_string(k) +
                                               " (to waypoint " + std::to_string(k) +
                                               "); null when a waypoint of it was not reached")),
      lateral_before_climb_m(fields.declare<double>(
          "leg" + std::to_string(k) + "_lateral_before_climb_m", "m",
          "largest sideways offset from leg " + std::to_string(k) +
              "'s straight line before the vehicle topped its climb; null when the leg does not climb")) {}

GateMetricFields::GateMetricFields(const std::string& name)
    : passed(fields.declare<bool>("gate_" + name + "_passed", "", "whether the vehicle passed through gate " + name)),
      time_s(fields.declare<double>("gate_" + name + "_time_s", "s",
                                    "first trajectory sample inside gate " + name + "; null when never")) {}

RecordFields mission_metric_fields(const VehicleDef& def) {
  RecordFields all;
  const auto copy = [&all](const RecordFields& some) {
    for (const RecordFieldInfo& f : some.fields()) {
      if (f.type == RecordType::flag) all.declare<bool>(f.name, f.unit, f.meaning);
      else all.declare<double>(f.name, f.unit, f.meaning);
    }
  };
  for (std::size_t k = 0; k < def.mission.size(); ++k) copy(LegMetricFields(k).fields);
  for (const MissionGate& gate : def.gates) copy(GateMetricFields(gate.name).fields);
  return all;
}

void set_or_null(nlohmann::json& record, const RecordField<double>& field, std::optional<double> value) {
  if (value) {
    field.set(record, *value);
    return;
  }
  if (record.is_null()) record = nlohmann::json::object();
  record[field.name()] = nullptr;
}

std::optional<double> get_unless_null(const nlohmann::json& record, const RecordField<double>& field) {
  if (!field.in(record) || record.at(field.name()).is_null()) return std::nullopt;
  return field.get(record);
}

void write_mission_metrics(const VehicleDef& def, const Eigen::Vector3d& start,
                           std::span<const TrajectorySample> trajectory,
                           std::span<const std::optional<std::size_t>> reached_sample, nlohmann::json& record) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> agl_m;
  for (const TrajectorySample& s : trajectory) {
    points.push_back(s.state.position_m);
    agl_m.push_back(s.height_above_ground_m);
  }
  const std::span<const Eigen::Vector3d> all(points);
  for (std::size_t k = 0; k < def.mission.size(); ++k) {
    const LegMetricFields leg(k);
    std::optional<double> length_m, lateral_m;
    const std::optional<std::size_t> first = k == 0 ? std::optional<std::size_t>(0) : reached_sample[k - 1];
    const std::optional<std::size_t> last = reached_sample[k];
    if (first && last && *last >= *first && *last < points.size()) {
      const auto flown = all.subspan(*first, *last - *first + 1);
      length_m = polyline_length_m(flown);
      const Eigen::Vector3d from = k == 0 ? start : def.mission[k - 1].position_m;
      lateral_m = lateral_before_climb_m(flown, from, def.mission[k].position_m);
    }
    set_or_null(record, leg.path_length_m, length_m);
    set_or_null(record, leg.lateral_before_climb_m, lateral_m);
  }
  for (const MissionGate& gate : def.gates) {
    const GateMetricFields fields(gate.name);
    std::optional<double> time_s;
    if (const auto i = first_inside(points, agl_m, gate.area_m, gate.max_agl_m)) time_s = trajectory[*i].time_s;
    fields.passed.set(record, time_s.has_value());
    set_or_null(record, fields.time_s, time_s);
  }
}

}  // namespace campo
