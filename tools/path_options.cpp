#include "tools/path_options.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "campo/json_reader.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

std::string kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::regular: return "a file";
    case fs::file_type::directory: return "a directory";
    case fs::file_type::block:
    case fs::file_type::character: return "a device";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::socket: return "a socket";
    default: return "neither a file nor a directory";
  }
}

// "" when `path` is a `type` (symbolic links followed); else what is wrong with it.
std::string check_existing(const std::string& path, fs::file_type type) {
  const std::string what = type == fs::file_type::directory ? "directory" : "regular file";
  if (path.empty()) return "expected the path of a " + what + ", got an empty string";
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  const std::string got = ", got \"" + path + "\"";
  if (status.type() == fs::file_type::not_found) return "expected an existing " + what + got + ", which does not exist";
  if (ec) return "expected an existing " + what + got + ": " + ec.message();  // e.g. a loop of symbolic links
  if (status.type() != type) return "expected a " + what + got + ", which is " + kind_of(status.type());
  return "";
}

// "" when `text` is a whole finite number above (or at) 0; else what was expected.
std::string check_number(const std::string& text, bool zero_allowed) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const bool number = !text.empty() && ec == std::errc() && end == text.data() + text.size() && std::isfinite(v);
  if (number && (zero_allowed ? v >= 0.0 : v > 0.0)) return "";
  return std::string("expected a number ") + (zero_allowed ? ">= 0" : "> 0") + ", got \"" + text + "\"";
}

}  // namespace

CLI::Validator non_negative_number() {
  return CLI::Validator([](std::string& text) { return check_number(text, true); }, "NONNEGATIVE");
}

CLI::Validator positive_number() {
  return CLI::Validator([](std::string& text) { return check_number(text, false); }, "POSITIVE");
}

CLI::Validator input_path() {
  return CLI::Validator(
      [](std::string& path) { return path.empty() ? std::string("expected a path, got an empty string") : std::string(); },
      "");
}

CLI::Validator existing_directory() {
  return CLI::Validator([](std::string& path) { return check_existing(path, fs::file_type::directory); }, "DIR");
}

CLI::Validator existing_file() {
  return CLI::Validator([](std::string& path) { return check_existing(path, fs::file_type::regular); }, "FILE");
}

std::string parse_error_message(const CLI::App* /*app*/, const CLI::Error& error) {
  return "error: command line: " + printable(error.what()) + "\nRun with --help for more information.\n";
}

CLI::Option* add_figure_format_option(CLI::App& app, std::vector<figure::FigureFormat>* formats) {
  return app
      .add_option_function<std::string>(
          "--figure-format",
          [formats](const std::string& list) { *formats = figure::parse_figure_formats(list); },
          "Formats of the figures, comma-separated: png (raster), pdf and svg (vector, text as text in PDF), "
          "e.g. png,pdf (default: png)")
      ->type_name("LIST")
      ->check(CLI::Validator(
          [](std::string& list) -> std::string {
            try {
              figure::parse_figure_formats(list);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return {};
          },
          ""));
}

}  // namespace campo::cli
