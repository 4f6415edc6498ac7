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
  #define CAMPO_GL_LOAD(name, type) api.name = reinterpret_cast<type>(entry("gl" #name));
  CAMPO_GL_FUNCTIONS(CAMPO_GL_LOAD)
#undef CAMPO_GL_LOAD
  return api;
}

}  // namespace

const GlApi& gl() {
  static const GlApi api = load();
  return api;
}

}  // namespace campo
