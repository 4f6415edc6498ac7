// libFuzzer target of the sweep spec reader (docs/running.md, "Fuzzing"): the
// bytes go through what `campo sweep` does before it runs anything, the spec
// read, expanded into its runs, and every run's scene loaded with its
// overrides and checked. An InputError is the expected refusal; any other
// exception escapes, aborts, and libFuzzer reports it with the input.
#include <cstddef>
#include <cstdint>
#include <string>

#include "campo/json_reader.hpp"
#include "sweep/expansion.hpp"
#include "sweep/sweep_spec.hpp"
#include "session/scene_checks.hpp"

namespace {

// The input stands where the bundled specs are, so "../two_barriers.json"
// reaches a bundled scene as it does from scenes/sweeps/*.json. Bundled scene
// names are found from the working directory (tools/fuzz.sh runs in the root).
const std::filesystem::path kInputPath =
    std::filesystem::path(CAMPO_SOURCE_DIR) / "scenes" / "sweeps" / "fuzz_input.json";

// Every run's scene is loaded in expansion: 100,000 runs (the spec limit) take
// minutes. A few runs reach every override and axis value the spec can write
// while keeping an input to milliseconds; the run count check is the same code
// at any limit.
campo::SweepLimits fuzz_limits() {
  campo::SweepLimits limits;
  limits.max_runs = 16;
  return limits;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const campo::SweepSpec spec = campo::read_sweep_spec_text(text, kInputPath, fuzz_limits());
    campo::expand_sweep(spec, [](const campo::Scene& scene) {
      campo::check_vehicles_and_planners(scene);
      campo::check_runnable(scene);
    });
  } catch (const campo::InputError&) {
    // Refused with file, pointer and expectation: the contract holds.
  }
  return 0;
}
