#include "scene/heightfield_sources.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <muParser.h>
#include <opencv2/core.hpp>

#include "campo/json_reader.hpp"
#include "core/image_io.hpp"
#include "scene/generators_grid.hpp"

namespace campo {
namespace {

/// A CSV field longer than this is not a number anyone meant to write.
constexpr std::size_t kMaxCsvFieldChars = 64;

std::string heightfield_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// A grid of the given layout with storage for every vertex (size already checked).
HeightGrid allocate_grid(int cols, int rows, double spacing_x_m, double spacing_y_m) {
  HeightGrid grid;
  grid.cols = cols;
  grid.rows = rows;
  grid.spacing_x_m = spacing_x_m;
  grid.spacing_y_m = spacing_y_m;
  grid.heights_m.resize(static_cast<std::size_t>(cols) * rows);
  return grid;
}

bool is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r'; }

/// One CSV field (surrounding blanks allowed) as a finite number; `line` and
/// `column` (1-based) locate it in messages.
double parse_csv_field(std::string_view field, long line, long column) {
  const auto first = std::find_if_not(field.begin(), field.end(), is_blank);
  const auto last = std::find_if_not(field.rbegin(), field.rend(), is_blank).base();
  const std::string where = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";
  if (first >= last) throw std::runtime_error(where + "empty field");
  const std::string_view text(&*first, static_cast<std::size_t>(last - first));
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw std::runtime_error(where + "'" + std::string(text) + "' is not a finite number");
  }
  return value;
}

/// The fields of a PNG's IHDR chunk that decide whether we accept it.
struct PngHeader {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int bit_depth = 0;
  int colour_type = 0;
};

/// Reads the PNG signature and IHDR chunk only, so the image size can be
/// checked before anything is decoded.
PngHeader read_png_header(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open PNG file '" + path.string() + "'");
  // Signature (8 bytes), IHDR length (4) and type (4), width (4), height (4), depth, colour type.
  unsigned char bytes[26] = {};
  in.read(reinterpret_cast<char*>(bytes), sizeof bytes);
  constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (in.gcount() != sizeof bytes || !std::equal(kSignature, kSignature + 8, bytes) ||
      std::memcmp(bytes + 12, "IHDR", 4) != 0) {
    throw std::runtime_error("'" + path.string() + "' is not a PNG file");
  }
  const auto big_endian = [&](int offset) {
    return std::uint32_t{bytes[offset]} << 24 | std::uint32_t{bytes[offset + 1]} << 16 |
           std::uint32_t{bytes[offset + 2]} << 8 | std::uint32_t{bytes[offset + 3]};
  };
  return {big_endian(16), big_endian(20), bytes[24], bytes[25]};
}

std::string png_colour_type_name(int colour_type) {
  switch (colour_type) {
    case 0: return "greyscale";
    case 2: return "RGB";
    case 3: return "palette";
    case 4: return "greyscale with alpha";
    case 6: return "RGBA";
    default: return "unknown";
  }
}

}  // namespace

HeightGrid heightgrid_from_expression(const std::string& expression, const Eigen::Vector2d& size_m,
                                      double spacing_m, const Eigen::Isometry3d& pose) {
  const GridLayout layout = grid_layout<std::runtime_error>(size_m, spacing_m);
  const std::string context = "expression '" + expression + "': ";
  HeightGrid grid = allocate_grid(layout.cols, layout.rows, layout.spacing_x_m, layout.spacing_y_m);
  // muParser reads x and y through these addresses at every Eval().
  double x = 0.0;
  double y = 0.0;
  try {
    mu::Parser parser;
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.SetExpr(expression);
    // A comma list ("x, y") would silently keep only its last value.
    parser.Eval();
    if (parser.GetNumResults() != 1) throw std::runtime_error(context + "must be a single value, not a list");
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) {
        const Eigen::Vector3d local(grid_vertex_coordinate(c, grid.cols, grid.spacing_x_m),
                                    grid_vertex_coordinate(r, grid.rows, grid.spacing_y_m), 0.0);
        const Eigen::Vector3d world = pose * local;
        x = world.x();
        y = world.y();
        const double z = parser.Eval();
        if (!std::isfinite(z)) {
          throw std::runtime_error(context + "not finite (" + heightfield_number(z) + ") at x = " + heightfield_number(world.x()) +
                                   ", y = " + heightfield_number(world.y()));
        }
        grid.heights_m[static_cast<std::size_t>(r) * grid.cols + c] = z - pose.translation().z();
      }
    }
  } catch (const mu::Parser::exception_type& error) {
    throw std::runtime_error(context + error.GetMsg());
  }
  return grid;
}

