#pragma once
/// Checks of the command-line options that name paths to read or take a
/// number, and the one form of every command-line error: "error: command
/// line: WHAT" on one line (docs/limits.md), whether CLI11 or campo finds it.
#include <cctype>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "render/figure_canvas.hpp"

namespace campo::cli {

/// A path to read: refuses an empty string ("--map: expected a path, got an empty string").
CLI::Validator input_path();
/// An existing directory, symbolic links followed; else the path and the system's
/// reason ("runs: expected an existing directory, got \"d\": Too many levels of symbolic links").
CLI::Validator existing_directory();
/// An existing regular file, symbolic links followed; else the path and the system's reason.
CLI::Validator existing_file();

/// A finite number >= 0 ("--at: expected a number >= 0, got \"-5\""; CLI11's
/// NonNegativeNumber printed its range's upper end, DBL_MAX, in full).
CLI::Validator non_negative_number();
/// A finite number > 0.
CLI::Validator positive_number();

/// A choice among names, case-insensitive, given to the option as the enum's
/// value; refused with the names listed ("--format: expected markdown, md, csv
/// or latex, got \"x\""), never CLI11's map of names to numbers.
template <class E>
CLI::Validator named_choice(std::vector<std::pair<std::string, E>> names) {
  return CLI::Validator(
      [names](std::string& text) -> std::string {
        std::string lower = text;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        for (const auto& [name, value] : names) {
          if (lower == name) {
            text = std::to_string(static_cast<int>(value));
            return {};
          }
        }
        std::string list;
        for (std::size_t i = 0; i < names.size(); ++i) {
          list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i].first;
        }
        return "expected " + list + ", got \"" + text + "\"";
      },
      "");
}

/// --figure-format FORMATS: the comma-separated formats (png, pdf, svg) every
/// figure of the command is written in, into `formats` (default: as given by
/// the caller, PNG). One definition for every command that draws figures.
CLI::Option* add_figure_format_option(CLI::App& app, std::vector<figure::FigureFormat>* formats);

/// What campo prints for a CLI11 parse error (an unknown option, a missing or
/// refused value): "error: command line: " and CLI11's text with control
/// characters escaped, then a line pointing at --help. For App::failure_message.
std::string parse_error_message(const CLI::App* app, const CLI::Error& error);

}  // namespace campo::cli
