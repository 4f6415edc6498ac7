#include "scene/mesh_sources.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <unordered_map>
#include <string_view>
#include <utility>

#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <dlfcn.h>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"

namespace campo {

namespace {

// ---------------------------------------------------------------------------
// assimp, loaded on first use.

struct AssimpApi {
  decltype(&aiImportFileExWithProperties) import_file = nullptr;
  decltype(&aiReleaseImport) release_import = nullptr;
  decltype(&aiGetErrorString) error_string = nullptr;
  decltype(&aiCreatePropertyStore) create_properties = nullptr;
  decltype(&aiSetImportPropertyInteger) set_integer = nullptr;
  decltype(&aiReleasePropertyStore) release_properties = nullptr;
};

AssimpApi load_assimp() {
  // Never closed: the library stays for the process's life, like OSMesa (sensors/gl_api.cpp).
  void* const library = dlopen("libassimp.so.5", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    throw std::runtime_error(std::string("cannot read meshes: cannot load libassimp.so.5 (Debian libassimp5): ") +
                             dlerror());
  }
  const auto symbol = [library](const char* name) {
    void* const address = dlsym(library, name);
    if (address == nullptr) throw std::runtime_error(std::string("cannot read meshes: libassimp.so.5 has no ") + name);
    return address;
  };
  AssimpApi api;
  api.import_file = reinterpret_cast<decltype(api.import_file)>(symbol("aiImportFileExWithProperties"));
  api.release_import = reinterpret_cast<decltype(api.release_import)>(symbol("aiReleaseImport"));
  api.error_string = reinterpret_cast<decltype(api.error_string)>(symbol("aiGetErrorString"));
  api.create_properties = reinterpret_cast<decltype(api.create_properties)>(symbol("aiCreatePropertyStore"));
  api.set_integer = reinterpret_cast<decltype(api.set_integer)>(symbol("aiSetImportPropertyInteger"));
  api.release_properties = reinterpret_cast<decltype(api.release_properties)>(symbol("aiReleasePropertyStore"));
  return api;
}

const AssimpApi& assimp() {
  static const AssimpApi api = load_assimp();
  return api;
}

// assimp's C API keeps its last error in a global: one import at a time.
std::mutex& assimp_mutex() {
  static std::mutex mutex;
  return mutex;
}

// ---------------------------------------------------------------------------
// What a file declares, read before assimp parses it: a file that declares
// more than the limits is refused before anything is allocated for it.

enum class Format { obj, stl, ply, gltf, glb };

struct Declared {
  std::size_t triangles = 0;
  std::size_t vertices = 0;
};

[[noreturn]] void refuse(const std::string& what) { throw std::runtime_error(what); }

std::string count_text(std::size_t n) { return std::to_string(n); }

void check_declared(const Declared& d, const MeshLimits& limits, std::size_t max_triangles) {
  if (d.vertices > limits.max_vertices) {
    refuse("the file declares " + count_text(d.vertices) + " vertices, more than the limit of " +
           count_text(limits.max_vertices));
  }
  if (d.triangles > max_triangles) {
    refuse("the file declares " + count_text(d.triangles) + " triangles, more than the limit of " +
           count_text(max_triangles) +
           (max_triangles < limits.max_triangles
                ? " (what is left of the scene's " + count_text(limits.max_triangles) + " triangles in all meshes)"
                : std::string()));
  }
}

bool starts_with_word(std::string_view line, std::string_view word) {
  return line.size() > word.size() && line.substr(0, word.size()) == word &&
         (line[word.size()] == ' ' || line[word.size()] == '\t');
}

// A file a mesh names (an OBJ's material library, a glTF's buffer or image),
// which assimp opens itself: it must be a regular file if it exists (a FIFO
// or a device would block or never end); a missing one assimp reports.
void check_side_file(const std::filesystem::path& mesh, std::string_view name, const char* what) {
  std::filesystem::path side(std::string{name});
  if (side.is_relative()) side = mesh.parent_path() / side;
  std::error_code ec;
  if (std::filesystem::exists(side, ec) && !std::filesystem::is_regular_file(side, ec)) {
    refuse(std::string("a mesh whose ") + what + " is a regular file, but \"" + side.string() + "\" is not");
  }
}

// OBJ: "v" lines are vertices; an "f" line of n corners is n - 2 triangles.
Declared scan_obj(const std::string& bytes, const std::filesystem::path& path, const MeshLimits& limits,
                  std::size_t max_triangles) {
  Declared d;
  std::size_t at = 0;
  while (at < bytes.size()) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    std::string_view line(bytes.data() + at, end - at);
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    if (starts_with_word(line, "mtllib")) {
      std::string_view name = line.substr(7);
      while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.remove_suffix(1);
      while (!name.empty() && std::isspace(static_cast<unsigned char>(name.front()))) name.remove_prefix(1);
      if (!name.empty()) check_side_file(path, name, "material library (mtllib)");
    } else if (starts_with_word(line, "v")) {
      ++d.vertices;
    } else if (starts_with_word(line, "f")) {
      std::size_t corners = 0;
      bool in_token = false;
      for (std::size_t i = 1; i < line.size(); ++i) {
        const bool space = line[i] == ' ' || line[i] == '\t' || line[i] == '\r';
        if (!space && !in_token) ++corners;
        in_token = !space;
      }
      if (corners >= 3) d.triangles += corners - 2;
    }
    if (d.vertices > limits.max_vertices || d.triangles > max_triangles) break;  // enough to refuse
    at = end + 1;
  }
  return d;
}

std::uint32_t read_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
  return v;  // little-endian, as STL and GLB store it
}

