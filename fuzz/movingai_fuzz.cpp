// libFuzzer target of the MovingAI benchmark readers (docs/running.md, "Fuzzing"): the bytes
// as a .map file (`campo plan --map`), read and turned into a grid graph, and as a .scen file.
// A FormatError (exit 2 in the program, naming the file and line) is the expected refusal;
// any other exception escapes, aborts, and libFuzzer reports it with the input.
#include <cstddef>
#include <cstdint>

#include "fuzz/file_input.hpp"
#include "grid/movingai.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = campo::fuzz::input_file(data, size, "input.map");
  try {
    (void)campo::grid::to_grid_graph(campo::grid::read_movingai_map(path));
  } catch (const campo::grid::FormatError&) {
    // Refused naming the file and line: the contract holds.
  }
  try {
    (void)campo::grid::read_movingai_scenario(path);
  } catch (const campo::grid::FormatError&) {
  }
  return 0;
}
