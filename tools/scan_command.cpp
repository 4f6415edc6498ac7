#include <charconv>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "campo/scene_loader.hpp"
#include "core/output_dir.hpp"
#include "run/provenance.hpp"
#include "sensors/depth_image.hpp"
#include "sensors/lidar.hpp"
#include "sensors/scan_io.hpp"
#include "campo/sensor_factory.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

struct ScanOptions {
  std::string scene;
  std::string sensor;
  std::string vehicle;
  std::string pose;
  std::string res;
  std::string fov;
  std::string range;
  std::string seed;  ///< as given; checked by parse_seed
  bool seed_set = false;
  std::string out;
};

// Splits "a<sep>b<sep>c" into exactly `count` finite numbers, or throws an
// InputError naming the option.
std::vector<double> parse_numbers(const std::string& text, char sep, std::size_t count,
                                  const std::string& option, const std::string& expected) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(sep, start);
    const std::string item = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || ec != std::errc() || ptr != item.data() + item.size() || !std::isfinite(v)) {
      throw InputError("command line", option, "expected " + expected + ", got \"" + text + "\"");
    }
    values.push_back(v);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (values.size() != count) {
    throw InputError("command line", option, "expected " + expected + ", got \"" + text + "\"");
  }
  return values;
}

int run_scan(const ScanOptions& o) {
  check_output_directory(o.out, "--out");
  const Scene scene = load_scene(o.scene);

  // Sensor and pose: from the options, else from the scene's vehicle.
  const VehicleDef* vehicle = nullptr;
  if (!o.vehicle.empty()) {
    vehicle = scene.find_vehicle(o.vehicle);
    if (!vehicle) throw InputError("command line", "--vehicle", "no vehicle \"" + o.vehicle + "\" in " + o.scene);
  } else if (!scene.vehicles.empty()) {
    vehicle = &scene.vehicles.front();
  }
  nlohmann::json sensor_block;
  if (o.sensor == "depth_camera") {
    // The scanner3d frustum, rendered instead of ray-cast.
    sensor_block = {{"type", "depth_camera"}, {"preset", "scanner3d"}};
  } else if (!o.sensor.empty()) {
    sensor_block = {{"type", "lidar"}, {"preset", o.sensor}};
  } else if (vehicle && !vehicle->sensors.empty()) {
    sensor_block = sensor_json(vehicle->sensors.front());
  } else {
    throw InputError("command line", "--sensor",
                     "a sensor preset: the scene has no vehicle with a sensor to default to");
  }
  if (!o.res.empty()) {
    const auto v = parse_numbers(o.res, 'x', 2, "--res", "COLSxROWS, e.g. 64x64");
    if (v[0] != std::floor(v[0]) || v[1] != std::floor(v[1])) {
      throw InputError("command line", "--res", "expected whole numbers COLSxROWS, got \"" + o.res + "\"");
    }
    sensor_block["resolution"] = {static_cast<long>(v[0]), static_cast<long>(v[1])};
    sensor_block.erase("beams");
  }
  if (!o.fov.empty()) {
    const auto v = parse_numbers(o.fov, 'x', 2, "--fov", "HxV in degrees, e.g. 90x90");
    sensor_block["fov_deg"] = {v[0], v[1]};
  }
  if (!o.range.empty()) {
    const auto v = parse_numbers(o.range, ',', 2, "--range", "MIN,MAX in metres, e.g. 0.1,10");
    sensor_block["range_m"] = {v[0], v[1]};
  }
  const SensorDef sensor = parse_sensor(JsonNode(sensor_block, "command line", ""));
  const RangeSensorConfig& config = sensor.range;

  Eigen::Isometry3d sensor_pose;
  if (!o.pose.empty()) {
    const auto v = parse_numbers(o.pose, ',', 6, "--pose", "x,y,z,roll,pitch,yaw (metres, degrees)");
    sensor_pose = to_isometry(Pose{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}});
  } else if (vehicle) {
    sensor_pose = vehicle->pose * to_isometry(config.mount);
  } else {
    throw InputError("command line", "--pose", "a sensor pose: the scene has no vehicle to default to");
  }

  const std::uint64_t world_seed = o.seed_set ? parse_seed(o.seed, "command line", "--seed") : scene.world.seed;
  const std::unique_ptr<RangeSensor> ranger = make_range_sensor(scene, sensor, world_seed);
  RangeScan scan;
  ranger->scan(sensor_pose, 0.0, scripted_poses(scene, 0.0), scan);

  const cv::Mat depth = depth_map(scan, config);
  StagedOutput out(o.out);
  write_file_atomically(out.path("ranges.csv"), ranges_csv(scan));
  write_file_atomically(out.path("hits.csv"), hits_csv(scan));
  write_file_atomically(out.path("points.ply"), points_ply(scan));
  write_depth_png(depth, out.path("depth.png"));
  const Eigen::Vector3d p = sensor_pose.translation();
  const Eigen::Vector3d rpy = rpy_deg_from_rotation(sensor_pose.linear());
  nlohmann::json record = {
      {"sensor", sensor_json(sensor)},
      {"sensor_pose", {{"position_m", {p.x(), p.y(), p.z()}}, {"rpy_deg", {rpy.x(), rpy.y(), rpy.z()}}}},
      {"noise_seed", world_seed},
      {"rows", scan.rows},
      {"cols", scan.cols},
      {"hits", scan.points.size()},
      {"depth_png", "16-bit grey, pixel = round(range / max_range * 65535), 0 below min range"},
      {"provenance", provenance(scene)},
  };
  write_file_atomically(out.path("scan.json"), record.dump(2) + "\n");
  out.commit();
  std::cout << "scan " << scan.cols << "x" << scan.rows << ": " << scan.points.size() << " of "
            << scan.ranges_m.size() << " beams hit; wrote " << o.out
            << "/{ranges.csv,hits.csv,depth.png,points.ply,scan.json}\n";
  return kOk;
}

}  // namespace

