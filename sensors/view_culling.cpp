#include "sensors/view_culling.hpp"

#include <optional>

#include <algorithm>

namespace campo {

Chunk bound(const SceneMesh& mesh, std::uint32_t first, std::uint32_t count) {
  Eigen::AlignedBox3f box;
  for (std::uint32_t i = first; i < first + count; ++i) box.extend(mesh.positions[mesh.indices[i]]);
  Chunk chunk{first, count, box, box.center(), 0.0f, 0};
  for (std::uint32_t i = first; i < first + count; ++i) {
    chunk.radius = std::max(chunk.radius, (mesh.positions[mesh.indices[i]] - chunk.centre).norm());
  }
  return chunk;
}

std::vector<Chunk> cut_into_chunks(const SceneMesh& mesh, const std::vector<MeshPart>& parts,
                                   std::uint32_t max_triangles) {
  std::vector<Chunk> chunks;
  const std::uint32_t max_indices = 3 * max_triangles;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const MeshPart& part = parts[p];
    for (std::uint32_t done = 0; done < part.index_count; done += max_indices) {
      Chunk chunk = bound(mesh, part.first_index + done, std::min(max_indices, part.index_count - done));
      chunk.part = static_cast<std::uint32_t>(p);
      chunks.push_back(chunk);
    }
  }
  return chunks;
}

ViewVolume::ViewVolume(double half_width, double half_height, double far_m) : far_m_(static_cast<float>(far_m)) {
  const auto plane = [](double x, double y, double z) {
    return Eigen::Vector4f(Eigen::Vector4d(x, y, z, 0.0).normalized().cast<float>());
  };
  side_planes_[0] = plane(1.0, 0.0, half_width);
  side_planes_[1] = plane(-1.0, 0.0, half_width);
  side_planes_[2] = plane(0.0, 1.0, half_height);
  side_planes_[3] = plane(0.0, -1.0, half_height);
}

bool back_faces_hidden(const Eigen::Vector3d& eye, const std::vector<Chunk>& solids, const std::vector<Chunk>& movers,
                       const std::vector<Eigen::Isometry3d>& mover_poses, const std::vector<OpenSurface>& open_surfaces) {
  const Eigen::Vector3f eye_f = eye.cast<float>();
  for (const Chunk& solid : solids) {
    if (solid.box.contains(eye_f)) return false;
  }
  for (std::size_t i = 0; i < movers.size(); ++i) {
    if (movers[i].box.contains((mover_poses[i].inverse() * eye).cast<float>())) return false;
  }
  for (const OpenSurface& surface : open_surfaces) {
    const Eigen::Vector3d local = surface.shape->pose.inverse() * eye;
    if (local.z() > surface.top_m) continue;
    if (surface.shape->type == ShapeType::plane) return false;
    const std::optional<double> ground = surface.shape->terrain->height_at(local.x(), local.y());
    if (!ground || local.z() <= *ground) return false;
  }
  return true;
}

}  // namespace campo
