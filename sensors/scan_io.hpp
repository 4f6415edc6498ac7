#pragma once
/// Text outputs of a LIDAR scan: range and hit grids as CSV, the point cloud
/// as ASCII PLY, and a JSON description of the sensor.
#include <string>

#include <nlohmann/json.hpp>

#include "sensors/lidar.hpp"

namespace campo {

/// One line per beam row, comma-separated ranges in metres (0.1 mm
/// resolution); a beam without a return reads the sensor's max range.
std::string ranges_csv(const RangeScan& scan);
/// Same layout as ranges_csv: 1 for a return, 0 for none.
std::string hits_csv(const RangeScan& scan);
/// ASCII PLY of the world-frame hit points.
std::string points_ply(const RangeScan& scan);
/// The sensor's effective parameters as JSON (the keys of a scene sensor block).
nlohmann::json sensor_json(const SensorDef& sensor);

}  // namespace campo
