#pragma once
/// Strict readers of the MovingAI grid benchmark (Sturtevant 2012): `.map`
/// files (`type octile`, `height H`, `width W`, `map`, then H rows of W cells:
/// `.` `G` `S` passable, `@` `O` `T` `W` not; x = column, y = row, (0,0) top
/// left) and `.scen` files (`version 1`, then one problem per line:
/// bucket, map, width, height, start x, start y, goal x, goal y, optimal length).
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "grid/grid_graph.hpp"

namespace campo::grid {

/// Bad benchmark input: the file, the 1-based line (0: the whole file) and
/// what was expected. what() is "FILE: line N: MESSAGE" with control
/// characters escaped (campo::printable); message() is as given.
class FormatError : public std::runtime_error {
 public:
  FormatError(std::string file, int line, const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string message_;
};

/// Limits that stop hostile input from exhausting memory.
struct MovingAiLimits {
  std::uintmax_t max_file_bytes = 64u << 20;  ///< bytes of one file
  int max_dimension = 4096;                   ///< cells along x or y
};

struct MovingAiMap {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> passable;  ///< row-major, width * height; 1 = passable

  bool is_passable(int x, int y) const { return passable[static_cast<std::size_t>(y) * width + x] != 0; }
};

struct MovingAiProblem {
  int line = 0;   ///< 1-based line in the .scen file
  int bucket = 0;
  std::string map;  ///< map name as the file gives it
  int map_width = 0;
  int map_height = 0;
  Cell start;
  Cell goal;
  double optimal_length = 0.0;  ///< octile cost, as the file rounds it
};

MovingAiMap read_movingai_map(const std::filesystem::path& file, const MovingAiLimits& limits = {});
std::vector<MovingAiProblem> read_movingai_scenario(const std::filesystem::path& file,
                                                    const MovingAiLimits& limits = {});

/// Checks every problem against the map: same width and height, start and
/// goal passable. Errors name the scenario file and the problem's line.
void check_scenario(const std::filesystem::path& scen_file, std::span<const MovingAiProblem> problems,
                    const MovingAiMap& map);

/// The map as an 8-connected grid (octile costs, no corner cutting), as the
/// benchmark defines: passable cells free, the others blocked.
GridGraph to_grid_graph(const MovingAiMap& map);

/// Whether a cost (cell units) matches the file's optimal length, which is
/// rounded (to 5 or 8 decimals): within 1e-3 absolute or 1e-4 relative.
bool matches_optimal(double cost, double optimal_length);

}  // namespace campo::grid