bool begins_with_solid(const std::string& bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  return bytes.compare(i, 5, "solid") == 0;
}

// STL: binary when the size is exactly the header's count of 50-byte
// records; otherwise ASCII if it begins "solid", each "vertex" a corner.
Declared scan_stl(const std::string& bytes, const MeshLimits& limits, std::size_t max_triangles) {
  Declared d;
  const bool sized_binary = bytes.size() >= 84 && 84 + 50 * static_cast<std::uint64_t>(read_u32(bytes, 80)) == bytes.size();
  if (sized_binary || !begins_with_solid(bytes)) {
    if (bytes.size() < 84) {
      refuse("a truncated binary STL: " + count_text(bytes.size()) +
             " bytes, less than its 84-byte header (an ASCII STL begins with \"solid\")");
    }
    const std::uint64_t count = read_u32(bytes, 80);
    d.triangles = static_cast<std::size_t>(count);
    d.vertices = 0;  // three per record, counted as triangles
    check_declared(d, limits, max_triangles);
    const std::uint64_t needed = 84 + 50 * count;
    if (bytes.size() < needed) {
      refuse("a truncated binary STL: its header declares " + count_text(d.triangles) + " triangles (" +
             std::to_string(needed) + " bytes), the file has " + count_text(bytes.size()) + " bytes");
    }
    return d;
  }
  std::size_t corners = 0;
  for (std::size_t at = bytes.find("vertex"); at != std::string::npos; at = bytes.find("vertex", at + 6)) {
    if (++corners / 3 > max_triangles) break;
  }
  d.triangles = corners / 3;
  return d;
}

// PLY: the header's "element vertex N" and "element face N" (a face is at least one triangle).
Declared scan_ply(const std::string& bytes) {
  Declared d;
  const std::size_t header_end = bytes.find("end_header");
  if (bytes.compare(0, 3, "ply") != 0 || header_end == std::string::npos || header_end > (1u << 20)) {
    refuse("a PLY file beginning \"ply\" with a header that ends \"end_header\" within 1 MiB");
  }
  std::size_t at = 0;
  while (at < header_end) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos || end > header_end) end = header_end;
    std::string_view line(bytes.data() + at, end - at);
    if (line.substr(0, 8) == "element ") {
      line.remove_prefix(8);
      const std::size_t space = line.find(' ');
      if (space != std::string_view::npos) {
        const std::string_view name = line.substr(0, space);
        double count = 0.0;
        try {
          count = std::stod(std::string(line.substr(space + 1)));
        } catch (const std::exception&) {
          refuse("a PLY header whose \"element " + std::string(name) + "\" has a count");
        }
        if (!(count >= 0.0)) refuse("a PLY header whose element counts are >= 0");
        const auto n = static_cast<std::size_t>(std::min(count, 1e18));
        if (name == "vertex") d.vertices += n;
        if (name == "face") d.triangles += n;
      }
    }
    at = end + 1;
  }
  return d;
}

