#include "grid/movingai.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "campo/json_reader.hpp"

namespace campo::grid {

namespace {

// The file's lines without line terminators ("\n" or "\r\n").
std::vector<std::string> read_lines(const std::filesystem::path& file, const MovingAiLimits& limits) {
  const std::string name = file.string();
  if (name.empty()) throw FormatError(name, 0, "expected the path of a file, got an empty string");
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(file, ec);
  if (ec) throw FormatError(name, 0, "cannot read the file: " + ec.message());
  if (bytes > limits.max_file_bytes) {
    throw FormatError(name, 0, "file too large: " + std::to_string(bytes) + " bytes, expected at most " +
                                   std::to_string(limits.max_file_bytes));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw FormatError(name, 0, "cannot open the file");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// A line quoted in a message: "TEXT", cut after 60 bytes (at a character's start) with "...".
std::string quote_text(std::string_view text) {
  constexpr std::size_t kMax = 60;
  if (text.size() <= kMax) return "\"" + std::string(text) + "\"";
  std::size_t cut = kMax;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) --cut;
  return "\"" + std::string(text.substr(0, cut)) + "...\"";
}

// The character starting at byte `at`: one byte, or a UTF-8 lead byte with its continuation bytes.
std::string character_at(std::string_view text, std::size_t at) {
  std::size_t end = at + 1;
  if ((static_cast<unsigned char>(text[at]) & 0xc0) == 0xc0) {
    while (end < text.size() && end < at + 4 && (static_cast<unsigned char>(text[end]) & 0xc0) == 0x80) ++end;
  }
  return std::string(text.substr(at, end - at));
}

bool blank(std::string_view line) { return line.find_first_not_of(" \t") == std::string_view::npos; }

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (true) {
    i = line.find_first_not_of(" \t", i);
    if (i == std::string_view::npos) break;
    const std::size_t end = std::min(line.find_first_of(" \t", i), line.size());
    fields.push_back(line.substr(i, end - i));
    i = end;
  }
  return fields;
}

// A whole field as an integer in [min, max], or a FormatError naming it.
int parse_int(std::string_view text, int min, int max, const std::string& file, int line, const std::string& what) {
  int value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || value < min || value > max) {
    throw FormatError(file, line, "expected " + what + " (an integer in [" + std::to_string(min) + ", " +
                                      std::to_string(max) + "]), got " + quote_text(text));
  }
  return value;
}

double parse_length(std::string_view text, const std::string& file, int line) {
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value) || value < 0.0) {
    throw FormatError(file, line, "expected the optimal length (a number >= 0), got " + quote_text(text));
  }
  return value;
}

// "KEYWORD VALUE" header line of a .map file.
int header_value(const std::vector<std::string>& lines, std::size_t index, std::string_view keyword,
                 const std::string& file, const MovingAiLimits& limits) {
  const int line = static_cast<int>(index) + 1;
  const std::string expected = "expected \"" + std::string(keyword) + " N\"";
  if (index >= lines.size()) throw FormatError(file, line, expected + ", got the end of the file");
  const auto fields = split_fields(lines[index]);
  if (fields.size() != 2 || fields[0] != keyword) throw FormatError(file, line, expected + ", got " + quote_text(lines[index]));
  return parse_int(fields[1], 1, limits.max_dimension, file, line, std::string(keyword));
}

void expect_line(const std::vector<std::string>& lines, std::size_t index, std::string_view expected,
                 const std::string& file) {
  const int line = static_cast<int>(index) + 1;
  if (index >= lines.size()) {
    throw FormatError(file, line, "expected \"" + std::string(expected) + "\", got the end of the file");
  }
  if (split_fields(lines[index]) != split_fields(expected)) {
    throw FormatError(file, line, "expected \"" + std::string(expected) + "\", got " + quote_text(lines[index]));
  }
}

}  // namespace

FormatError::FormatError(std::string file, int line, const std::string& message)
    : std::runtime_error(printable((file.empty() ? std::string("\"\" (empty path)") : file) + ": " +
                                   (line > 0 ? "line " + std::to_string(line) + ": " : std::string()) + message)),
      file_(std::move(file)),
      line_(line),
      message_(message) {}

