#include "scene/scene_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

namespace campo {

namespace {

// Heightfield cells are emitted in square tiles of this many cells a side, so
// that consecutive triangles lie close together and a renderer can cull runs
// of them by their bounds.
constexpr int kTerrainTileCells = 8;

// Vertices and triangles a shape turns into, for reserving the buffers.
struct MeshSize {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
};

// Union-find over vertex indices, for the connected pieces of a mesh.
std::uint32_t root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

MeshFacing mesh_facing(const TriangleMesh& mesh) {
  MeshFacing facing;
  const std::size_t count = mesh.triangles.size();
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * count);
  const auto edge = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; };
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return facing;
    for (int k = 0; k < 3; ++k) edges.push_back(edge(t[k], t[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  // Closed and consistent: no directed edge twice, and every one has its reverse.
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return facing;
  for (const std::uint64_t e : edges) {
    if (!std::binary_search(edges.begin(), edges.end(), (e << 32) | (e >> 32))) return facing;
  }
  // Each piece faces out when its signed volume (about the bounds' centre, for precision) is positive.
  std::vector<std::uint32_t> parent(mesh.vertices_m.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  for (const auto& t : mesh.triangles) {
    parent[root(parent, t[1])] = root(parent, t[0]);
    parent[root(parent, t[2])] = root(parent, t[0]);
  }
  const Eigen::Vector3d centre = mesh.bounds_m.center();
  std::unordered_map<std::uint32_t, double> volume;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices_m[t[0]] - centre, b = mesh.vertices_m[t[1]] - centre,
                          c = mesh.vertices_m[t[2]] - centre;
    volume[root(parent, t[0])] += a.dot(b.cross(c));
  }
  facing.two_sided = false;
  facing.flip.resize(count);
  for (std::size_t i = 0; i < count; ++i) facing.flip[i] = volume[root(parent, mesh.triangles[i][0])] < 0.0;
  return facing;
}

namespace {

MeshSize mesh_size(const Shape& shape, int n, const MeshFacing* facing) {
  const auto segments = static_cast<std::size_t>(n);
  switch (shape.type) {
    case ShapeType::cuboid:
      return {24, 12};
    case ShapeType::cylinder:
      // Side rings, then two capped fans with a centre vertex each.
      return {4 * segments + 2, 4 * segments};
    case ShapeType::cone:
      // One apex vertex per side triangle (each with its own normal), base ring, base fan.
      return {3 * segments + 1, 2 * segments};
    case ShapeType::sphere: {
      const std::size_t rings = segments / 2;
      return {2 + (rings - 1) * segments, 2 * segments * (rings - 1)};
    }
    case ShapeType::plane:
      return {4, 2};
    case ShapeType::heightfield: {
      const auto cols = static_cast<std::size_t>(shape.terrain->cols);
      const auto rows = static_cast<std::size_t>(shape.terrain->rows);
      return {cols * rows, 2 * (cols - 1) * (rows - 1)};
    }
    case ShapeType::mesh: {
      // Flat shading: three vertices of its own per drawn triangle.
      const std::size_t drawn = (facing->two_sided ? 2 : 1) * shape.mesh->triangles.size();
      return {3 * drawn, drawn};
    }
  }
  return {};
}

// Appends vertices and triangles of one part, mapping local coordinates
// through `placement` (world pose, or identity for movers).
class PartWriter {
 public:
  PartWriter(SceneMesh& mesh, const Eigen::Isometry3d& placement)
      : mesh_(mesh),
        placement_(placement),
        base_(static_cast<std::uint32_t>(mesh.positions.size())) {}

  // Adds a vertex (local position, local unit normal); returns its index within the part.
  std::uint32_t vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& normal) {
    mesh_.positions.push_back((placement_ * position).cast<float>());
    mesh_.normals.push_back((placement_.linear() * normal).normalized().cast<float>());
    return static_cast<std::uint32_t>(mesh_.positions.size()) - 1 - base_;
  }
  // Counter-clockwise seen from outside.
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh_.indices.insert(mesh_.indices.end(), {base_ + a, base_ + b, base_ + c});
  }

 private:
  SceneMesh& mesh_;
  Eigen::Isometry3d placement_;
  std::uint32_t base_;
};

void add_cuboid(PartWriter& w, const Eigen::Vector3d& size) {
  const Eigen::Vector3d h = 0.5 * size;
  // Each face: its outward axis, then two in-face axes whose cross product is
  // that axis, so the corners below run counter-clockwise seen from outside.
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n[axis] = sign;
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      u[(axis + 1) % 3] = 1.0;
      v[(axis + 2) % 3] = sign;
      const Eigen::Vector3d centre = n.cwiseProduct(h);
      const Eigen::Vector3d du = u.cwiseProduct(h);
      const Eigen::Vector3d dv = v.cwiseProduct(h);
      const std::uint32_t a = w.vertex(centre - du - dv, n);
      const std::uint32_t b = w.vertex(centre + du - dv, n);
      const std::uint32_t c = w.vertex(centre + du + dv, n);
      const std::uint32_t d = w.vertex(centre - du + dv, n);
      w.triangle(a, b, c);
      w.triangle(a, c, d);
    }
  }
}

