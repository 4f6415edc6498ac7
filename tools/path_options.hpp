#pragma once
/// Checks of the command-line options that name paths to read or take a
/// number, and the one form of every command-line error: "error: command
/// line: WHAT" on one line (docs/limits.md), whether CLI11 or campo finds it.
#include <string>

#include <CLI/CLI.hpp>

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

/// What campo prints for a CLI11 parse error (an unknown option, a missing or
/// refused value): "error: command line: " and CLI11's text with control
/// characters escaped, then a line pointing at --help. For App::failure_message.
std::string parse_error_message(const CLI::App* app, const CLI::Error& error);

}  // namespace campo::cli
