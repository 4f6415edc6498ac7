// libFuzzer target of the PNG reader (docs/running.md, "Fuzzing"): the bytes as a PNG file
// (terrains, recorded depth maps), decoded by read_png_file, then as a heightfield's "png"
// terrain. An InputError (or the terrain reader's std::runtime_error, which the scene loader
// names with its pointer) is the expected refusal; any other exception escapes, aborts, and
// libFuzzer reports it with the input, as it does an allocation beyond its memory limit.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "campo/json_reader.hpp"
#include "core/image_io.hpp"
#include "fuzz/file_input.hpp"
#include "scene/heightfield_sources.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = campo::fuzz::input_file(data, size, "image.png");
  try {
    (void)campo::read_png_file(path);
  } catch (const campo::InputError&) {
    // Refused naming the file: the contract holds.
  }
  try {
    (void)campo::heightgrid_from_png(path, {10.0, 10.0}, 5.0, 0.0);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
