// libFuzzer target of the terrain CSV reader (docs/running.md, "Fuzzing"): the bytes as a
// heightfield's "csv" file, read at 1 m spacing. The reader refuses with std::runtime_error,
// which the scene loader turns into an InputError naming the object's pointer; any other
// exception escapes, aborts, and libFuzzer reports it with the input.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/file_input.hpp"
#include "scene/heightfield_sources.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = campo::fuzz::input_file(data, size, "heights.csv");
  try {
    (void)campo::heightgrid_from_csv(path, 1.0);
  } catch (const std::runtime_error&) {
    // Refused with what was wrong: the loader names the scene's pointer with it.
  }
  return 0;
}
