#pragma once
// The readers of terrain CSVs, PNGs and MovingAI maps take a path: each input is written to a
// scratch file of its own process (libFuzzer runs one input at a time per process) and read
// from there, as the program reads the user's file.
#include <cstddef>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace campo::fuzz {

/// Writes the input to a scratch file named `name` and returns its path.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = std::filesystem::temp_directory_path() / ("campo_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    // Removed when libFuzzer exits normally; a crash leaves it beside the finding.
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() / ("campo_fuzz_" + std::to_string(::getpid())),
                                  ignored);
    });
    return d;
  }();
  const std::filesystem::path path = dir / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  return path;
}

}  // namespace campo::fuzz
