#pragma once
/// Private helpers of render/ for off-screen OpenGL with OSMesa (llvmpipe):
/// an owned context, RAII names of GL objects, shader programs, frame
/// buffers and a SceneMesh on the GPU. Every GL call needs the owning
/// context current on the calling thread; an owner of GL names makes its
/// context current in its destructor so the names are deleted there.
#include "sensors/gl_api.hpp"

#include <cstdint>
#include <utility>

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
