#pragma once
// Triangle meshes built in code for the tests of mesh shapes (ray caster,
// depth camera, figures, replays): a cuboid, a faceted cylinder and an
// icosphere, counter-clockwise seen from outside, vertices shared between
// triangles as a file would share them.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "campo/scene.hpp"

namespace campo::test_support {

inline std::shared_ptr<TriangleMesh> finished(TriangleMesh mesh, bool closed) {
  mesh.bounds_m.setEmpty();
  for (const Eigen::Vector3d& v : mesh.vertices_m) mesh.bounds_m.extend(v);
  mesh.closed = closed;
  mesh.source_path = "built in code";
  return std::make_shared<TriangleMesh>(std::move(mesh));
}

/// A cuboid of full extents `size` centred on the origin: 8 vertices, 12 triangles.
inline std::shared_ptr<TriangleMesh> cuboid_mesh(const Eigen::Vector3d& size = Eigen::Vector3d::Ones()) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices_m.emplace_back((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                              (i & 4 ? 0.5 : -0.5) * size.z());
  }
  // Vertex i has x from bit 0, y from bit 1, z from bit 2; two triangles a face.
  m.triangles = {{0, 2, 3}, {0, 3, 1},   // z = -0.5, facing -z
                 {4, 5, 7}, {4, 7, 6},   // z = +0.5
                 {0, 1, 5}, {0, 5, 4},   // y = -0.5
                 {2, 6, 7}, {2, 7, 3},   // y = +0.5
                 {0, 4, 6}, {0, 6, 2},   // x = -0.5
                 {1, 3, 7}, {1, 7, 5}};  // x = +0.5
  return finished(std::move(m), true);
}

/// A cylinder of radius r and height h about local z, centred on the origin:
/// `segments` around (vertices on the circle), capped by fans from a centre vertex.
inline std::shared_ptr<TriangleMesh> cylinder_mesh(double r = 0.5, double h = 1.0, int segments = 512) {
  TriangleMesh m;
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::uint32_t k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    m.vertices_m.emplace_back(r * std::cos(a), r * std::sin(a), -0.5 * h);  // 2k: bottom
    m.vertices_m.emplace_back(r * std::cos(a), r * std::sin(a), 0.5 * h);   // 2k + 1: top
  }
  const std::uint32_t bottom = 2 * n, top = 2 * n + 1;
  m.vertices_m.emplace_back(0.0, 0.0, -0.5 * h);
  m.vertices_m.emplace_back(0.0, 0.0, 0.5 * h);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t b0 = 2 * k, b1 = 2 * ((k + 1) % n);
    m.triangles.push_back({b0, b1, b1 + 1});
    m.triangles.push_back({b0, b1 + 1, b0 + 1});
    m.triangles.push_back({bottom, b1, b0});
    m.triangles.push_back({top, b0 + 1, b1 + 1});
  }
  return finished(std::move(m), true);
}

/// An icosahedron of radius r subdivided `levels` times (20 * 4^levels
/// triangles), every vertex pushed out to the sphere.
inline std::shared_ptr<TriangleMesh> icosphere_mesh(double r = 1.0, int levels = 4) {
  TriangleMesh m;
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  for (const auto& v : std::vector<Eigen::Vector3d>{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                                    {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                                    {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}}) {
    m.vertices_m.push_back(r * v.normalized());
  }
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    const auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = middle.emplace(key, static_cast<std::uint32_t>(m.vertices_m.size()));
      if (added) m.vertices_m.push_back(r * (m.vertices_m[a] + m.vertices_m[b]).normalized());
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& t : m.triangles) {
      const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  return finished(std::move(m), true);
}

/// A mesh shape at `pose`.
inline Shape mesh_shape(std::shared_ptr<const TriangleMesh> mesh, const Eigen::Isometry3d& pose,
                        const Color& color = {}) {
  Shape s;
  s.type = ShapeType::mesh;
  s.alias = "mesh";
  s.mesh = std::move(mesh);
  s.pose = pose;
  s.color = color;
  return s;
}

}  // namespace campo::test_support
