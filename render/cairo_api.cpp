#include "render/cairo_api.hpp"

#include <stdexcept>
#include <string>

#include <dlfcn.h>

namespace campo {

namespace {

CairoApi load() {
  // Never closed: figures may be drawn until the process ends (and a thread's
  // text-measuring context is destroyed at its exit).
  void* const library = dlopen("libcairo.so.2", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    throw std::runtime_error(std::string("cairo: cannot load libcairo.so.2 (Debian libcairo2): ") + dlerror());
  }
  const auto symbol = [library](const char* name) {
    void* const address = dlsym(library, name);
    if (address == nullptr) throw std::runtime_error(std::string("cairo: libcairo.so.2 has no ") + name);
    return address;
  };
  CairoApi api;
#define CAMPO_CAIRO_LOAD(name) api.name = reinterpret_cast<decltype(api.name)>(symbol("cairo_" #name));
  CAMPO_CAIRO_FUNCTIONS(CAMPO_CAIRO_LOAD)
#undef CAMPO_CAIRO_LOAD
  return api;
}

}  // namespace

const CairoApi& cairo() {
  static const CairoApi api = load();
  return api;
}

}  // namespace campo
