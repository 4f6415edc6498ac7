#pragma once
/// Private helpers of render/ for off-screen OpenGL with OSMesa (llvmpipe):
/// an owned context, RAII names of GL objects, shader programs, frame
/// buffers and a SceneMesh on the GPU. Every GL call needs the owning
/// context current on the calling thread; an owner of GL names makes its
/// context current in its destructor so the names are deleted there.
#include "sensors/gl_api.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "scene/scene_mesh.hpp"

namespace campo {

/// An OSMesa OpenGL 4.5 core context. Draws go to frame buffer objects, so
/// its own window buffer is a single pixel.
class OsmesaContext {
 public:
  /// Throws std::runtime_error when OSMesa cannot make the context.
  OsmesaContext();
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  /// Binds the context to the calling thread (cheap when it already is);
  /// throws std::runtime_error on failure.
  void make_current();
  /// The same for destructors: false on failure.
  bool bind() noexcept;

 private:
  OSMesaContext context_ = nullptr;
  std::uint32_t window_pixel_ = 0;  // RGBA8 window buffer of 1 x 1
};

/// Owns one GL object name; `Delete` releases it in the current context.
template <void (*Delete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  ~GlName() {
    if (id_ != 0) Delete(id_);
  }
  GlName(GlName&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      if (id_ != 0) Delete(id_);
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;

  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

inline void gl_delete_buffer(GLuint id) { gl().DeleteBuffers(1, &id); }
inline void gl_delete_vertex_array(GLuint id) { gl().DeleteVertexArrays(1, &id); }
inline void gl_delete_framebuffer(GLuint id) { gl().DeleteFramebuffers(1, &id); }
inline void gl_delete_renderbuffer(GLuint id) { gl().DeleteRenderbuffers(1, &id); }

inline void gl_delete_program(GLuint id) { gl().DeleteProgram(id); }
inline void gl_delete_shader(GLuint id) { gl().DeleteShader(id); }

using GlBuffer = GlName<&gl_delete_buffer>;
using GlVertexArray = GlName<&gl_delete_vertex_array>;
using GlFramebuffer = GlName<&gl_delete_framebuffer>;
using GlRenderbuffer = GlName<&gl_delete_renderbuffer>;
using GlProgram = GlName<&gl_delete_program>;

/// Throws std::runtime_error naming `what` if GL has recorded an error.
void check_gl(const char* what);

/// Compiles and links a program from GLSL sources; throws std::runtime_error
/// with the compiler log on failure.
GlProgram make_program(const char* vertex_source, const char* fragment_source);

/// A frame buffer with optional colour and depth render buffers.
struct Framebuffer {
  GlFramebuffer fbo;
  GlRenderbuffer colour;
  GlRenderbuffer depth;
};

/// A complete frame buffer of width x height pixels; a format of 0 leaves
/// that attachment out; samples > 1 makes it multisampled.
Framebuffer make_framebuffer(int width_px, int height_px, GLenum colour_format, GLenum depth_format,
                             int samples = 1);

/// Throws std::invalid_argument "<what> needs a render of W x H px, more
/// than ... OpenGL allows" when either side exceeds GL_MAX_RENDERBUFFER_SIZE.
void check_render_size(int width_px, int height_px, const std::string& what);

/// The cameras' near plane when their minimum range is 0, m: closer surfaces
/// are not seen.
inline constexpr double kSmallestNear_m = 1e-3;

/// The projection of a pinhole view (eye frame: looking along -z, x right, y
/// up; the image plane at z = -1 reaching +-half_width, +-half_height) to
/// reversed depth in [0, 1] (with use_reversed_depth): window depth
/// d = near (far - z) / ((far - near) z), 1 at the near plane, 0 at the far
/// one, affine in 1/z and so in screen position across any planar triangle;
/// floats keep their precision where 1/z is small, far from the eye.
Eigen::Matrix4f reversed_depth_projection(double half_width, double half_height, double near_m, double far_m);

/// Sets the current context's state for reversed_depth_projection (zero-to-one
/// clip depth, GL_GREATER, depth cleared to 0) over a viewport of width x
/// height, without dithering or multisampling (sensor images are exact and
/// deterministic) and with tightly packed rows for glReadPixels.
void use_reversed_depth(int width_px, int height_px);

/// The index runs of one glMultiDrawElements: runs of triangles added in
/// index order, each merged with the one before when they are adjacent.
/// Reserve once; adding and clearing then allocate nothing.
class DrawRuns {
 public:
  void reserve(std::size_t runs) {
    counts_.reserve(runs);
    offsets_.reserve(runs);
  }
  void clear() {
    counts_.clear();
    offsets_.clear();
  }
  bool empty() const { return counts_.empty(); }
  void add(std::uint32_t first_index, std::uint32_t index_count) {
    if (!counts_.empty() && first_index == end_) {
      counts_.back() += static_cast<GLsizei>(index_count);
    } else {
      counts_.push_back(static_cast<GLsizei>(index_count));
      offsets_.push_back(reinterpret_cast<const void*>(std::size_t{first_index} * sizeof(std::uint32_t)));
    }
    end_ = first_index + index_count;
  }
  /// Draws the runs as triangles of 32-bit indices of the bound vertex array.
  void draw() const {
    gl().MultiDrawElements(GL_TRIANGLES, counts_.data(), GL_UNSIGNED_INT, offsets_.data(),
                           static_cast<GLsizei>(counts_.size()));
  }

 private:
  std::vector<GLsizei> counts_;
  std::vector<const void*> offsets_;
  std::uint32_t end_ = 0;  // one past the last index of the last run
};

/// A mesh in GPU buffers: attribute 0 = position, 1 = normal (when uploaded).
struct GpuMesh {
  GlVertexArray vao;
  GlBuffer positions;
  GlBuffer normals;
  GlBuffer indices;
};

/// Uploads the mesh once into static buffers; leaves its vertex array bound.
GpuMesh upload_mesh(const SceneMesh& mesh, bool with_normals);

}  // namespace campo
