#pragma once
/// Configuration of a range sensor (SPEC §6), the ray-cast LIDAR or the depth
/// camera alike (its kind says which): field of view, beam layout, range
/// limits, mount pose, rate and imperfections.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "campo/pose.hpp"

namespace campo {

/// One beam direction in the sensor frame (x forward, y left, z up).
struct Beam {
  double azimuth_deg = 0.0;    ///< positive to the left (counter-clockwise about z)
  double elevation_deg = 0.0;  ///< positive up
};

/// How a range sensor measures: the scene's sensor "type". Both kinds fill
/// the same RangeScan (the same depth map over the same angular grid), so
/// planners take either.
enum class RangeSensorKind {
  lidar,         ///< beams ray-cast against the physics geometry (sensors/lidar.hpp)
  depth_camera,  ///< an image rendered off-screen with OSMesa (sensors/depth_camera.hpp)
};
/// "lidar" or "depth_camera", as the scene names the kind.
std::string_view to_string(RangeSensorKind kind);

/// Sensor frame: x forward, y left, z up. A grid sensor's pixel (col, row)
/// looks at azimuth = fov_h/2 - (col + 0.5) * fov_h / cols (so column 0 is the
/// leftmost) and elevation = fov_v/2 - (row + 0.5) * fov_v / rows (row 0 the
/// top), matching the depth-map convention: (0,0) top-left, x right, y down.
struct RangeSensorConfig {
  RangeSensorKind kind = RangeSensorKind::lidar;  ///< ray-cast beams or a rendered image
  std::string preset = "custom";  ///< preset it started from, for provenance
  double fov_h_deg = 90.0;        ///< horizontal field of view, (0, 360]
  double fov_v_deg = 90.0;        ///< vertical field of view, [0, 180)
  int cols = 256;                 ///< beams across, >= 1
  int rows = 256;                 ///< beams down, >= 1
  std::vector<Beam> beams;        ///< explicit beams; when set they replace the grid (rows = 1)
  double min_range_m = 0.05;      ///< nearer returns read as 0 in the depth map
  double max_range_m = 10.0;      ///< beyond this: no hit
  double noise_stddev_m = 0.0;    ///< Gaussian range noise, metres
  double dropout_probability = 0.0;  ///< chance a beam returns nothing, [0, 1]
  double quantization_m = 0.0;    ///< round ranges to this step; 0 = off
  double rate_hz = 0.0;           ///< scans per second; 0 = the world's sensor rate
  Pose mount;                     ///< relative to the carrier's body frame
  std::uint64_t seed = 0;         ///< noise stream, combined with the world seed

  int beam_count() const { return beams.empty() ? cols * rows : static_cast<int>(beams.size()); }
  /// The scan's layout, the one place a sensor's resolution is read from:
  /// the grid's rows x cols, or one row of the explicit beams. Sensors size
  /// their scans (RangeScan::rows, cols) with it and planners take their
  /// image geometry from the scan they read.
  int scan_rows() const { return beams.empty() ? rows : 1; }
  int scan_cols() const { return beams.empty() ? cols : static_cast<int>(beams.size()); }
};

/// A range image: a beam grid of more than one row (the depth camera, the
/// scanner3d LIDAR), as opposed to a fan of beams in one row (a leddar, a
/// planar scanner). Depth-map planners and figures read only images.
inline bool is_image(const RangeSensorConfig& c) { return c.beams.empty() && c.rows > 1; }

/// Preset names: "scanner3d", "leddar_vu8", "planar180" (a sensor block's
/// "preset", for either kind).
std::vector<std::string_view> sensor_preset_names();
/// The preset's configuration (a LIDAR's); nullopt for an unknown name.
std::optional<RangeSensorConfig> sensor_preset(std::string_view name);

}  // namespace campo