HeightGrid heightgrid_from_csv(const std::filesystem::path& path, double spacing_m) {
  if (!(std::isfinite(spacing_m) && spacing_m > 0.0)) {
    throw std::runtime_error("CSV grid spacing must be finite and > 0, got " + heightfield_number(spacing_m));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open CSV file '" + path.string() + "'");

  // Streamed a character at a time so no line, field or grid grows past its limit.
  std::vector<double> values;  // file order: the northern row first
  long cols = 0;               // fields per line, set by the first line
  long data_lines = 0;
  long line = 1;
  long fields = 0;             // fields finished on the current line
  bool line_blank = true;      // nothing but blanks on the current line so far
  long first_blank_line = 0;   // a blank line is only allowed at the end of the file
  std::string field;

  const auto end_field = [&] {
    if (values.size() >= static_cast<std::size_t>(kMaxHeightfieldVertices)) {
      throw std::runtime_error("line " + std::to_string(line) + ": more than " +
                               std::to_string(kMaxHeightfieldVertices) + " heights");
    }
    values.push_back(parse_csv_field(field, line, fields + 1));
    ++fields;
    field.clear();
  };
  const auto end_line = [&] {
    if (line_blank) {
      if (first_blank_line == 0) first_blank_line = line;
    } else {
      if (first_blank_line != 0) throw std::runtime_error("line " + std::to_string(first_blank_line) + " is empty");
      end_field();
      if (cols == 0) cols = fields;
      if (fields != cols) {
        throw std::runtime_error("line " + std::to_string(line) + " has " + std::to_string(fields) +
                                 " fields, expected " + std::to_string(cols) + " as on the first line");
      }
      ++data_lines;
    }
    ++line;
    fields = 0;
    line_blank = true;
    field.clear();
  };

  char buffer[1 << 16];
  do {
    in.read(buffer, sizeof buffer);
    const std::streamsize count = in.gcount();
    for (std::streamsize i = 0; i < count; ++i) {
      const char ch = buffer[i];
      if (ch == '\n') {
        end_line();
      } else if (ch == ',') {
        line_blank = false;
        end_field();
      } else {
        if (!is_blank(ch)) line_blank = false;
        if (field.size() == kMaxCsvFieldChars) {
          throw std::runtime_error("line " + std::to_string(line) + ", column " + std::to_string(fields + 1) +
                                   ": field longer than " + std::to_string(kMaxCsvFieldChars) + " characters");
        }
        field.push_back(ch);
      }
    }
  } while (in);
  if (in.bad()) throw std::runtime_error("error reading CSV file '" + path.string() + "'");
  end_line();  // a last line without a newline

  if (values.empty()) throw std::runtime_error("CSV file has no heights");
  if (data_lines < 2 || cols < 2) {
    throw std::runtime_error("CSV grid is " + std::to_string(data_lines) + " lines x " + std::to_string(cols) +
                             " columns; at least 2 x 2 heights are needed");
  }
  const auto rows = static_cast<int>(data_lines);
  HeightGrid grid = allocate_grid(static_cast<int>(cols), rows, spacing_m, spacing_m);
  // Grid row 0 is the south edge, the file's last line.
  for (int r = 0; r < rows; ++r) {
    const auto source = values.begin() + static_cast<std::ptrdiff_t>(rows - 1 - r) * cols;
    std::copy(source, source + cols, grid.heights_m.begin() + static_cast<std::ptrdiff_t>(r) * cols);
  }
  return grid;
}

HeightGrid heightgrid_from_png(const std::filesystem::path& path, const Eigen::Vector2d& size_m,
                               double height_scale_m, double min_height_m) {
  if (!(size_m.allFinite() && size_m.minCoeff() > 0.0)) {
    throw std::runtime_error("PNG terrain size must be finite and > 0, got " + heightfield_number(size_m.x()) + " x " +
                             heightfield_number(size_m.y()) + " m");
  }
  if (!std::isfinite(height_scale_m) || !std::isfinite(min_height_m)) {
    throw std::runtime_error("PNG terrain height scale and minimum height must be finite");
  }
  const PngHeader header = read_png_header(path);
  if (header.colour_type != 0) {
    throw std::runtime_error("PNG must be single-channel greyscale, got colour type " +
                             std::to_string(header.colour_type) + " (" + png_colour_type_name(header.colour_type) +
                             ")");
  }
  if (header.bit_depth != 8 && header.bit_depth != 16) {
    throw std::runtime_error("PNG must have 8 or 16 bits per pixel, got " + std::to_string(header.bit_depth));
  }
  const std::string dimensions = std::to_string(header.width) + " x " + std::to_string(header.height) + " pixels";
  if (header.width < 2 || header.height < 2) {
    throw std::runtime_error("PNG is " + dimensions + "; at least 2 x 2 are needed");
  }
  if (std::uint64_t{header.width} * header.height > static_cast<std::uint64_t>(kMaxHeightfieldVertices)) {
    throw std::runtime_error("PNG is " + dimensions + ", more than the limit of " +
                             std::to_string(kMaxHeightfieldVertices) + " pixels");
  }

  cv::Mat image;
  try {
    image = read_png_file(path);
  } catch (const InputError& e) {
    throw std::runtime_error(e.what());  // the loader names the scene's pointer with it
  }
  if (image.cols != static_cast<int>(header.width) || image.rows != static_cast<int>(header.height) ||
      (image.type() != CV_8UC1 && image.type() != CV_16UC1)) {
    throw std::runtime_error("PNG file '" + path.string() + "' decoded to an unexpected image");
  }
  const double max_pixel = image.depth() == CV_8U ? 255.0 : 65535.0;
  HeightGrid grid = allocate_grid(image.cols, image.rows, size_m.x() / (image.cols - 1),
                                  size_m.y() / (image.rows - 1));
  // Grid row 0 is the south edge, the image's bottom row.
  for (int r = 0; r < grid.rows; ++r) {
    const int image_row = grid.rows - 1 - r;
    for (int c = 0; c < grid.cols; ++c) {
      const double pixel = image.depth() == CV_8U ? image.at<std::uint8_t>(image_row, c)
                                                  : image.at<std::uint16_t>(image_row, c);
      grid.heights_m[static_cast<std::size_t>(r) * grid.cols + c] =
          min_height_m + (pixel / max_pixel) * height_scale_m;
    }
  }
  return grid;
}

}  // namespace campo
