#include "campo/run_record.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <filesystem>

#include "campo/planner_registry.hpp"
#include "run/event_log.hpp"
#include "run/provenance.hpp"
#include "scene/sensor_fields.hpp"
#include "scene/world_config.hpp"
#include "sensors/scan_io.hpp"

namespace campo {

namespace {

// Names and values of a flat view of a JSON object of numbers and arrays of numbers.
void flatten(const nlohmann::json& j, const std::string& prefix, std::vector<std::string>* names,
             std::vector<double>* values) {
  if (j.is_number()) {
    if (names) names->push_back(prefix);
    if (values) values->push_back(j.get<double>());
  } else if (j.is_object()) {
    for (const auto& [key, v] : j.items()) flatten(v, prefix.empty() ? key : prefix + "_" + key, names, values);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) flatten(j[i], prefix + "_" + std::to_string(i), names, values);
  }
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

struct CommandFields {
  Eigen::Vector3d point = Eigen::Vector3d::Constant(std::nan(""));
  double speed = std::nan("");
  double v = std::nan("");
  double w = std::nan("");
};

CommandFields fields_of(const Command& c) {
  CommandFields f;
  std::visit(
      [&f](const auto& cmd) {
        using T = std::decay_t<decltype(cmd)>;
        if constexpr (std::is_same_v<T, command::Hold>) f.point = cmd.position_m;
        if constexpr (std::is_same_v<T, command::GoTo>) {
          f.point = cmd.target_m;
          f.speed = cmd.speed_mps;
        }
        if constexpr (std::is_same_v<T, command::Face>) f.point = cmd.point_m;
        if constexpr (std::is_same_v<T, command::Altitude>) f.point.z() = cmd.z_m;
        if constexpr (std::is_same_v<T, command::Twist>) {
          f.v = cmd.v_mps;
          f.w = cmd.w_radps;
        }
      },
      c);
  return f;
}

// The low-level commands' values, in columns after the actuators: a file has the columns of the kinds
// its vehicle was given (none for the others, so their files stay as they were). `kinds`: a bit per Command index.
struct LowLevelColumn {
  const char* name;
  unsigned kinds;
};
constexpr unsigned kind_bit(std::size_t index) { return 1u << index; }
template <class T, std::size_t I = 0>
constexpr unsigned bit_of() {
  if constexpr (std::is_same_v<std::variant_alternative_t<I, Command>, T>) {
    return kind_bit(I);
  } else {
    return bit_of<T, I + 1>();
  }
}
constexpr unsigned kVelocityBit = bit_of<command::Velocity>(), kAttitudeBit = bit_of<command::AttitudeThrust>(),
                   kRotorsBit = bit_of<command::Rotors>(), kWheelsBit = bit_of<command::Wheels>();
constexpr LowLevelColumn kLowLevelColumns[] = {
    {"cmd_forward_mps", kVelocityBit},  // Velocity in the heading frame
    {"cmd_left_mps", kVelocityBit},
    {"cmd_up_mps", kVelocityBit},
    {"cmd_roll_rad", kAttitudeBit},
    {"cmd_pitch_rad", kAttitudeBit},
    {"cmd_yaw_rate_radps", kVelocityBit | kAttitudeBit},
    {"cmd_thrust_n", kAttitudeBit},
    {"cmd_rotor_0_radps", kRotorsBit},
    {"cmd_rotor_1_radps", kRotorsBit},
    {"cmd_rotor_2_radps", kRotorsBit},
    {"cmd_rotor_3_radps", kRotorsBit},
    {"cmd_front_left_radps", kWheelsBit},
    {"cmd_front_right_radps", kWheelsBit},
    {"cmd_rear_left_radps", kWheelsBit},
    {"cmd_rear_right_radps", kWheelsBit},
};
constexpr std::size_t kLowLevelCount = std::size(kLowLevelColumns);

// The values of kLowLevelColumns for `c`, NaN where they do not apply.
std::array<double, kLowLevelCount> low_level_values(const Command& c) {
  std::array<double, kLowLevelCount> v;
  v.fill(std::nan(""));
  if (const auto* cmd = std::get_if<command::Velocity>(&c)) {
    for (int i = 0; i < 3; ++i) v[static_cast<std::size_t>(i)] = cmd->velocity_mps[i];
    v[5] = cmd->yaw_rate_radps;
  } else if (const auto* a = std::get_if<command::AttitudeThrust>(&c)) {
    v[3] = a->roll_rad;
    v[4] = a->pitch_rad;
    v[5] = a->yaw_rate_radps;
    v[6] = a->thrust_n;
  } else if (const auto* r = std::get_if<command::Rotors>(&c)) {
    std::copy(r->speeds_radps.begin(), r->speeds_radps.end(), v.begin() + 7);
  } else if (const auto* w = std::get_if<command::Wheels>(&c)) {
    std::copy(w->speeds_radps.begin(), w->speeds_radps.end(), v.begin() + 11);
  }
  return v;
}

// ",%.9g" (std::to_chars with a precision prints as printf would, several times faster); NaN as an empty field.
void append(std::string& out, double v) {
  out += ',';
  if (std::isnan(v)) return;
  char buffer[32];
  const auto written = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 9);
  out.append(buffer, written.ptr);
}

// Relative data files of the scene (CSV/PNG terrain) resolve against this.
nlohmann::json with_data_dir(nlohmann::json provenance, const Scene& scene) {
  const std::filesystem::path dir = std::filesystem::path(scene.source_path).parent_path();
  provenance["scene"]["data_dir"] = std::filesystem::absolute(dir.empty() ? std::filesystem::path(".") : dir).string();
  return provenance;
}

}  // namespace