Command add_scan(CLI::App& app) {
  auto o = std::make_shared<ScanOptions>();
  app.add_option("scene", o->scene, "Scene file (JSON)")->required()->check(input_path());
  std::string presets;
  for (auto name : sensor_preset_names()) presets += (presets.empty() ? "" : ", ") + std::string(name);
  app.add_option("--sensor", o->sensor,
                 "LIDAR preset (" + presets + "), or depth_camera (the scanner3d frustum rendered with "
                 "OSMesa); default: the first sensor of the vehicle");
  app.add_option("--vehicle", o->vehicle, "Vehicle whose pose and sensor are the defaults (default: the first)");
  app.add_option("--pose", o->pose,
                 "Sensor pose x,y,z,roll,pitch,yaw in metres and degrees, world frame; "
                 "default: the vehicle's pose with the sensor's mount");
  app.add_option("--res", o->res, "Beam grid COLSxROWS, e.g. 64x64");
  app.add_option("--fov", o->fov, "Field of view HxV in degrees, e.g. 90x90");
  app.add_option("--range", o->range, "Range limits MIN,MAX in metres, e.g. 0.05,10");
  app.add_option("--seed", o->seed, "Noise seed, an integer in [0, 2^64-1] (default: the scene's world seed)")
      ->each([o](const std::string&) { o->seed_set = true; });
  app.add_option("--out", o->out, "Output directory (created if missing)")->required();
  app.footer(
      "Writes DIR/ranges.csv (one line per beam row, metres; no return = max range),\n"
      "DIR/hits.csv (1/0 per beam), DIR/depth.png (16-bit normalized depth map: pixel (0,0)\n"
      "top-left, value = range / max range, 0 below min range), DIR/points.ply (world-frame\n"
      "hit points) and DIR/scan.json (sensor parameters and provenance). Files appear\n"
      "together or not at all.\n"
      "Example: campo scan scenes/two_barriers.json --sensor scanner3d --res 64x64 \\\n"
      "           --pose 0,0,1.5,0,0,0 --out out/scan");
  return [o] { return run_scan(*o); };
}

}  // namespace campo::cli
