#include "sim/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace campo {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Distance from (r, z) to the region 0 <= r' <= radius(z'), |z'| <= h/2 of a
// solid of revolution whose radius falls linearly from r_bottom to r_top.
double distance_to_frustum(double r, double z, double r_bottom, double r_top, double h) {
  const double half = 0.5 * h;
  const double radius_at = r_bottom + (r_top - r_bottom) * (std::clamp(z, -half, half) + half) / h;
  if (std::abs(z) <= half && r <= radius_at) return 0.0;
  // Closest point on the profile: bottom disc, top disc, slanted side.
  const auto segment = [r, z](double r0, double z0, double r1, double z1) {
    const double dr = r1 - r0, dz = z1 - z0;
    const double t = std::clamp(((r - r0) * dr + (z - z0) * dz) / (dr * dr + dz * dz), 0.0, 1.0);
    return std::hypot(r - (r0 + t * dr), z - (z0 + t * dz));
  };
  double d = segment(0.0, -half, r_bottom, -half);
  d = std::min(d, segment(r_bottom, -half, r_top, half));
  if (r_top > 0.0) d = std::min(d, segment(r_top, half, 0.0, half));
  return d;
}

double bounding_radius(const Shape& s) {
  switch (s.type) {
    case ShapeType::cuboid: return 0.5 * s.size_m.norm();
    case ShapeType::cylinder:
    case ShapeType::cone: return std::hypot(s.radius_m, 0.5 * s.height_m);
    case ShapeType::sphere: return s.radius_m;
    default: return kInfinity;
  }
}

}  // namespace

double distance_to_shape(const Shape& shape, const Eigen::Vector3d& point) {
  return distance_to_shape(shape, shape.pose, point);
}

double distance_to_shape(const Shape& shape, const Eigen::Isometry3d& pose, const Eigen::Vector3d& point) {
  const Eigen::Vector3d local = pose.inverse() * point;
  switch (shape.type) {
    case ShapeType::cuboid: {
      const Eigen::Vector3d outside = (local.cwiseAbs() - 0.5 * shape.size_m).cwiseMax(0.0);
      return outside.norm();
    }
    case ShapeType::sphere:
      return std::max(0.0, local.norm() - shape.radius_m);
    case ShapeType::cylinder:
      return distance_to_frustum(local.head<2>().norm(), local.z(), shape.radius_m, shape.radius_m, shape.height_m);
    case ShapeType::cone:
      return distance_to_frustum(local.head<2>().norm(), local.z(), shape.radius_m, 0.0, shape.height_m);
    case ShapeType::plane:
    case ShapeType::heightfield:
      return kInfinity;
  }
  return kInfinity;
}

ClearanceField::ClearanceField(const Scene& scene) : scene_(scene) {
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& s = scene.shapes[i];
    if (s.type == ShapeType::plane || s.type == ShapeType::heightfield) continue;
    obstacles_.push_back(static_cast<int>(i));
    centres_.push_back(s.pose.translation());
    radii_.push_back(bounding_radius(s));
  }
}

double ClearanceField::distance(const Eigen::Vector3d& point, double t_s) const {
  double best = kInfinity;
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    // The bounding sphere bounds the distance from below: skip shapes that cannot beat `best`.
    if ((point - centres_[k]).norm() - radii_[k] >= best) continue;
    best = std::min(best, distance_to_shape(scene_.shapes[static_cast<std::size_t>(obstacles_[k])], point));
  }
  for (const Mover& mover : scene_.movers) {
    Eigen::Isometry3d pose = mover.shape.pose;
    pose.translation() = mover.position_at(t_s);
    best = std::min(best, distance_to_shape(mover.shape, pose, point));
  }
  return best;
}

}  // namespace campo
