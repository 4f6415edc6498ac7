#pragma once
/// Batched ray casting against the scene geometry (Embree BVH over exactly
/// the shapes the Bullet world collides with: analytic primitives, and the
/// heightfield triangulated the way Bullet triangulates it).
#include <cstdint>
#include <memory>
#include <span>

#include <Eigen/Core>

#include "sim/scene.hpp"

namespace campo {

/// Result of one ray: distance along the ray, or no hit.
struct RayHit {
  float distance_m;     ///< +infinity when nothing was hit within range
  std::int32_t shape;   ///< index into Scene::shapes, or -(1 + mover index); kNoShape for no hit
  static constexpr std::int32_t kNoShape = INT32_MIN;
};

class RayCaster {
 public:
  /// Builds the acceleration structure for the scene's shapes and movers
  /// (movers at t = 0). Keeps a reference to `scene`, which must outlive it.
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Moves the movers to their poses at simulation time t.
  void set_time(double t_s);

  /// Casts one ray per direction from `origin`; directions are unit vectors in
  /// the world frame. Hits nearer than min_range_m are ignored (the ray
  /// continues); hits beyond max_range_m are misses. No allocation.
  void cast(const Eigen::Vector3d& origin, std::span<const Eigen::Vector3f> directions,
            float min_range_m, float max_range_m, std::span<RayHit> hits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace campo