// Point k of n around a circle of radius r at height z, starting on +x.
Eigen::Vector3d ring_point(int k, int n, double r, double z) {
  const double a = 2.0 * std::numbers::pi * k / n;
  return {r * std::cos(a), r * std::sin(a), z};
}

// A flat disc at height z facing `facing_up` (+z) or down, as a fan.
void add_cap(PartWriter& w, int n, double r, double z, bool facing_up) {
  const Eigen::Vector3d normal(0.0, 0.0, facing_up ? 1.0 : -1.0);
  const std::uint32_t centre = w.vertex({0.0, 0.0, z}, normal);
  const std::uint32_t first = w.vertex(ring_point(0, n, r, z), normal);
  for (int k = 1; k < n; ++k) w.vertex(ring_point(k, n, r, z), normal);
  for (int k = 0; k < n; ++k) {
    const std::uint32_t a = first + static_cast<std::uint32_t>(k);
    const std::uint32_t b = first + static_cast<std::uint32_t>((k + 1) % n);
    if (facing_up) {
      w.triangle(centre, a, b);
    } else {
      w.triangle(centre, b, a);
    }
  }
}

void add_cylinder(PartWriter& w, int n, double r, double height) {
  const double hz = 0.5 * height;
  // Side: bottom and top ring, interleaved, with radial normals.
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d radial = ring_point(k, n, 1.0, 0.0);
    w.vertex(ring_point(k, n, r, -hz), radial);
    w.vertex(ring_point(k, n, r, hz), radial);
  }
  for (int k = 0; k < n; ++k) {
    const auto b0 = static_cast<std::uint32_t>(2 * k);
    const auto b1 = static_cast<std::uint32_t>(2 * ((k + 1) % n));
    w.triangle(b0, b1, b1 + 1);
    w.triangle(b0, b1 + 1, b0 + 1);
  }
  add_cap(w, n, r, -hz, false);
  add_cap(w, n, r, hz, true);
}

void add_cone(PartWriter& w, int n, double r, double height) {
  const double hz = 0.5 * height;
  // The side normal leans up by the half-angle of the cone.
  const auto side_normal = [&](double angle) {
    return Eigen::Vector3d(height * std::cos(angle), height * std::sin(angle), r).normalized();
  };
  for (int k = 0; k < n; ++k) {
    w.vertex(ring_point(k, n, r, -hz), side_normal(2.0 * std::numbers::pi * k / n));
  }
  // An apex vertex per side triangle, its normal midway between the two base vertices'.
  for (int k = 0; k < n; ++k) {
    const std::uint32_t apex = w.vertex({0.0, 0.0, hz}, side_normal(2.0 * std::numbers::pi * (k + 0.5) / n));
    w.triangle(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>((k + 1) % n), apex);
  }
  add_cap(w, n, r, -hz, false);
}

