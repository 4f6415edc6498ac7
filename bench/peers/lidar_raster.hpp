#pragma once
// The rasteriser peer of campo's LIDAR (bench/peers/lidar_embree.cpp, docs/PERFORMANCE.md,
// "LIDAR against a rasteriser"): a scan's rays all leave one point, so a software
// rasteriser drawing the scene's triangles from the sensor into a depth buffer of the
// scan's resolution and field of view answers the same question, one pixel per ray.
// OSMesa (llvmpipe) on the calling thread alone (LP_NUM_THREADS=0, which must be set
// before the first OSMesa context of the process), the triangles of build_scene_mesh
// uploaded once, static geometry culled against the view in runs of triangles
// (view_culling.hpp), back faces culled when the eye is outside every solid and above
// the ground, reversed float depth; the depth read back and turned into ranges along
// each pixel's ray.
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "campo/scene.hpp"

namespace campo::peers {

/// What the rasteriser draws: a pinhole view of width x height pixels whose
/// image plane at distance 1 reaches +-half_width and +-half_height (the
/// scan's field of view), depth from near_m to far_m.
struct RasterView {
  int width_px = 256;
  int height_px = 256;
  double half_width = 1.0;   ///< tan of half the horizontal field of view
  double half_height = 1.0;  ///< tan of half the vertical field of view
  double near_m = 0.05;
  double far_m = 10.0;
  /// Triangles per culled run of static geometry (0: one run per object).
  unsigned cull_run_triangles = 256;
};

class RasterScanner {
 public:
  /// Uploads `scene`'s triangles (moving bodies where scripted_poses has them
  /// at t = 0, as RayCaster places them). Throws std::runtime_error without OSMesa.
  RasterScanner(const Scene& scene, const RasterView& view);
  ~RasterScanner();
  RasterScanner(const RasterScanner&) = delete;
  RasterScanner& operator=(const RasterScanner&) = delete;

  /// Pixel (column, row) from the top left, row-major: its ray through the
  /// pixel's centre as a unit vector in the sensor frame (x forward, y left, z up).
  std::vector<Eigen::Vector3f> pixel_directions() const;
  std::size_t triangles() const;

  /// Renders the view from `sensor_pose` and writes the range along each
  /// pixel's ray (pixel_directions order), +inf where nothing lies within
  /// far_m along it.
  void scan(const Eigen::Isometry3d& sensor_pose, std::span<float> ranges_m);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace campo::peers
