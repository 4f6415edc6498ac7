#pragma once
/// All-or-nothing output: files are written into a hidden staging directory
/// inside the destination and moved into place by commit(). If the run fails
/// before commit(), the staging directory is removed and nothing is left
/// half-written. Every failure to write names the file and the system's
/// reason ("No space left on device").
#include <filesystem>
#include <string>

#include "campo/json_reader.hpp"

namespace campo {

/// An output that could not be written: `file` and the system's reason. An
/// InputError, so the command line reports it in one line with exit 2 (the
/// input or the place to write is refused, not a bug).
class OutputError : public InputError {
 public:
  OutputError(const std::filesystem::path& file, const std::string& message) : InputError(file.string(), "", message) {}
};

/// "WHAT: " and the system's text of `errnum` ("cannot write: No space left on device").
std::string system_reason(const std::string& what, int errnum);

class StagedOutput {
 public:
  /// Creates `dir` (and parents) and a staging directory inside it named
  /// ".staging-HOST-PID"; first removes the staging directories this host's
  /// processes left there when they were killed (their PID is not running),
  /// never another host's (shards of a sweep on a shared file system).
  explicit StagedOutput(std::filesystem::path dir);
  ~StagedOutput();
  StagedOutput(const StagedOutput&) = delete;
  StagedOutput& operator=(const StagedOutput&) = delete;

  /// Where to write the output file `name` before commit().
  std::filesystem::path path(const std::string& name) const { return staging_ / name; }
  /// Moves every staged file into the destination (each rename is atomic).
  void commit();

 private:
  std::filesystem::path dir_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

/// The staging directory name of process `pid` on this host: ".staging-HOST-PID".
std::string staging_name(long pid);

/// Removes the staging directories in `dir` of this host's processes that are
/// no longer running; returns how many.
int remove_stale_staging(const std::filesystem::path& dir);

/// Writes `text` to `path` through a temporary file and a rename; OutputError
/// naming the file and the system's reason when any step fails.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace campo
