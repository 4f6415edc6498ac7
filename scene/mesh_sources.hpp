#pragma once
/// Triangle meshes from files: OBJ, STL (ASCII and binary), PLY and glTF 2.0
/// (.gltf, .glb), read through assimp's C API. assimp is loaded with dlopen
/// on the first mesh read, so a process that reads no mesh never loads it.
/// Failures throw std::runtime_error with a message that says what was wrong
/// with the file (the scene loader adds the scene file and JSON pointer).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include <Eigen/Core>

#include "campo/config_fields.hpp"
#include "campo/scene.hpp"

namespace campo {

/// Which axis of the file points up. glTF 2.0 says +Y; OBJ, STL and PLY say
/// nothing, and the CAD and robotics tools that write them use +Z.
enum class MeshUpAxis : std::uint8_t {
  from_format,  ///< y for .gltf/.glb, z for the others
  z,            ///< the file's axes are the shape's axes
  y,            ///< +Y up: turned +90 degrees about x, so (x, y, z) -> (x, -z, y) (Blender's glTF convention)
};

/// The keys of a "mesh" object that say which file and how it is placed
/// (pose, static, mass_kg, friction and color are the keys every shape has).
struct MeshSourceConfig {
  std::string file;                                   ///< path, relative to the scene file
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();    ///< per axis of the shape, after up_axis; each in (0, 1e6]
  MeshUpAxis up_axis = MeshUpAxis::from_format;
};

/// The declarations of those keys (docs/scene-format.md's "mesh" table).
const ConfigFields<MeshSourceConfig>& mesh_source_fields();

/// Hostile-input limits of one mesh file, checked before assimp parses it
/// wherever the file declares its sizes (docs/limits.md).
struct MeshLimits {
  std::uintmax_t max_file_bytes = 128u << 20;  ///< bytes of the file (and of a glTF's buffers together)
  std::size_t max_triangles = 2'000'000;       ///< triangles the file declares or yields
  std::size_t max_vertices = 6'000'000;        ///< vertex records the file declares (3 per triangle of a soup)
  std::size_t max_nodes = 100'000;             ///< glTF scene-graph nodes
  int max_node_depth = 256;                    ///< glTF scene-graph nesting
};

/// A mesh as read, with what was dropped on the way.
struct MeshReadResult {
  TriangleMesh mesh;
  std::size_t degenerate_triangles = 0;  ///< zero-area triangles dropped
};

/// The file's triangles in one local frame: every node's transform applied
/// (parts of multi-part files where the file puts them), then `up_axis`, then
/// `scale`; exactly coincident vertices welded, degenerate triangles dropped.
/// `max_triangles` caps this mesh's triangles (what is left of a scene's
/// budget, at most limits.max_triangles). Refuses: a file over the limits,
/// a truncated or malformed file (assimp's message quoted), a vertex that is
/// not finite or beyond 1e6 m, and a mesh with no triangle left.
MeshReadResult read_triangle_mesh(const std::filesystem::path& path, const Eigen::Vector3d& scale,
                                  MeshUpAxis up_axis, const MeshLimits& limits, std::size_t max_triangles);

/// True when every edge of `triangles` is shared by exactly two of them.
bool is_closed_surface(const std::vector<std::array<std::uint32_t, 3>>& triangles);

}  // namespace campo
