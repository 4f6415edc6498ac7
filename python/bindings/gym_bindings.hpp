#pragma once
/// Binds campo.gym's native classes (_NavigationEnv, _NavigationBatch) and _save_video.
#include <pybind11/pybind11.h>

namespace campo::python {

void bind_gym(pybind11::module_& m);

}  // namespace campo::python