// glTF: the JSON's mesh primitives (a POSITION accessor and optional
// indices), buffers and scene graph, checked before assimp reads them.
Declared scan_gltf_json(const std::string& text, const std::filesystem::path& path, const MeshLimits& limits) {
  nlohmann::json doc;
  try {
    // The reader's own limits: nesting depth (assimp's JSON parser recurses), file size.
    doc = parse_json_text(text, path.string(), InputLimits{limits.max_file_bytes, 64});
  } catch (const std::exception& e) {
    refuse(std::string("glTF whose JSON reads: ") + e.what());
  }
  if (!doc.is_object()) refuse("glTF whose JSON is an object");
  const auto array = [&doc](const char* key) -> const nlohmann::json& {
    static const nlohmann::json kEmpty = nlohmann::json::array();
    const auto it = doc.find(key);
    return it != doc.end() && it->is_array() ? *it : kEmpty;
  };
  const nlohmann::json& accessors = array("accessors");
  const auto accessor_count = [&accessors](const nlohmann::json& index) -> std::size_t {
    if (!index.is_number_unsigned() || index.get<std::size_t>() >= accessors.size()) return 0;
    const nlohmann::json& a = accessors[index.get<std::size_t>()];
    const auto count = a.is_object() ? a.find("count") : a.end();
    if (count == a.end() || !count->is_number()) return 0;
    const double n = count->get<double>();
    return n > 0.0 ? static_cast<std::size_t>(std::min(n, 1e18)) : 0;
  };
  Declared d;
  for (const nlohmann::json& mesh : array("meshes")) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (const nlohmann::json& p : mesh["primitives"]) {
      if (!p.is_object()) continue;
      const int mode = p.contains("mode") && p["mode"].is_number_integer() ? p["mode"].get<int>() : 4;
      std::size_t positions = 0;
      if (p.contains("attributes") && p["attributes"].is_object() && p["attributes"].contains("POSITION")) {
        positions = accessor_count(p["attributes"]["POSITION"]);
      }
      const std::size_t corners = p.contains("indices") ? accessor_count(p["indices"]) : positions;
      d.vertices += positions;
      if (mode == 4) d.triangles += corners / 3;
      if ((mode == 5 || mode == 6) && corners >= 3) d.triangles += corners - 2;
    }
  }
  for (const char* key : {"buffers", "images"}) {
    for (const nlohmann::json& item : array(key)) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.rfind("data:", 0) != 0) check_side_file(path, uri, key[0] == 'b' ? "buffer file" : "image file");
    }
  }
  double buffer_bytes = 0.0;
  for (const nlohmann::json& b : array("buffers")) {
    if (b.is_object() && b.contains("byteLength") && b["byteLength"].is_number()) {
      buffer_bytes += std::max(0.0, b["byteLength"].get<double>());
    }
  }
  if (buffer_bytes > static_cast<double>(limits.max_file_bytes)) {
    refuse("glTF buffers of " + std::to_string(static_cast<std::uint64_t>(buffer_bytes)) +
           " bytes, more than the limit of " + std::to_string(limits.max_file_bytes));
  }
  // The node graph: a forest (one parent each, no cycle), not too deep.
  const nlohmann::json& nodes = array("nodes");
  if (nodes.size() > limits.max_nodes) {
    refuse("glTF with " + count_text(nodes.size()) + " nodes, more than the limit of " + count_text(limits.max_nodes));
  }
  std::vector<long> parent(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].is_object() || !nodes[i].contains("children") || !nodes[i]["children"].is_array()) continue;
    for (const nlohmann::json& child : nodes[i]["children"]) {
      if (!child.is_number_unsigned() || child.get<std::size_t>() >= nodes.size()) {
        refuse("glTF whose node " + count_text(i) + " has children that are node indices");
      }
      const std::size_t c = child.get<std::size_t>();
      if (parent[c] >= 0 || c == i) refuse("glTF whose node " + count_text(c) + " has at most one parent");
      parent[c] = static_cast<long>(i);
    }
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    int depth = 0;
    for (long at = parent[i]; at >= 0; at = parent[static_cast<std::size_t>(at)]) {
      if (++depth > limits.max_node_depth) {
        refuse("glTF whose nodes nest at most " + std::to_string(limits.max_node_depth) +
               " deep (node " + count_text(i) + " is deeper, or in a cycle)");
      }
    }
  }
  return d;
}

