#pragma once
// Small mesh files written by the tests themselves: a box and a closed
// cylinder as OBJ, STL (ASCII, binary), PLY (ASCII, binary) and glTF 2.0
// (.gltf with an embedded buffer, .glb), written from the formats'
// specifications (not through assimp, which reads them).
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace campo::test_support {

struct SimpleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// A box of full extents `size`, centred on the origin: 8 vertices, 12 triangles.
inline SimpleMesh box_mesh(const Eigen::Vector3d& size = Eigen::Vector3d::Ones()) {
  SimpleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                            (i & 4 ? 0.5 : -0.5) * size.z());
  }
  // Each face as a quad (counter-clockwise from outside), split in two.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}

/// A closed cylinder about z, centred on the origin: `segments` around, capped
/// by fans about a centre vertex: 2 * segments + 2 vertices, 4 * segments triangles.
inline SimpleMesh cylinder_mesh(double radius, double height, int segments) {
  SimpleMesh m;
  const auto n = static_cast<std::uint32_t>(segments);
  for (int ring = 0; ring < 2; ++ring) {
    for (int i = 0; i < segments; ++i) {
      const double a = 2.0 * std::numbers::pi * i / segments;
      m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), (ring == 0 ? -0.5 : 0.5) * height);
    }
  }
  m.vertices.emplace_back(0.0, 0.0, -0.5 * height);
  m.vertices.emplace_back(0.0, 0.0, 0.5 * height);
  const std::uint32_t bottom = 2 * n, top = 2 * n + 1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
    m.triangles.push_back({bottom, j, i});
    m.triangles.push_back({top, n + i, n + j});
  }
  return m;
}

// A fresh directory of this process's own under the temporary directory. CTest
// runs every test in a process of its own, two at a time: a fixed name shared
// by several tests let one read a file another was still writing.
inline std::filesystem::path process_temp_dir(const std::string& stem) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (stem + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

inline std::string obj_text(const SimpleMesh& m) {
  std::ostringstream s;
  s.precision(17);
  s << "# written by campo's tests\no part\n";
  for (const auto& v : m.vertices) s << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : m.triangles) s << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  return s.str();
}

inline Eigen::Vector3d face_normal(const SimpleMesh& m, const std::array<std::uint32_t, 3>& t) {
  const Eigen::Vector3d n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
  return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
}

inline std::string stl_ascii_text(const SimpleMesh& m) {
  std::ostringstream s;
  s.precision(9);
  s << "solid part\n";
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = face_normal(m, t);
    s << "  facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n    outer loop\n";
    for (const std::uint32_t i : t) {
      s << "      vertex " << m.vertices[i].x() << ' ' << m.vertices[i].y() << ' ' << m.vertices[i].z() << '\n';
    }
    s << "    endloop\n  endfacet\n";
  }
  s << "endsolid part\n";
  return s.str();
}

inline void append_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
inline void append_f32(std::string& out, double value) {
  const auto f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  append_u32(out, bits);
}

/// Binary STL; `declared` overrides the header's triangle count (a lying header).
inline std::string stl_binary_bytes(const SimpleMesh& m, long declared = -1) {
  std::string out(80, ' ');
  out.replace(0, 14, "binary by test");
  append_u32(out, static_cast<std::uint32_t>(declared >= 0 ? declared : static_cast<long>(m.triangles.size())));
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = face_normal(m, t);
    for (int k = 0; k < 3; ++k) append_f32(out, n[k]);
    for (const std::uint32_t i : t) {
      for (int k = 0; k < 3; ++k) append_f32(out, m.vertices[i][k]);
    }
    out += std::string(2, '\0');  // attribute byte count
  }
  return out;
}

inline std::string ply_ascii_text(const SimpleMesh& m) {
  std::ostringstream s;
  s.precision(17);
  s << "ply\nformat ascii 1.0\nelement vertex " << m.vertices.size()
    << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << m.triangles.size()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : m.vertices) s << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : m.triangles) s << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  return s.str();
}

inline std::string ply_binary_bytes(const SimpleMesh& m) {
  std::ostringstream s;
  s << "ply\nformat binary_little_endian 1.0\nelement vertex " << m.vertices.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangles.size()
    << "\nproperty list uchar uint vertex_indices\nend_header\n";
  std::string out = s.str();
  for (const auto& v : m.vertices) {
    for (int k = 0; k < 3; ++k) append_f32(out, v[k]);
  }
  for (const auto& t : m.triangles) {
    out += static_cast<char>(3);
    for (const std::uint32_t i : t) append_u32(out, i);
  }
  return out;
}

inline std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

/// glTF 2.0: one mesh (float positions, uint32 indices) placed by `nodes_json`
/// (the "nodes" array; the scene's roots are `roots_json`, e.g. "[0]").
/// `glb`: the binary container; else JSON with the buffer as a data URI.
inline std::string gltf_bytes(const SimpleMesh& m, bool glb, const std::string& nodes_json = R"([{"mesh": 0}])",
                              const std::string& roots_json = "[0]") {
  std::string buffer;
  Eigen::Vector3d lo = m.vertices.front(), hi = lo;
  for (const auto& v : m.vertices) {
    for (int k = 0; k < 3; ++k) append_f32(buffer, v[k]);
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const std::size_t positions_bytes = buffer.size();
  for (const auto& t : m.triangles) {
    for (const std::uint32_t i : t) append_u32(buffer, i);
  }
  std::ostringstream j;
  j.precision(9);
  j << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" << roots_json << R"(}], "nodes": )" << nodes_json
    << R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],)"
    << R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" << m.vertices.size()
    << R"(, "type": "VEC3", "min": [)" << lo.x() << ", " << lo.y() << ", " << lo.z() << "], \"max\": [" << hi.x() << ", "
    << hi.y() << ", " << hi.z() << "]}, "
    << R"({"bufferView": 1, "componentType": 5125, "count": )" << 3 * m.triangles.size() << R"(, "type": "SCALAR"}],)"
    << R"( "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )" << positions_bytes << "}, "
    << R"({"buffer": 0, "byteOffset": )" << positions_bytes << R"(, "byteLength": )" << buffer.size() - positions_bytes
    << "}], \"buffers\": [{\"byteLength\": " << buffer.size();
  if (!glb) {
    j << R"(, "uri": "data:application/octet-stream;base64,)" << base64(buffer) << "\"}]}";
    return j.str();
  }
  j << "}]}";
  std::string json = j.str();
  while (json.size() % 4 != 0) json += ' ';
  while (buffer.size() % 4 != 0) buffer += '\0';
  std::string out = "glTF";
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + buffer.size()));
  append_u32(out, static_cast<std::uint32_t>(json.size()));
  out += "JSON";
  out += json;
  append_u32(out, static_cast<std::uint32_t>(buffer.size()));
  out += std::string("BIN\0", 4);
  out += buffer;
  return out;
}

}  // namespace campo::test_support
