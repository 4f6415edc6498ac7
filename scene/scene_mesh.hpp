#pragma once
/// One triangle-mesh view of a Scene, built once and shared by everything
/// that draws or renders it (the OSMesa depth camera, colour snapshots).
/// Heightfields use exactly the triangles Bullet collides with; boxes are
/// exact; round shapes are tessellated finely enough for centimetre agreement
/// with the ray-cast LIDAR; mesh shapes are their own triangles, flat-shaded,
/// drawn once facing out when closed and consistently wound, else from both
/// sides (as the ray caster sees them).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "campo/scene.hpp"

namespace campo {

struct MeshOptions {
  int round_segments = 64;             ///< segments around cylinders, cones and spheres, >= 8
  double plane_half_extent_m = 2000.0; ///< planes become squares this far from their origin
};

/// A run of triangles of one scene shape.
struct MeshPart {
  std::uint32_t first_index = 0;  ///< into SceneMesh::indices
  std::uint32_t index_count = 0;
  Color color;
  int shape = 0;  ///< index into Scene::shapes, or -(1 + mover index)
};

struct SceneMesh {
  std::vector<Eigen::Vector3f> positions;  ///< static shapes: world frame; moving bodies: their shape frame
  std::vector<Eigen::Vector3f> normals;    ///< unit, per vertex (flat for boxes and meshes, smooth for round shapes)
  std::vector<std::uint32_t> indices;      ///< counter-clockwise triangles seen from outside
  std::vector<MeshPart> parts;             ///< static shapes, in scene order
  std::vector<MeshPart> moving_parts;      ///< one per moving_bodies(scene) entry, in that order
                                           ///< (place with World::moving_body_poses or scripted_poses)
  std::size_t triangle_count() const { return indices.size() / 3; }
};

SceneMesh build_scene_mesh(const Scene& scene, const MeshOptions& options = {});

/// How a TriangleMesh's triangles face. A closed mesh whose every edge runs
/// once each way between its two triangles has an outside: its triangles are
/// drawn once, turned (per connected piece) so that they run
/// counter-clockwise seen from outside, and back faces may be culled (by the
/// renderers, and by the ray caster while the sensor is outside the mesh).
/// Any other mesh (open, or wound inconsistently) is two-sided: it is drawn
/// from both sides, each triangle twice, the second reversed.
struct MeshFacing {
  bool two_sided = true;
  std::vector<bool> flip;  ///< per triangle, when one-sided: reverse its winding to face out
};

MeshFacing mesh_facing(const TriangleMesh& mesh);

}  // namespace campo