Declared scan_glb(const std::string& bytes, const std::filesystem::path& path, const MeshLimits& limits) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) {
    refuse("a GLB file: a 12-byte header beginning \"glTF\" and a JSON chunk");
  }
  const std::uint32_t length = read_u32(bytes, 8);
  if (length > bytes.size()) {
    refuse("a complete GLB file: its header declares " + std::to_string(length) + " bytes, the file has " +
           count_text(bytes.size()));
  }
  const std::uint32_t json_length = read_u32(bytes, 12);
  if (read_u32(bytes, 16) != 0x4E4F534Au || 20 + static_cast<std::uint64_t>(json_length) > bytes.size()) {
    refuse("a GLB file whose first chunk is its JSON, complete");
  }
  return scan_gltf_json(bytes.substr(20, json_length), path, limits);
}

// ---------------------------------------------------------------------------

Format format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") return Format::obj;
  if (ext == ".stl") return Format::stl;
  if (ext == ".ply") return Format::ply;
  if (ext == ".gltf") return Format::gltf;
  if (ext == ".glb") return Format::glb;
  refuse("a mesh file ending .obj, .stl, .ply, .gltf or .glb, not \"" + path.filename().string() + "\"");
}

std::string read_bytes(const std::filesystem::path& path, const MeshLimits& limits) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) refuse("a mesh file, but \"" + path.string() + "\" is not a file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) refuse("a readable mesh file: " + ec.message());
  if (size == 0) refuse("a mesh file, but \"" + path.string() + "\" is empty");
  if (size > limits.max_file_bytes) {
    refuse("a mesh file of at most " + std::to_string(limits.max_file_bytes) + " bytes, \"" + path.string() +
           "\" has " + std::to_string(size));
  }
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) refuse("a readable mesh file \"" + path.string() + "\"");
  return bytes;
}

// Exactly equal positions share one vertex (-0 and +0 alike), so parts and
// flat-shaded faces of one surface connect.
struct PositionHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (int i = 0; i < 3; ++i) {
      h ^= std::bit_cast<std::uint64_t>(p[i] + 0.0) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    }
    return static_cast<std::size_t>(h);
  }
};
struct PositionEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return a == b; }
};

constexpr double kMaxCoordinate_m = 1e6;  // as every position of a scene

class MeshBuilder {
 public:
  MeshBuilder(const Eigen::Matrix3d& frame, std::size_t max_triangles, const MeshLimits& limits)
      : frame_(frame), max_triangles_(max_triangles), limits_(limits) {}

