#pragma once
/// The OpenGL and OSMesa entry points campo uses, loaded from libOSMesa on
/// first use rather than linked: OSMesa brings LLVM (tens of megabytes and
/// dozens of libraries) into every process that links it, and only runs
/// with a depth camera or a snapshot need it. Call GL as gl().Name(...).
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

namespace campo {

/// The GL functions campo calls: X(name without "gl", type of its pointer).
/// GL 1.0/1.1 functions have no PFNGL type: their declarations give it.
#define CAMPO_GL_FUNCTIONS(X) \
  X(AttachShader, PFNGLATTACHSHADERPROC) \
  X(BindBuffer, PFNGLBINDBUFFERPROC) \
  X(BindFramebuffer, PFNGLBINDFRAMEBUFFERPROC) \
  X(BindRenderbuffer, PFNGLBINDRENDERBUFFERPROC) \
  X(BindVertexArray, PFNGLBINDVERTEXARRAYPROC) \
  X(BlitFramebuffer, PFNGLBLITFRAMEBUFFERPROC) \
  X(BufferData, PFNGLBUFFERDATAPROC) \
  X(CheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC) \
  X(Clear, decltype(&glClear)) \
  X(ClearColor, decltype(&glClearColor)) \
  X(ClearDepth, decltype(&glClearDepth)) \
  X(ClipControl, PFNGLCLIPCONTROLPROC) \
  X(CompileShader, PFNGLCOMPILESHADERPROC) \
  X(CreateProgram, PFNGLCREATEPROGRAMPROC) \
  X(CreateShader, PFNGLCREATESHADERPROC) \
  X(DeleteBuffers, PFNGLDELETEBUFFERSPROC) \
  X(DeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC) \
  X(DeleteProgram, PFNGLDELETEPROGRAMPROC) \
  X(DeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC) \
  X(DeleteShader, PFNGLDELETESHADERPROC) \
  X(DeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC) \
  X(DepthFunc, decltype(&glDepthFunc)) \
  X(Disable, decltype(&glDisable)) \
  X(DrawBuffer, decltype(&glDrawBuffer)) \
  X(DrawElements, decltype(&glDrawElements)) \
  X(Enable, decltype(&glEnable)) \
  X(EnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC) \
  X(FramebufferRenderbuffer, PFNGLFRAMEBUFFERRENDERBUFFERPROC) \
  X(GenBuffers, PFNGLGENBUFFERSPROC) \
  X(GenFramebuffers, PFNGLGENFRAMEBUFFERSPROC) \
  X(GenRenderbuffers, PFNGLGENRENDERBUFFERSPROC) \
  X(GenVertexArrays, PFNGLGENVERTEXARRAYSPROC) \
  X(GetError, decltype(&glGetError)) \
  X(GetIntegerv, decltype(&glGetIntegerv)) \
  X(GetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC) \
  X(GetProgramiv, PFNGLGETPROGRAMIVPROC) \
  X(GetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC) \
  X(GetShaderiv, PFNGLGETSHADERIVPROC) \
  X(LinkProgram, PFNGLLINKPROGRAMPROC) \
  X(MultiDrawElements, PFNGLMULTIDRAWELEMENTSPROC) \
  X(PixelStorei, decltype(&glPixelStorei)) \
  X(ReadBuffer, decltype(&glReadBuffer)) \
  X(ReadPixels, decltype(&glReadPixels)) \
  X(RenderbufferStorage, PFNGLRENDERBUFFERSTORAGEPROC) \
  X(RenderbufferStorageMultisample, PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC) \
  X(ShaderSource, PFNGLSHADERSOURCEPROC) \
  X(Uniform1f, PFNGLUNIFORM1FPROC) \
  X(Uniform2f, PFNGLUNIFORM2FPROC) \
  X(Uniform3f, PFNGLUNIFORM3FPROC) \
  X(UniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC) \
  X(UseProgram, PFNGLUSEPROGRAMPROC) \
  X(VertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC) \
  X(Viewport, decltype(&glViewport))

struct GlApi {
  decltype(&OSMesaCreateContextAttribs) CreateContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) MakeCurrent = nullptr;
  decltype(&OSMesaGetCurrentContext) GetCurrentContext = nullptr;
  decltype(&OSMesaDestroyContext) DestroyContext = nullptr;
#define CAMPO_GL_MEMBER(name, type) type name = nullptr;
  CAMPO_GL_FUNCTIONS(CAMPO_GL_MEMBER)
#undef CAMPO_GL_MEMBER
};

/// The entry points; loads libOSMesa the first time (thread-safe). Throws
/// std::runtime_error naming the library or the entry point it lacks.
const GlApi& gl();

}  // namespace campo
