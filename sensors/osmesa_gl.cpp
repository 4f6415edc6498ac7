#include "sensors/osmesa_gl.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace campo {

OsmesaContext::OsmesaContext() {
  // (key, value) pairs; no depth buffer of its own: frame buffer objects have theirs.
  const int attributes[] = {
      OSMESA_FORMAT, OSMESA_RGBA,
      OSMESA_DEPTH_BITS, 0,
      OSMESA_PROFILE, OSMESA_CORE_PROFILE,
      OSMESA_CONTEXT_MAJOR_VERSION, 4,
      OSMESA_CONTEXT_MINOR_VERSION, 5,
      0};
  context_ = gl().CreateContextAttribs(attributes, nullptr);
  if (!context_) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
  if (!bind()) {
    gl().DestroyContext(context_);
    throw std::runtime_error("OSMesa: cannot make the context current");
  }
}

OsmesaContext::~OsmesaContext() {
  if (gl().GetCurrentContext() == context_) gl().MakeCurrent(nullptr, nullptr, 0, 0, 0);
  gl().DestroyContext(context_);
}

bool OsmesaContext::bind() noexcept {
  return gl().MakeCurrent(context_, &window_pixel_, GL_UNSIGNED_BYTE, 1, 1) == GL_TRUE;
}

void OsmesaContext::make_current() {
  if (!bind()) throw std::runtime_error("OSMesa: cannot make the context current");
}

void check_gl(const char* what) {
  const GLenum error = gl().GetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", error);
    throw std::runtime_error(std::string("OpenGL error ") + code + " while " + what);
  }
}

namespace {

// A shader object; once attached, the program keeps it alive.
using GlShader = GlName<&gl_delete_shader>;

GlShader compile(GLenum stage, const char* source) {
  GlShader shader(gl().CreateShader(stage));
  gl().ShaderSource(shader.id(), 1, &source, nullptr);
  gl().CompileShader(shader.id());
  GLint ok = GL_FALSE;
  gl().GetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    gl().GetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl().GetShaderInfoLog(shader.id(), length, nullptr, log.data());
    throw std::runtime_error("OpenGL: shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

GlProgram make_program(const char* vertex_source, const char* fragment_source) {
  const GlShader vertex = compile(GL_VERTEX_SHADER, vertex_source);
  const GlShader fragment = compile(GL_FRAGMENT_SHADER, fragment_source);
  GlProgram program(gl().CreateProgram());
  gl().AttachShader(program.id(), vertex.id());
  gl().AttachShader(program.id(), fragment.id());
  gl().LinkProgram(program.id());
  GLint ok = GL_FALSE;
  gl().GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    gl().GetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl().GetProgramInfoLog(program.id(), length, nullptr, log.data());
    throw std::runtime_error("OpenGL: program does not link: " + log);
  }
  return program;
}

Framebuffer make_framebuffer(int width_px, int height_px, GLenum colour_format, GLenum depth_format,
                             int samples) {
  Framebuffer fb;
  GLuint id = 0;
  gl().GenFramebuffers(1, &id);
  fb.fbo = GlFramebuffer(id);
  gl().BindFramebuffer(GL_FRAMEBUFFER, id);
  const auto attach = [&](GLenum format, GLenum attachment) {
    GLuint rb = 0;
    gl().GenRenderbuffers(1, &rb);
    gl().BindRenderbuffer(GL_RENDERBUFFER, rb);
    if (samples > 1) {
      gl().RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width_px, height_px);
    } else {
      gl().RenderbufferStorage(GL_RENDERBUFFER, format, width_px, height_px);
    }
    gl().FramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, rb);
    return GlRenderbuffer(rb);
  };
  if (colour_format != 0) {
    fb.colour = attach(colour_format, GL_COLOR_ATTACHMENT0);
  } else {
    gl().DrawBuffer(GL_NONE);
    gl().ReadBuffer(GL_NONE);
  }
  if (depth_format != 0) fb.depth = attach(depth_format, GL_DEPTH_ATTACHMENT);
  if (gl().CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("OpenGL: frame buffer of " + std::to_string(width_px) + " x " +
                             std::to_string(height_px) + " px is incomplete");
  }
  check_gl("making a frame buffer");
  return fb;
}

void check_render_size(int width_px, int height_px, const std::string& what) {
  GLint max_size = 0;
  gl().GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width_px > max_size || height_px > max_size) {
    throw std::invalid_argument(what + " needs a render of " + std::to_string(width_px) + " x " +
                                std::to_string(height_px) + " px, more than the " + std::to_string(max_size) +
                                " px a side OpenGL allows; use fewer pixels or a narrower field of view");
  }
}

Eigen::Matrix4f reversed_depth_projection(double half_width, double half_height, double near_m, double far_m) {
  const double n = near_m;
  const double d = far_m;
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = 1.0 / half_width;
  p(1, 1) = 1.0 / half_height;
  p(2, 2) = n / (d - n);
  p(2, 3) = n * d / (d - n);
  p(3, 2) = -1.0;
  return p.cast<float>();
}

void use_reversed_depth(int width_px, int height_px) {
  gl().ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  gl().Viewport(0, 0, width_px, height_px);
  gl().Enable(GL_DEPTH_TEST);
  gl().DepthFunc(GL_GREATER);
  gl().ClearDepth(0.0);
  gl().Disable(GL_DITHER);
  gl().Disable(GL_MULTISAMPLE);
  gl().PixelStorei(GL_PACK_ALIGNMENT, 1);
}

GpuMesh upload_mesh(const SceneMesh& mesh, bool with_normals) {
  GpuMesh gpu;
  GLuint id = 0;
  gl().GenVertexArrays(1, &id);
  gpu.vao = GlVertexArray(id);
  gl().BindVertexArray(id);
  const auto buffer = [](GLenum target, std::size_t bytes, const void* data) {
    GLuint name = 0;
    gl().GenBuffers(1, &name);
    gl().BindBuffer(target, name);
    gl().BufferData(target, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
    return GlBuffer(name);
  };
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));
  gpu.positions = buffer(GL_ARRAY_BUFFER, mesh.positions.size() * sizeof(Eigen::Vector3f), mesh.positions.data());
  gl().VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl().EnableVertexAttribArray(0);
  if (with_normals) {
    gpu.normals = buffer(GL_ARRAY_BUFFER, mesh.normals.size() * sizeof(Eigen::Vector3f), mesh.normals.data());
    gl().VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl().EnableVertexAttribArray(1);
  }
  gpu.indices =
      buffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.size() * sizeof(std::uint32_t), mesh.indices.data());
  check_gl("uploading a mesh");
  return gpu;
}

}  // namespace campo
