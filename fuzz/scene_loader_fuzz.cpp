// libFuzzer target of the scene loader (docs/running.md, "Fuzzing"): the bytes
// go through what `campo validate` does with a file, load_scene and then the
// vehicle and planner checks. An InputError is the loader refusing the input,
// which is expected; any other exception escapes, aborts, and libFuzzer
// reports it with the input, as it does every sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "session/scene_checks.hpp"

namespace {

// The input stands where the bundled scenes are, so relative terrain files
// ("csv", "png") resolve against scenes/ as they would for a bundled scene.
const std::filesystem::path kInputPath = std::filesystem::path(CAMPO_SOURCE_DIR) / "scenes" / "fuzz_input.json";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const campo::Scene scene = campo::load_scene_text(text, kInputPath);
    campo::check_vehicles_and_planners(scene);
  } catch (const campo::InputError&) {
    // Refused with file, pointer and expectation: the contract holds.
  }
  return 0;
}