void add_sphere(PartWriter& w, int n, double r) {
  const int rings = n / 2;
  const std::uint32_t south = w.vertex({0.0, 0.0, -r}, -Eigen::Vector3d::UnitZ());
  // Latitude circles j = 1 .. rings-1, n vertices each.
  for (int j = 1; j < rings; ++j) {
    const double latitude = std::numbers::pi * (static_cast<double>(j) / rings - 0.5);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d unit =
          ring_point(k, n, std::cos(latitude), 0.0) + Eigen::Vector3d(0.0, 0.0, std::sin(latitude));
      w.vertex(r * unit, unit);
    }
  }
  const std::uint32_t north = w.vertex({0.0, 0.0, r}, Eigen::Vector3d::UnitZ());
  const auto at = [n](int circle, int k) {
    return static_cast<std::uint32_t>(1 + (circle - 1) * n + k % n);
  };
  for (int k = 0; k < n; ++k) {
    w.triangle(south, at(1, k + 1), at(1, k));
    for (int j = 1; j + 1 < rings; ++j) {
      w.triangle(at(j, k), at(j, k + 1), at(j + 1, k + 1));
      w.triangle(at(j, k), at(j + 1, k + 1), at(j + 1, k));
    }
    w.triangle(north, at(rings - 1, k), at(rings - 1, k + 1));
  }
}

void add_plane(PartWriter& w, double half_extent) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const double e = half_extent;
  const std::uint32_t a = w.vertex({-e, -e, 0.0}, n);
  const std::uint32_t b = w.vertex({e, -e, 0.0}, n);
  const std::uint32_t c = w.vertex({e, e, 0.0}, n);
  const std::uint32_t d = w.vertex({-e, e, 0.0}, n);
  w.triangle(a, b, c);
  w.triangle(a, c, d);
}

void add_heightfield(PartWriter& w, const HeightGrid& g) {
  const auto x = [&g](int c) { return (c - 0.5 * (g.cols - 1)) * g.spacing_x_m; };
  const auto y = [&g](int r) { return (r - 0.5 * (g.rows - 1)) * g.spacing_y_m; };
  // Smooth normals from central differences (one-sided on the border).
  for (int r = 0; r < g.rows; ++r) {
    const int r0 = std::max(r - 1, 0);
    const int r1 = std::min(r + 1, g.rows - 1);
    for (int c = 0; c < g.cols; ++c) {
      const int c0 = std::max(c - 1, 0);
      const int c1 = std::min(c + 1, g.cols - 1);
      const double dhdx = (g.at(c1, r) - g.at(c0, r)) / (x(c1) - x(c0));
      const double dhdy = (g.at(c, r1) - g.at(c, r0)) / (y(r1) - y(r0));
      w.vertex({x(c), y(r), g.at(c, r)}, Eigen::Vector3d(-dhdx, -dhdy, 1.0).normalized());
    }
  }
  const auto at = [&g](int c, int r) { return static_cast<std::uint32_t>(r * g.cols + c); };
  for (int tr = 0; tr < g.rows - 1; tr += kTerrainTileCells) {
    for (int tc = 0; tc < g.cols - 1; tc += kTerrainTileCells) {
      for (int r = tr; r < std::min(tr + kTerrainTileCells, g.rows - 1); ++r) {
        for (int c = tc; c < std::min(tc + kTerrainTileCells, g.cols - 1); ++c) {
          // Split along the diagonal (c+1, r)-(c, r+1), as Bullet does.
          w.triangle(at(c, r), at(c + 1, r), at(c, r + 1));
          w.triangle(at(c + 1, r), at(c + 1, r + 1), at(c, r + 1));
        }
      }
    }
  }
}

