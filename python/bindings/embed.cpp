// libcampo_python: starts a Python interpreter inside a program that is not
// Python (campo run --planner python:..., a sweep's runs) and imports the
// campo package, whose native module registers the "python" planner scheme.
// Loaded on demand by planners/planner_registry.cpp (load_python_support).
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

#include <dlfcn.h>

#include <pybind11/embed.h>

namespace py = pybind11;

namespace {

// build/python in the build tree; PREFIX/lib/python3/dist-packages when installed beside this library.
std::filesystem::path package_dir() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&package_dir), &info) != 0 && info.dli_fname) {
    const std::filesystem::path installed =
        std::filesystem::path(info.dli_fname).parent_path().parent_path() / CAMPO_PYTHON_INSTALL_DIR;
    std::error_code ec;
    if (std::filesystem::exists(installed / "campo", ec)) return installed;
  }
  return CAMPO_PYTHON_BUILD_DIR;
}

}  // namespace

/// Starts Python (once) and imports campo; 0 on success, else 1 with the
/// reason in `error` (size bytes, NUL-terminated).
extern "C" __attribute__((visibility("default"))) int campo_python_start(char* error, std::size_t size) {
  try {
    if (!Py_IsInitialized()) {
      // As pybind11 configures it, with no signal handlers: Ctrl-C stays campo's (a sweep's runs are
      // stopped by their parent).
      PyConfig config;
      PyConfig_InitIsolatedConfig(&config);
      config.isolated = 0;
      config.use_environment = 1;  // PYTHONPATH finds the planners' modules
      config.install_signal_handlers = 0;
      // The interpreter campo was built against (its standard library and its numpy), whatever
      // python3 comes first on the PATH (pyenv, a virtual environment) or PYTHONHOME says.
      for (const auto& [field, value] : {std::pair{&config.program_name, CAMPO_PYTHON_EXECUTABLE},
                                         std::pair{&config.executable, CAMPO_PYTHON_EXECUTABLE},
                                         std::pair{&config.home, CAMPO_PYTHON_HOME}}) {
        if (*value == '\0') continue;
        const PyStatus status = PyConfig_SetBytesString(&config, field, value);
        if (PyStatus_Exception(status)) {
          PyConfig_Clear(&config);
          throw std::runtime_error(status.err_msg ? status.err_msg : "cannot configure Python");
        }
      }
      py::initialize_interpreter(&config, 0, nullptr, false);
    }
    py::module_ sys = py::module_::import("sys");
    // The planner's package is found like a script's imports: the working directory, then PYTHONPATH.
    sys.attr("path").attr("insert")(0, std::filesystem::current_path().string());
    sys.attr("path").attr("append")(package_dir().string());
    py::module_::import("campo");
    // A planner's os._exit ends its run as failed, not campo (planner_limits.hpp).
    py::module_::import("campo._campo").attr("_guard_process_exit")();
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(error, size, "%s", e.what());
    return 1;
  }
}