  void add(const aiMesh& mesh, const Eigen::Matrix4d& node, std::size_t mesh_index) {
    if (mesh.mNumFaces == 0 || mesh.mVertices == nullptr) return;
    if (out_.triangles.size() + mesh.mNumFaces > max_triangles_) {
      refuse("a mesh of at most " + count_text(max_triangles_) + " triangles, but its parts (as the file's nodes place them) have more" +
             (max_triangles_ < limits_.max_triangles
                  ? " (what is left of the scene's " + count_text(limits_.max_triangles) + " triangles in all meshes)"
                  : std::string()));
    }
    // Every vertex of this part in the shape's frame, checked.
    const Eigen::Matrix3d linear = frame_ * node.topLeftCorner<3, 3>();
    const Eigen::Vector3d offset = frame_ * node.topRightCorner<3, 1>();
    positions_.resize(mesh.mNumVertices);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& v = mesh.mVertices[i];
      const Eigen::Vector3d file(v.x, v.y, v.z);
      if (!file.allFinite()) {
        refuse("finite vertices, but vertex " + std::to_string(i) + " of part " + count_text(mesh_index) +
               " is not a number or infinite");
      }
      positions_[i] = linear * file + offset;
      if (!positions_[i].allFinite() || positions_[i].cwiseAbs().maxCoeff() > kMaxCoordinate_m) {
        refuse("vertices within 1e6 m of the mesh's origin (after scale), but vertex " + std::to_string(i) +
               " of part " + count_text(mesh_index) + " is not");
      }
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines: not surfaces
      std::array<std::uint32_t, 3> corners{};
      bool valid = true;
      for (int k = 0; k < 3; ++k) {
        const unsigned index = face.mIndices[k];
        if (index >= mesh.mNumVertices) {
          valid = false;
          break;
        }
        corners[static_cast<std::size_t>(k)] = index;
      }
      if (!valid) refuse("faces whose indices name vertices, but a face of part " + count_text(mesh_index) + " does not");
      const Eigen::Vector3d& a = positions_[corners[0]];
      const Eigen::Vector3d& b = positions_[corners[1]];
      const Eigen::Vector3d& c = positions_[corners[2]];
      const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      // Zero area: its height over the longest edge is nothing at double precision.
      if ((b - a).cross(c - a).norm() <= 1e-12 * longest || longest == 0.0) {
        ++degenerate_;
        continue;
      }
      out_.triangles.push_back({index_of(a), index_of(b), index_of(c)});
    }
  }

  MeshReadResult finish() {
    MeshReadResult result;
    result.degenerate_triangles = degenerate_;
    if (out_.triangles.empty()) {
      refuse(degenerate_ > 0 ? "a mesh with triangles, but all " + count_text(degenerate_) + " of its triangles have zero area"
                             : std::string("a mesh with triangles, but the file has none"));
    }
    for (const Eigen::Vector3d& v : out_.vertices_m) out_.bounds_m.extend(v);
    out_.closed = is_closed_surface(out_.triangles);
    result.mesh = std::move(out_);
    return result;
  }

 private:
  std::uint32_t index_of(const Eigen::Vector3d& p) {
    const auto [it, inserted] = index_.try_emplace(p, static_cast<std::uint32_t>(out_.vertices_m.size()));
    if (inserted) out_.vertices_m.push_back(p);
    return it->second;
  }

  Eigen::Matrix3d frame_;
  std::size_t max_triangles_;
  const MeshLimits& limits_;
  TriangleMesh out_;
  std::size_t degenerate_ = 0;
  std::vector<Eigen::Vector3d> positions_;  // scratch: one part's vertices
  std::unordered_map<Eigen::Vector3d, std::uint32_t, PositionHash, PositionEqual> index_;
};

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

// The imported scene, released however the reading ends.
struct ImportedScene {
  const aiScene* scene = nullptr;
  ~ImportedScene() {
    if (scene) assimp().release_import(scene);
  }
};

}  // namespace

const ConfigFields<MeshSourceConfig>& mesh_source_fields() {
  using C = MeshSourceConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .text("file", &C::file,
                "required: the mesh file, relative to the scene file: OBJ (.obj), STL ASCII or binary (.stl), PLY "
                "(.ply), glTF 2.0 (.gltf, .glb); its units are metres")
          .custom(
              "scale", "", "a number > 0, or [sx, sy, sz] each > 0; at most 1e6",
              "multiplies the file's coordinates (one number: all three axes), along the shape's axes after "
              "`up_axis`",
              [](const JsonNode& n, C& c) {
                const Range range{0.0, 1e6, true, false};
                c.scale = n.value().is_number() ? Eigen::Vector3d::Constant(n.as_number(range)) : n.as_vector3(range);
              },
              [](const C& c, nlohmann::json& j) {
                if (c.scale.x() == c.scale.y() && c.scale.y() == c.scale.z()) {
                  j["scale"] = c.scale.x();
                } else {
                  j["scale"] = {c.scale.x(), c.scale.y(), c.scale.z()};
                }
              })
          .choice("up_axis", &C::up_axis,
                  {{"format", MeshUpAxis::from_format}, {"z", MeshUpAxis::z}, {"y", MeshUpAxis::y}},
                  "which axis of the file is up: `z` keeps the file's axes; `y` turns +Y up to +Z (x stays, "
                  "y -> z, z -> -y: a glTF or a Blender export comes out as Blender shows it); `format`: `y` for "
                  "glTF/GLB (the glTF standard), `z` for OBJ, STL and PLY");
  return fields;
}