std::string trajectory_file(const EpisodeResult& result, std::size_t vehicle) {
  return result.vehicles.size() == 1 ? "trajectory.csv" : "trajectory_" + result.vehicles.at(vehicle).alias + ".csv";
}

std::string events_file(const EpisodeResult& result, std::size_t vehicle) {
  return result.vehicles.size() == 1 ? kEventsFile : "events_" + result.vehicles.at(vehicle).alias + ".jsonl";
}

std::string trajectory_csv(const VehicleResult& result) {
  std::vector<std::string> actuator_names;
  if (!result.trajectory.empty()) flatten(result.trajectory.front().actuators, "", &actuator_names, nullptr);
  std::string out =
      "time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,vx_mps,vy_mps,vz_mps,wx_radps,wy_radps,wz_radps,"
      "command,cmd_x_m,cmd_y_m,cmd_z_m,cmd_speed_mps,cmd_v_mps,cmd_w_radps,clearance_m,"
      "est_x_m,est_y_m,est_z_m,height_above_ground_m";
  for (const auto& name : actuator_names) out += "," + name;
  unsigned kinds = 0;
  for (const TrajectorySample& s : result.trajectory) kinds |= kind_bit(s.command.index());
  std::vector<std::size_t> low_level;  // the columns of kLowLevelColumns this file has
  for (std::size_t i = 0; i < kLowLevelCount; ++i) {
    if (kLowLevelColumns[i].kinds & kinds) {
      low_level.push_back(i);
      out += ",";
      out += kLowLevelColumns[i].name;
    }
  }
  out += "\n";
  std::vector<double> actuators;
  for (const TrajectorySample& s : result.trajectory) {
    char buffer[32];
    out.append(buffer, static_cast<std::size_t>(std::snprintf(buffer, sizeof buffer, "%.6f", s.time_s)));
    for (int i = 0; i < 3; ++i) append(out, s.state.position_m[i]);
    const Eigen::Vector3d rpy = rpy_deg_from_rotation(s.state.orientation.toRotationMatrix());
    for (int i = 0; i < 3; ++i) append(out, rpy[i]);
    for (int i = 0; i < 3; ++i) append(out, s.state.linear_velocity_mps[i]);
    for (int i = 0; i < 3; ++i) append(out, s.state.angular_velocity_radps[i]);
    out += ",";
    out += command_name(s.command);
    const CommandFields f = fields_of(s.command);
    for (int i = 0; i < 3; ++i) append(out, f.point[i]);
    append(out, f.speed);
    append(out, f.v);
    append(out, f.w);
    append(out, s.clearance_m);
    for (int i = 0; i < 3; ++i) append(out, s.estimated_position_m[i]);
    append(out, s.height_above_ground_m);
    actuators.clear();
    flatten(s.actuators, "", nullptr, &actuators);
    for (std::size_t i = 0; i < actuator_names.size(); ++i) append(out, i < actuators.size() ? actuators[i] : std::nan(""));
    if (!low_level.empty()) {
      const auto values = low_level_values(s.command);
      for (const std::size_t i : low_level) append(out, values[i]);
    }
    out += "\n";
  }
  return out;
}

