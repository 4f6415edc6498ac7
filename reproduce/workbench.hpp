#pragma once
/// Where the reproduction report's experiments run: campo itself, started as
/// a child process for every command, so that each command the report lists
/// is exactly what was run and can be run again by hand.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace campo {

struct WorkbenchConfig {
  std::filesystem::path campo_binary;  ///< the campo executable to run
  std::filesystem::path work_dir;      ///< sweeps and runs (emptied first; must be campo's or empty)
  std::filesystem::path figure_dir;    ///< the figures the report shows
  std::string figure_prefix;           ///< how the report refers to figure_dir ("reproductions/")
  bool quick = false;                  ///< reduced experiments
  int jobs = 1;                        ///< runs at a time in sweeps
};

class Workbench {
 public:
  /// Prepares the directories: the work directory is emptied when it holds
  /// an earlier report's work (a marker file says so), so no result of an
  /// older campo is reused; any other non-empty directory is an InputError.
  explicit Workbench(WorkbenchConfig config);

  /// Runs `campo args...`, its output passed through; returns the command
  /// as the report shows it ("campo run scenes/wall.json --out ..."). Throws
  /// std::runtime_error naming the command when its exit code is not 0.
  std::string campo(const std::vector<std::string>& args) const;
  /// campo() with the command's standard output captured into `output` instead.
  std::string campo(const std::vector<std::string>& args, std::string& output) const;

  /// A sweep spec for this report: `file` itself, or with `quick`, a copy
  /// reduced by `reduce` (e.g. fewer seeds) written to the work directory,
  /// its scene paths made absolute.
  std::filesystem::path spec(const std::filesystem::path& file,
                             const std::function<void(nlohmann::json&)>& reduce) const;

  /// work_dir / name.
  std::filesystem::path work(const std::string& name) const { return config_.work_dir / name; }

  /// Copies a PNG into the figure directory as `name`; returns how the report refers to it.
  std::string publish(const std::filesystem::path& png, const std::string& name) const;

  bool quick() const { return config_.quick; }
  int jobs() const { return config_.jobs; }

 private:
  std::string run(const std::vector<std::string>& args, std::string* output) const;
  WorkbenchConfig config_;
};

/// `args` as one shell command line, words quoted where a shell needs it.
std::string command_line(const std::vector<std::string>& args);

}  // namespace campo
