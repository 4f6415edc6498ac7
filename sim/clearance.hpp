#pragma once
/// Distances from points to scene shapes, for clearance metrics. Analytic
/// and exact for every primitive; ground (planes, heightfields) is not an
/// obstacle and is left out.
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "sim/scene.hpp"

namespace campo {

/// Euclidean distance from `point` to the solid `shape` (0 inside). Planes
/// and heightfields: +infinity (not obstacles).
double distance_to_shape(const Shape& shape, const Eigen::Vector3d& point);
/// The same with the shape placed at `pose` instead of shape.pose (movers).
double distance_to_shape(const Shape& shape, const Eigen::Isometry3d& pose, const Eigen::Vector3d& point);

/// Nearest obstacle distance over the static obstacles of a scene, with a
/// coarse bounding-sphere cull so the cost stays low in large scenes.
class ClearanceField {
 public:
  explicit ClearanceField(const Scene& scene);
  /// Distance from `point` to the nearest static obstacle or mover (movers at time t).
  double distance(const Eigen::Vector3d& point, double t_s) const;

 private:
  const Scene& scene_;
  std::vector<int> obstacles_;             // indices of non-ground shapes
  std::vector<Eigen::Vector3d> centres_;   // bounding-sphere centres
  std::vector<double> radii_;              // bounding-sphere radii
};

}  // namespace campo
