#pragma once
/// Batched ray casting against the scene geometry: exactly the shapes the
/// Bullet world collides with (analytic primitives, and the heightfield
/// triangulated the way Bullet triangulates it), and mesh shapes as their
/// triangles, two-sided and watertight (a dynamic mesh too, though Bullet
/// collides it as its convex hull). Two methods, same answers: an Embree BVH
/// traversed ray by ray, and for the many rays of a scan from one origin a
/// RayFan (sensors/ray_fan.hpp), where each surface in range is projected
/// onto the rays that may hit it; a mesh is not projected: the fan's rays
/// that meet its bounding sphere go through its own BVH.
#include <cstdint>
#include <memory>
#include <span>

#include <Eigen/Geometry>

#include "campo/scene.hpp"

namespace campo {

/// Result of one ray: distance along the ray, or no hit.
struct RayHit {
  float distance_m;     ///< +infinity when nothing was hit within range
  std::int32_t shape;   ///< index into Scene::shapes, or -(1 + mover index); kNoShape for no hit
  static constexpr std::int32_t kNoShape = INT32_MIN;
};

class RayFan;

/// How RayCaster::cast finds hits. `automatic` casts a RayFan by projection
/// when the CPU has AVX2 and the fan holds many rays for the geometry in
/// range (primitives, heightfield cells and mesh triangles), and otherwise
/// ray by ray through Embree; the others force a method (tests, benchmarks).
enum class CastMethod { automatic, embree, fan };

class RayCaster {
 public:
  /// Builds the acceleration structure: the static shapes once, and the
  /// moving bodies (moving_bodies(scene)) at their poses at t = 0.
  /// `scene` must outlive the caster. CastMethod::fan throws
  /// std::runtime_error on a CPU without AVX2 and FMA.
  explicit RayCaster(const Scene& scene, CastMethod method = CastMethod::automatic);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Places the moving bodies: one world-frame pose per moving_bodies(scene)
  /// entry, in that order (World::moving_body_poses, or scripted_poses).
  /// Throws std::invalid_argument for a wrong count.
  void set_poses(std::span<const Eigen::Isometry3d> poses);

  /// Casts one ray per direction from `origin`; directions are unit vectors in
  /// the world frame. Hits nearer than min_range_m are ignored (the ray
  /// continues); hits beyond max_range_m are misses. No allocation, except
  /// with CastMethod::fan, which bins the directions into a RayFan first.
  void cast(const Eigen::Vector3d& origin, std::span<const Eigen::Vector3f> directions,
            float min_range_m, float max_range_m, std::span<RayHit> hits) const;
  /// The same for a fan of directions given in the sensor frame, cast from
  /// `sensor_pose` (world frame); hits in the fan's direction order. Buffers
  /// are kept per thread: no allocation once they have grown.
  void cast(const Eigen::Isometry3d& sensor_pose, const RayFan& fan, float min_range_m, float max_range_m,
            std::span<RayHit> hits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace campo
