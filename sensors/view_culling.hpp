#pragma once
/// Private helpers of the OSMesa sensors (depth camera, colour camera): the
/// scene mesh cut into runs of triangles with their bounds, and the test of a
/// run against a perspective view, so a frame draws only what it may see.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "scene/scene_mesh.hpp"

namespace campo {

/// A run of triangles with its bounds (mesh frame): a sphere to cull against
/// the view, a box to tell how near the eye it comes.
struct Chunk {
  std::uint32_t first_index = 0;
  std::uint32_t index_count = 0;
  Eigen::AlignedBox3f box;
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  float radius = 0.0f;
  std::uint32_t part = 0;  ///< index of its part in the list it was cut from
};

/// The bounds of indices [first, first + count) of `mesh`.
Chunk bound(const SceneMesh& mesh, std::uint32_t first, std::uint32_t count);

/// The cameras cull static geometry in runs of this many triangles (two
/// heightfield tiles, a cylinder, a band of a sphere).
inline constexpr std::uint32_t kCullChunkTriangles = 256;

/// `parts` (of `mesh`) cut into runs of at most `max_triangles` triangles, in
/// index-buffer order; each run records the index of its part in `parts`.
std::vector<Chunk> cut_into_chunks(const SceneMesh& mesh, const std::vector<MeshPart>& parts,
                                   std::uint32_t max_triangles);

/// A plane or heightfield: a surface with no inside, seen from below too.
struct OpenSurface {
  const Shape* shape = nullptr;
  double top_m = 0.0;  ///< local z of its highest point: 0 for a plane
};

/// Whether back faces may be culled for an eye at `eye` (world frame). The
/// ray caster's surfaces are two-sided, but the first surface along any ray
/// faces the eye when the eye is outside every closed shape (`solids`, static,
/// mesh frame = world; `movers`, each in its shape frame, placed by
/// `mover_poses`) and above every heightfield and plane (`open_surfaces`). A
/// heightfield has no walls: outside its footprint the eye must be above its
/// highest point.
bool back_faces_hidden(const Eigen::Vector3d& eye, const std::vector<Chunk>& solids, const std::vector<Chunk>& movers,
                       const std::vector<Eigen::Isometry3d>& mover_poses, const std::vector<OpenSurface>& open_surfaces);

/// The eye frame (GL's: looking along -z, x right, y up) of a sensor at
/// `sensor_pose` (world frame; x forward, y left, z up) from the world frame.
inline Eigen::Isometry3d eye_from_world_at(const Eigen::Isometry3d& sensor_pose) {
  Eigen::Isometry3d eye_from_sensor = Eigen::Isometry3d::Identity();
  eye_from_sensor.linear() << 0, -1, 0, 0, 0, 1, -1, 0, 0;
  return eye_from_sensor * sensor_pose.inverse();
}

/// A perspective view in the eye frame (looking along -z, x right, y up) out
/// to `far_m`, its image plane at z = -1 reaching +-half_width and
/// +-half_height.
class ViewVolume {
 public:
  ViewVolume() = default;
  ViewVolume(double half_width, double half_height, double far_m);
  /// False when a sphere (centre in the eye frame) lies wholly outside.
  bool may_see(const Eigen::Vector3f& centre, float radius) const {
    if (centre.norm() - radius > far_m_) return false;
    for (const Eigen::Vector4f& plane : side_planes_) {
      if (plane.head<3>().dot(centre) > radius) return false;
    }
    return true;
  }

 private:
  Eigen::Vector4f side_planes_[4];  // unit normals pointing out
  float far_m_ = 0.0f;
};

}  // namespace campo
