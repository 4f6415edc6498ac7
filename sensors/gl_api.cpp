#include "sensors/gl_api.hpp"

#include <stdexcept>
#include <string>

#include <dlfcn.h>

namespace campo {

namespace {

GlApi load() {
  // Never closed: GL state lives until the process ends.
  void* const library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    throw std::runtime_error(std::string("OSMesa: cannot load libOSMesa.so.8 (Debian libosmesa6): ") + dlerror());
  }
  const auto symbol = [library](const char* name) {
    void* const address = dlsym(library, name);
    if (address == nullptr) throw std::runtime_error(std::string("OSMesa: libOSMesa.so.8 has no ") + name);
    return address;
  };
  GlApi api;
  api.CreateContextAttribs = reinterpret_cast<decltype(api.CreateContextAttribs)>(symbol("OSMesaCreateContextAttribs"));
  api.MakeCurrent = reinterpret_cast<decltype(api.MakeCurrent)>(symbol("OSMesaMakeCurrent"));
  api.GetCurrentContext = reinterpret_cast<decltype(api.GetCurrentContext)>(symbol("OSMesaGetCurrentContext"));
  api.DestroyContext = reinterpret_cast<decltype(api.DestroyContext)>(symbol("OSMesaDestroyContext"));
  const auto get_proc = reinterpret_cast<decltype(&OSMesaGetProcAddress)>(symbol("OSMesaGetProcAddress"));
  // GL entry points as OSMesa hands them out (every GL 4.5 function), else exported by the library.
  const auto entry = [&](const char* name) -> void* {
    if (const auto address = get_proc(name)) return reinterpret_cast<void*>(address);
    return symbol(name);
  };
    api.AttachShader = reinterpret_cast<PFNGLATTACHSHADERPROC>(entry("glAttachShader"));
    api.BindBuffer = reinterpret_cast<PFNGLBINDBUFFERPROC>(entry("glBindBuffer"));
    api.BindFramebuffer = reinterpret_cast<PFNGLBINDFRAMEBUFFERPROC>(entry("glBindFramebuffer"));
    api.BindRenderbuffer = reinterpret_cast<PFNGLBINDRENDERBUFFERPROC>(entry("glBindRenderbuffer"));
    api.BindVertexArray = reinterpret_cast<PFNGLBINDVERTEXARRAYPROC>(entry("glBindVertexArray"));
    api.BlitFramebuffer = reinterpret_cast<PFNGLBLITFRAMEBUFFERPROC>(entry("glBlitFramebuffer"));
    api.BufferData = reinterpret_cast<PFNGLBUFFERDATAPROC>(entry("glBufferData"));
    api.CheckFramebufferStatus = reinterpret_cast<PFNGLCHECKFRAMEBUFFERSTATUSPROC>(entry("glCheckFramebufferStatus"));
    api.Clear = reinterpret_cast<decltype(&glClear)>(entry("glClear"));
    api.ClearColor = reinterpret_cast<decltype(&glClearColor)>(entry("glClearColor"));
    api.ClearDepth = reinterpret_cast<decltype(&glClearDepth)>(entry("glClearDepth"));
    api.ClipControl = reinterpret_cast<PFNGLCLIPCONTROLPROC>(entry("glClipControl"));
    api.CompileShader = reinterpret_cast<PFNGLCOMPILESHADERPROC>(entry("glCompileShader"));
    api.CreateProgram = reinterpret_cast<PFNGLCREATEPROGRAMPROC>(entry("glCreateProgram"));
    api.CreateShader = reinterpret_cast<PFNGLCREATESHADERPROC>(entry("glCreateShader"));
    api.DeleteBuffers = reinterpret_cast<PFNGLDELETEBUFFERSPROC>(entry("glDeleteBuffers"));
    api.DeleteFramebuffers = reinterpret_cast<PFNGLDELETEFRAMEBUFFERSPROC>(entry("glDeleteFramebuffers"));
    api.DeleteProgram = reinterpret_cast<PFNGLDELETEPROGRAMPROC>(entry("glDeleteProgram"));
    api.DeleteRenderbuffers = reinterpret_cast<PFNGLDELETERENDERBUFFERSPROC>(entry("glDeleteRenderbuffers"));
    api.DeleteShader = reinterpret_cast<PFNGLDELETESHADERPROC>(entry("glDeleteShader"));
    api.DeleteVertexArrays = reinterpret_cast<PFNGLDELETEVERTEXARRAYSPROC>(entry("glDeleteVertexArrays"));
    api.DepthFunc = reinterpret_cast<decltype(&glDepthFunc)>(entry("glDepthFunc"));
    api.Disable = reinterpret_cast<decltype(&glDisable)>(entry("glDisable"));
    api.DrawBuffer = reinterpret_cast<decltype(&glDrawBuffer)>(entry("glDrawBuffer"));
    api.DrawElements = reinterpret_cast<decltype(&glDrawElements)>(entry("glDrawElements"));
    api.Enable = reinterpret_cast<decltype(&glEnable)>(entry("glEnable"));
    api.EnableVertexAttribArray = reinterpret_cast<PFNGLENABLEVERTEXATTRIBARRAYPROC>(entry("glEnableVertexAttribArray"));
    api.FramebufferRenderbuffer = reinterpret_cast<PFNGLFRAMEBUFFERRENDERBUFFERPROC>(entry("glFramebufferRenderbuffer"));
    api.GenBuffers = reinterpret_cast<PFNGLGENBUFFERSPROC>(entry("glGenBuffers"));
    api.GenFramebuffers = reinterpret_cast<PFNGLGENFRAMEBUFFERSPROC>(entry("glGenFramebuffers"));
    api.GenRenderbuffers = reinterpret_cast<PFNGLGENRENDERBUFFERSPROC>(entry("glGenRenderbuffers"));
    api.GenVertexArrays = reinterpret_cast<PFNGLGENVERTEXARRAYSPROC>(entry("glGenVertexArrays"));
    api.GetError = reinterpret_cast<decltype(&glGetError)>(entry("glGetError"));
    api.GetIntegerv = reinterpret_cast<decltype(&glGetIntegerv)>(entry("glGetIntegerv"));
    api.GetProgramInfoLog = reinterpret_cast<PFNGLGETPROGRAMINFOLOGPROC>(entry("glGetProgramInfoLog"));
    api.GetProgramiv = reinterpret_cast<PFNGLGETPROGRAMIVPROC>(entry("glGetProgramiv"));
    api.GetShaderInfoLog = reinterpret_cast<PFNGLGETSHADERINFOLOGPROC>(entry("glGetShaderInfoLog"));
    api.GetShaderiv = reinterpret_cast<PFNGLGETSHADERIVPROC>(entry("glGetShaderiv"));
    api.LinkProgram = reinterpret_cast<PFNGLLINKPROGRAMPROC>(entry("glLinkProgram"));
    api.MultiDrawElements = reinterpret_cast<PFNGLMULTIDRAWELEMENTSPROC>(entry("glMultiDrawElements"));
    api.PixelStorei = reinterpret_cast<decltype(&glPixelStorei)>(entry("glPixelStorei"));
    api.ReadBuffer = reinterpret_cast<decltype(&glReadBuffer)>(entry("glReadBuffer"));
    api.ReadPixels = reinterpret_cast<decltype(&glReadPixels)>(entry("glReadPixels"));
    api.RenderbufferStorage = reinterpret_cast<PFNGLRENDERBUFFERSTORAGEPROC>(entry("glRenderbufferStorage"));
    api.RenderbufferStorageMultisample = reinterpret_cast<PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC>(entry("glRenderbufferStorageMultisample"));
    api.ShaderSource = reinterpret_cast<PFNGLSHADERSOURCEPROC>(entry("glShaderSource"));
    api.Uniform1f = reinterpret_cast<PFNGLUNIFORM1FPROC>(entry("glUniform1f"));
    api.Uniform2f = reinterpret_cast<PFNGLUNIFORM2FPROC>(entry("glUniform2f"));
    api.Uniform3f = reinterpret_cast<PFNGLUNIFORM3FPROC>(entry("glUniform3f"));
    api.UniformMatrix4fv = reinterpret_cast<PFNGLUNIFORMMATRIX4FVPROC>(entry("glUniformMatrix4fv"));
    api.UseProgram = reinterpret_cast<PFNGLUSEPROGRAMPROC>(entry("glUseProgram"));
    api.VertexAttribPointer = reinterpret_cast<PFNGLVERTEXATTRIBPOINTERPROC>(entry("glVertexAttribPointer"));
    api.Viewport = reinterpret_cast<decltype(&glViewport)>(entry("glViewport"));
  return api;
}

}  // namespace

const GlApi& gl() {
  static const GlApi api = load();
  return api;
}

}  // namespace campo