namespace {

// Sensor blocks of one type as a scene gives them: "type", "alias" and every field.
template <class Def, class Config>
nlohmann::json sensor_blocks(const std::vector<Def>& defs, Config Def::*config, const ConfigFields<Config>& fields,
                             const char* type) {
  nlohmann::json blocks = nlohmann::json::array();
  for (const Def& def : defs) {
    nlohmann::json j = fields.write(def.*config);
    j["type"] = type;
    j["alias"] = def.alias;
    blocks.push_back(j);
  }
  return blocks;
}

// What one vehicle ran with: its definition and effective parameters.
nlohmann::json vehicle_parameters(const VehicleDef& def, const VehicleResult& result) {
  nlohmann::json sensors = nlohmann::json::array();
  for (const SensorDef& s : def.sensors) sensors.push_back(sensor_json(s));
  // The IMUs and colour cameras (listed only where there are some, so the records of scenes
  // without them are as before).
  const nlohmann::json imus = sensor_blocks(def.imus, &ImuDef::imu, imu_config_fields(), "imu");
  const nlohmann::json cameras = sensor_blocks(def.rgb_cameras, &RgbCameraDef::camera, rgb_camera_config_fields(), "rgb_camera");
  nlohmann::json mission = nlohmann::json::array();
  for (const Waypoint& wp : def.mission) {
    nlohmann::json j = {{"position_m", vector_json(wp.position_m)}};
    if (wp.heading_deg) j["heading_deg"] = *wp.heading_deg;
    mission.push_back(j);
  }
  nlohmann::json parameters = {
      {"vehicle",
       {{"alias", def.alias},
        {"type", to_string(def.type)},
        {"start_position_m", vector_json(def.pose.translation())},
        {"start_rpy_deg", vector_json(rpy_deg_from_rotation(def.pose.linear()))},
        {"parameters", result.vehicle_parameters},
        {"state_noise", state_noise_fields().write(def.state_noise)}}},
      {"planner", {{"name", def.planner.name}, {"parameters", result.planner_parameters}}},
      {"sensors", sensors},
      {"mission", mission}};
  if (!imus.empty()) parameters["imus"] = imus;
  if (!cameras.empty()) parameters["rgb_cameras"] = cameras;
  return parameters;
}

nlohmann::json event_log_json(const std::string& file, const std::vector<PlannerEvent>& events) {
  std::size_t bounded = 0;
  for (const PlannerEvent& e : events) bounded += was_bounded(e.decisions);
  return {{"file", file}, {"count", events.size()}, {"bounded", bounded}};
}

}  // namespace

nlohmann::json run_json(const Scene& scene, const EpisodeResult& result, const EpisodeOptions& options,
                        const std::vector<std::string>& overrides) {
  nlohmann::json final_body_poses = nlohmann::json::array();
  const std::vector<MovingBody> bodies = moving_bodies(scene);
  for (std::size_t i = 0; i < bodies.size() && i < result.final_body_poses.size(); ++i) {
    const Eigen::Isometry3d& pose = result.final_body_poses[i];
    final_body_poses.push_back({{"alias", bodies[i].shape->alias},
                                {"position_m", vector_json(pose.translation())},
                                {"rpy_deg", vector_json(rpy_deg_from_rotation(pose.linear()))}});
  }
  nlohmann::json run_provenance = with_data_dir(provenance(scene), scene);
  if (result.vehicles.size() == 1) {
    const VehicleDef& def = scene.vehicles.at(0);
    const VehicleResult& vehicle = result.vehicles.front();
    // The planner's code is part of what produced the run: built in, or which plugin file.
    run_provenance["planner"] = planner_provenance(def.planner.name);
    nlohmann::json parameters = {{"world", world_config_fields().write(scene.world)}};
    parameters.update(vehicle_parameters(def, vehicle));
    parameters["stop_on_collision"] = options.stop_on_collision;
    return {
        {"metrics", to_json(vehicle.metrics)},
        {"provenance", run_provenance},
        {"overrides", overrides},
        {"parameters", parameters},
        {"final_state_hash", result.final_state_hash},
        {"final_body_poses", final_body_poses},
        // The decisions themselves are in events.jsonl, so this file does not grow with the run.
        {"event_log", event_log_json(kEventsFile, vehicle.events)},
    };
  }
  // Several vehicles: the run's metrics at the top, each vehicle's record under "vehicles".
  nlohmann::json vehicles = nlohmann::json::array();
  for (std::size_t i = 0; i < result.vehicles.size(); ++i) {
    const VehicleDef& def = scene.vehicles.at(i);
    const VehicleResult& vehicle = result.vehicles[i];
    vehicles.push_back({{"alias", def.alias},
                        {"metrics", to_json(vehicle.metrics)},
                        {"parameters", vehicle_parameters(def, vehicle)},
                        {"planner_provenance", planner_provenance(def.planner.name)},
                        {"trajectory_file", trajectory_file(result, i)},
                        {"event_log", event_log_json(events_file(result, i), vehicle.events)}});
  }
  return {
      {"metrics", to_json(result.fleet)},
      {"vehicles", vehicles},
      {"provenance", run_provenance},
      {"overrides", overrides},
      {"parameters",
       {{"world", world_config_fields().write(scene.world)},
        {"end", to_string(scene.end)},
        {"stop_on_collision", options.stop_on_collision}}},
      {"final_state_hash", result.final_state_hash},
      {"final_body_poses", final_body_poses},
  };
}

}  // namespace campo