bool is_closed_surface(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      edges.push_back(std::min(a, b) << 32 | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) return false;
    i = j;
  }
  return !edges.empty();
}

MeshReadResult read_triangle_mesh(const std::filesystem::path& path, const Eigen::Vector3d& scale,
                                  MeshUpAxis up_axis, const MeshLimits& limits, std::size_t max_triangles) {
  max_triangles = std::min(max_triangles, limits.max_triangles);
  const Format format = format_of(path);
  std::string bytes = read_bytes(path, limits);
  // The sizes the file declares, before assimp allocates for them.
  Declared declared;
  switch (format) {
    case Format::obj: declared = scan_obj(bytes, path, limits, max_triangles); break;
    case Format::stl: declared = scan_stl(bytes, limits, max_triangles); break;
    case Format::ply: declared = scan_ply(bytes); break;
    case Format::gltf: declared = scan_gltf_json(bytes, path, limits); break;
    case Format::glb: declared = scan_glb(bytes, path, limits); break;
  }
  check_declared(declared, limits, max_triangles);
  const std::string sha256 = sha256_hex(bytes);
  std::string().swap(bytes);  // assimp reads the file itself: not held twice

  if (up_axis == MeshUpAxis::from_format) {
    up_axis = format == Format::gltf || format == Format::glb ? MeshUpAxis::y : MeshUpAxis::z;
  }
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  if (up_axis == MeshUpAxis::y) frame << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // +90 degrees about x
  frame = scale.asDiagonal() * frame;

  const AssimpApi& api = assimp();
  std::lock_guard<std::mutex> lock(assimp_mutex());
  aiPropertyStore* properties = api.create_properties();
  // Points and lines are dropped, not kept as meshes; no skeleton stand-ins.
  // No aiProcess_JoinIdenticalVertices: the builder welds coincident
  // positions itself (across parts too), and assimp's pass would double the
  // memory of a large triangle soup (a binary STL) while it runs.
  api.set_integer(properties, AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  api.set_integer(properties, AI_CONFIG_IMPORT_NO_SKELETON_MESHES, 1);
  ImportedScene imported;
  imported.scene = api.import_file(path.c_str(),
                                   aiProcess_Triangulate | aiProcess_SortByPType |
                                       aiProcess_ValidateDataStructure,
                                   nullptr, properties);
  api.release_properties(properties);
  if (imported.scene == nullptr) {
    const char* why = api.error_string();
    refuse(std::string("a mesh file that assimp reads, but it says: ") + (why && *why ? why : "(no reason given)"));
  }
  const aiScene& scene = *imported.scene;
  if ((scene.mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene.mRootNode == nullptr || scene.mNumMeshes == 0) {
    refuse("a mesh with triangles, but the file has none");
  }
  MeshBuilder builder(frame, max_triangles, limits);
  // Each node's meshes where the node puts them: walked without recursion.
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack{{scene.mRootNode, to_eigen(scene.mRootNode->mTransformation)}};
  std::size_t nodes = 0;
  while (!stack.empty()) {
    const auto [node, transform] = stack.back();
    stack.pop_back();
    if (++nodes > limits.max_nodes) {
      refuse("a mesh of at most " + count_text(limits.max_nodes) + " scene-graph nodes");
    }
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const unsigned index = node->mMeshes[m];
      if (index < scene.mNumMeshes && scene.mMeshes[index] != nullptr) builder.add(*scene.mMeshes[index], transform, index);
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren[c];
      if (child != nullptr) stack.emplace_back(child, transform * to_eigen(child->mTransformation));
    }
  }
  MeshReadResult result = builder.finish();
  result.mesh.source_path = path.string();
  result.mesh.source_sha256 = sha256;
  return result;
}

}  // namespace campo