// A file's triangles with flat normals; degenerate ones (no area, no normal) are left out.
void add_triangle_mesh(PartWriter& w, const TriangleMesh& mesh, const MeshFacing& facing) {
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    Eigen::Vector3d a = mesh.vertices_m[t[0]], b = mesh.vertices_m[t[1]], c = mesh.vertices_m[t[2]];
    if (!facing.two_sided && facing.flip[i]) std::swap(b, c);
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double norm = cross.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) continue;
    const Eigen::Vector3d n = cross / norm;
    const std::uint32_t ia = w.vertex(a, n), ib = w.vertex(b, n), ic = w.vertex(c, n);
    w.triangle(ia, ib, ic);
    if (facing.two_sided) {
      const std::uint32_t ja = w.vertex(a, -n), jb = w.vertex(b, -n), jc = w.vertex(c, -n);
      w.triangle(ja, jc, jb);
    }
  }
}

void add_shape(SceneMesh& mesh, const Shape& shape, const Eigen::Isometry3d& placement,
               const MeshOptions& options, const MeshFacing* facing) {
  PartWriter w(mesh, placement);
  const int n = options.round_segments;
  switch (shape.type) {
    case ShapeType::cuboid:
      add_cuboid(w, shape.size_m);
      break;
    case ShapeType::cylinder:
      add_cylinder(w, n, shape.radius_m, shape.height_m);
      break;
    case ShapeType::cone:
      add_cone(w, n, shape.radius_m, shape.height_m);
      break;
    case ShapeType::sphere:
      add_sphere(w, n, shape.radius_m);
      break;
    case ShapeType::plane:
      add_plane(w, options.plane_half_extent_m);
      break;
    case ShapeType::heightfield:
      add_heightfield(w, *shape.terrain);
      break;
    case ShapeType::mesh:
      add_triangle_mesh(w, *shape.mesh, *facing);
      break;
  }
}

}  // namespace

SceneMesh build_scene_mesh(const Scene& scene, const MeshOptions& options) {
  if (options.round_segments < 8) {
    throw std::invalid_argument("build_scene_mesh: round_segments must be >= 8, got " +
                                std::to_string(options.round_segments));
  }
  if (!(options.plane_half_extent_m > 0.0)) {
    throw std::invalid_argument("build_scene_mesh: plane_half_extent_m must be > 0");
  }
  // How each distinct TriangleMesh is drawn, worked out once (shapes may share one).
  std::unordered_map<const TriangleMesh*, MeshFacing> facings;
  const auto facing_of = [&](const Shape& shape) -> const MeshFacing* {
    if (shape.type != ShapeType::mesh) return nullptr;
    auto it = facings.find(shape.mesh.get());
    if (it == facings.end()) it = facings.emplace(shape.mesh.get(), mesh_facing(*shape.mesh)).first;
    return &it->second;
  };
  MeshSize total;
  const auto count = [&](const Shape& shape) {
    const MeshSize s = mesh_size(shape, options.round_segments, facing_of(shape));
    total.vertices += s.vertices;
    total.triangles += s.triangles;
  };
  for (const Shape& shape : scene.shapes) count(shape);
  for (const Mover& mover : scene.movers) count(mover.shape);

  SceneMesh mesh;
  mesh.positions.reserve(total.vertices);
  mesh.normals.reserve(total.vertices);
  mesh.indices.reserve(3 * total.triangles);
  mesh.parts.reserve(scene.shapes.size());
  const std::vector<MovingBody> bodies = moving_bodies(scene);
  mesh.moving_parts.reserve(bodies.size());

  const auto add_part = [&](std::vector<MeshPart>& parts, const Shape& shape, int id,
                            const Eigen::Isometry3d& placement) {
    const auto first = static_cast<std::uint32_t>(mesh.indices.size());
    add_shape(mesh, shape, placement, options, facing_of(shape));
    parts.push_back({first, static_cast<std::uint32_t>(mesh.indices.size()) - first, shape.color, id});
  };
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    if (scene.shapes[i].is_static) add_part(mesh.parts, scene.shapes[i], static_cast<int>(i), scene.shapes[i].pose);
  }
  // Moving bodies stay in their shape frame: a renderer places them where the world has them.
  for (const MovingBody& body : bodies) {
    add_part(mesh.moving_parts, *body.shape, body.id, Eigen::Isometry3d::Identity());
  }
  return mesh;
}

}  // namespace campo
