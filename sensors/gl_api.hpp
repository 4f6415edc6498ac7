#pragma once
/// The OpenGL and OSMesa entry points campo uses, loaded from libOSMesa on
/// first use rather than linked: OSMesa brings LLVM (tens of megabytes and
/// dozens of libraries) into every process that links it, and only runs
/// with a depth camera or a snapshot need it. Call GL as gl().Name(...).
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

namespace campo {

struct GlApi {
  decltype(&OSMesaCreateContextAttribs) CreateContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) MakeCurrent = nullptr;
  decltype(&OSMesaGetCurrentContext) GetCurrentContext = nullptr;
  decltype(&OSMesaDestroyContext) DestroyContext = nullptr;
  PFNGLATTACHSHADERPROC AttachShader = nullptr;
  PFNGLBINDBUFFERPROC BindBuffer = nullptr;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
  PFNGLBINDRENDERBUFFERPROC BindRenderbuffer = nullptr;
  PFNGLBINDVERTEXARRAYPROC BindVertexArray = nullptr;
  PFNGLBLITFRAMEBUFFERPROC BlitFramebuffer = nullptr;
  PFNGLBUFFERDATAPROC BufferData = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus = nullptr;
  decltype(&glClear) Clear = nullptr;
  decltype(&glClearColor) ClearColor = nullptr;
  decltype(&glClearDepth) ClearDepth = nullptr;
  PFNGLCLIPCONTROLPROC ClipControl = nullptr;
  PFNGLCOMPILESHADERPROC CompileShader = nullptr;
  PFNGLCREATEPROGRAMPROC CreateProgram = nullptr;
  PFNGLCREATESHADERPROC CreateShader = nullptr;
  PFNGLDELETEBUFFERSPROC DeleteBuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers = nullptr;
  PFNGLDELETEPROGRAMPROC DeleteProgram = nullptr;
  PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers = nullptr;
  PFNGLDELETESHADERPROC DeleteShader = nullptr;
  PFNGLDELETEVERTEXARRAYSPROC DeleteVertexArrays = nullptr;
  decltype(&glDepthFunc) DepthFunc = nullptr;
  decltype(&glDisable) Disable = nullptr;
  decltype(&glDrawBuffer) DrawBuffer = nullptr;
  decltype(&glDrawElements) DrawElements = nullptr;
  decltype(&glEnable) Enable = nullptr;
  PFNGLENABLEVERTEXATTRIBARRAYPROC EnableVertexAttribArray = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer = nullptr;
  PFNGLGENBUFFERSPROC GenBuffers = nullptr;
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
  PFNGLGENRENDERBUFFERSPROC GenRenderbuffers = nullptr;
  PFNGLGENVERTEXARRAYSPROC GenVertexArrays = nullptr;
  decltype(&glGetError) GetError = nullptr;
  decltype(&glGetIntegerv) GetIntegerv = nullptr;
  PFNGLGETPROGRAMINFOLOGPROC GetProgramInfoLog = nullptr;
  PFNGLGETPROGRAMIVPROC GetProgramiv = nullptr;
  PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog = nullptr;
  PFNGLGETSHADERIVPROC GetShaderiv = nullptr;
  PFNGLLINKPROGRAMPROC LinkProgram = nullptr;
  PFNGLMULTIDRAWELEMENTSPROC MultiDrawElements = nullptr;
  decltype(&glPixelStorei) PixelStorei = nullptr;
  decltype(&glReadBuffer) ReadBuffer = nullptr;
  decltype(&glReadPixels) ReadPixels = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage = nullptr;
  PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC RenderbufferStorageMultisample = nullptr;
  PFNGLSHADERSOURCEPROC ShaderSource = nullptr;
  PFNGLUNIFORM1FPROC Uniform1f = nullptr;
  PFNGLUNIFORM2FPROC Uniform2f = nullptr;
  PFNGLUNIFORM3FPROC Uniform3f = nullptr;
  PFNGLUNIFORMMATRIX4FVPROC UniformMatrix4fv = nullptr;
  PFNGLUSEPROGRAMPROC UseProgram = nullptr;
  PFNGLVERTEXATTRIBPOINTERPROC VertexAttribPointer = nullptr;
  decltype(&glViewport) Viewport = nullptr;
};

/// The entry points; loads libOSMesa the first time (thread-safe). Throws
/// std::runtime_error naming the library or the entry point it lacks.
const GlApi& gl();

}  // namespace campo
