#pragma once
/// A fan of rays from one origin: a scan's beam directions in the sensor
/// frame, sorted once into bins of a cube map around the sensor. Casting it
/// (RayCaster::cast with a pose) then goes the other way round from a ray
/// tracer: each surface in range is projected onto the bins it may cover and
/// tested only against their rays (sensors/fan_kernels.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "sensors/fan_kernels.hpp"

namespace campo {

class RayFan {
 public:
  /// `directions`: unit vectors in the sensor frame, in beam order. Throws
  /// std::invalid_argument for a direction that is not one (to 1e-4).
  explicit RayFan(std::span<const Eigen::Vector3f> directions);

  std::size_t size() const { return order_.size(); }
  /// The sorted rays, for the kernels.
  fan::Rays rays() const;
  /// Sorted slot -> index of its direction in beam order.
  std::span<const std::uint32_t> order() const { return order_; }
  /// Bins per side of cube face `face` (0 when the face holds no ray).
  int grid(int face) const { return grid_[face]; }

  /// The cube face a direction belongs to and its coordinates on it (see
  /// fan::kFaces).
  static int face_of(const Eigen::Vector3f& d);
  static Eigen::Vector2f face_coordinates(const Eigen::Vector3f& d, int face);

 private:
  std::vector<float> x_, y_, z_;  // sorted by bin; 8 readable floats past the end
  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> bin_start_;
  int grid_[fan::kFaces] = {};
  std::uint32_t first_bin_[fan::kFaces] = {};
  float cone_axis_[3] = {1.0f, 0.0f, 0.0f};  // see fan::Rays
  float cone_cos_ = -1.0f, cone_sin_ = 0.0f;
};

}  // namespace campo