MovingAiMap read_movingai_map(const std::filesystem::path& path, const MovingAiLimits& limits) {
  const std::string file = path.string();
  const std::vector<std::string> lines = read_lines(path, limits);
  MovingAiMap map;
  expect_line(lines, 0, "type octile", file);
  map.height = header_value(lines, 1, "height", file, limits);
  map.width = header_value(lines, 2, "width", file, limits);
  expect_line(lines, 3, "map", file);

  map.passable.resize(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height));
  for (int y = 0; y < map.height; ++y) {
    const std::size_t index = 4 + static_cast<std::size_t>(y);
    const int line = static_cast<int>(index) + 1;
    if (index >= lines.size()) {
      throw FormatError(file, line, "expected map row " + std::to_string(y) + " of " + std::to_string(map.height) +
                                        ", got the end of the file");
    }
    const std::string& row = lines[index];
    if (static_cast<int>(row.size()) != map.width) {
      throw FormatError(file, line, "expected a row of " + std::to_string(map.width) + " cells, got " +
                                        std::to_string(row.size()));
    }
    for (int x = 0; x < map.width; ++x) {
      const char c = row[static_cast<std::size_t>(x)];
      bool passable = false;
      switch (c) {
        case '.': case 'G': case 'S': passable = true; break;
        case '@': case 'O': case 'T': case 'W': passable = false; break;
        default:
          throw FormatError(file, line, "column " + std::to_string(x) + ": expected one of . G S @ O T W, got '" +
                                            character_at(row, static_cast<std::size_t>(x)) + "'");
      }
      map.passable[static_cast<std::size_t>(y) * map.width + x] = passable ? 1 : 0;
    }
  }
  for (std::size_t index = 4 + static_cast<std::size_t>(map.height); index < lines.size(); ++index) {
    if (!blank(lines[index])) {
      throw FormatError(file, static_cast<int>(index) + 1,
                        "expected the end of the map after " + std::to_string(map.height) + " rows");
    }
  }
  return map;
}

std::vector<MovingAiProblem> read_movingai_scenario(const std::filesystem::path& path, const MovingAiLimits& limits) {
  const std::string file = path.string();
  const std::vector<std::string> lines = read_lines(path, limits);
  if (lines.empty() || (split_fields(lines[0]) != std::vector<std::string_view>{"version", "1"} &&
                        split_fields(lines[0]) != std::vector<std::string_view>{"version", "1.0"})) {
    throw FormatError(file, 1, "expected \"version 1\"");
  }
  std::vector<MovingAiProblem> problems;
  for (std::size_t index = 1; index < lines.size(); ++index) {
    if (blank(lines[index])) continue;
    const int line = static_cast<int>(index) + 1;
    const auto f = split_fields(lines[index]);
    if (f.size() != 9) {
      throw FormatError(file, line,
                        "expected 9 fields (bucket map width height start_x start_y goal_x goal_y optimal_length), got " +
                            std::to_string(f.size()));
    }
    MovingAiProblem p;
    p.line = line;
    p.bucket = parse_int(f[0], 0, 1 << 30, file, line, "bucket");
    p.map = std::string(f[1]);
    p.map_width = parse_int(f[2], 1, limits.max_dimension, file, line, "map width");
    p.map_height = parse_int(f[3], 1, limits.max_dimension, file, line, "map height");
    p.start.x = parse_int(f[4], 0, p.map_width - 1, file, line, "start_x");
    p.start.y = parse_int(f[5], 0, p.map_height - 1, file, line, "start_y");
    p.goal.x = parse_int(f[6], 0, p.map_width - 1, file, line, "goal_x");
    p.goal.y = parse_int(f[7], 0, p.map_height - 1, file, line, "goal_y");
    p.optimal_length = parse_length(f[8], file, line);
    problems.push_back(p);
  }
  return problems;
}

void check_scenario(const std::filesystem::path& scen_file, std::span<const MovingAiProblem> problems,
                    const MovingAiMap& map) {
  const std::string file = scen_file.string();
  for (const MovingAiProblem& p : problems) {
    if (p.map_width != map.width || p.map_height != map.height) {
      throw FormatError(file, p.line, "expected the map's size " + std::to_string(map.width) + " x " +
                                          std::to_string(map.height) + ", got " + std::to_string(p.map_width) +
                                          " x " + std::to_string(p.map_height));
    }
    for (const auto& [cell, what] : {std::pair{p.start, "start"}, std::pair{p.goal, "goal"}}) {
      if (!map.is_passable(cell.x, cell.y)) {
        throw FormatError(file, p.line, std::string("expected a passable ") + what + " cell, got (" +
                                            std::to_string(cell.x) + ", " + std::to_string(cell.y) +
                                            "), which the map blocks");
      }
    }
  }
}

GridGraph to_grid_graph(const MovingAiMap& map) {
  GridGraph graph({map.width, map.height, 1}, Connectivity::eight);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      graph.set_state({x, y, 0}, map.is_passable(x, y) ? CellState::free : CellState::blocked);
    }
  }
  return graph;
}

bool matches_optimal(double cost, double optimal_length) {
  return cost >= 0.0 && std::abs(cost - optimal_length) <= std::max(1e-3, 1e-4 * optimal_length);
}

}  // namespace campo::grid
