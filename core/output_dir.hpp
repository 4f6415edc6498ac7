#pragma once
/// All-or-nothing output: files are written into a hidden staging directory
/// inside the destination and moved into place by commit(). If the run fails
/// before commit(), the staging directory is removed and nothing is left
/// half-written. Every failure to write names the file and the system's
/// reason ("No space left on device").
#include <filesystem>
#include <string>
#include <vector>

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

/// The file an output path names once symbolic links are followed (a chain of
/// them, relative ones against their own folder): where the bytes go. It is a
/// regular file or does not exist yet. OutputError for an empty path, a loop
/// of links, or a path that names a directory, device, FIFO or socket: campo
/// writes through links, never replaces what is not a file of its own.
std::filesystem::path output_file_target(const std::filesystem::path& path);

/// Checks before any work that `path` can become an output file: its target
/// (output_file_target) is a regular file or new, and the nearest existing
/// folder on its way is a folder campo may write into (not on a read-only
/// file system). OutputError naming the path and the reason otherwise. `what`
/// names the option in the message ("--out").
void check_output_file(const std::filesystem::path& path, const std::string& what);

/// The same for an output directory: it is a directory (links followed) or
/// can be created in the nearest existing folder, which must be writable.
void check_output_directory(const std::filesystem::path& path, const std::string& what);

/// std::filesystem::create_directories, failing with an OutputError that names the
/// folder and the system's reason; for folders inside an output being staged.
void create_output_directories(const std::filesystem::path& dir);

/// Copies the folder `from` with everything in it to `to` (made with its parents), file by file,
/// links as links. OutputError naming the file and the system's own reason (std::filesystem's
/// copy reports a full disk as "Input/output error").
void copy_output_tree(const std::filesystem::path& from, const std::filesystem::path& to);

/// A directory created with its missing parents for output. Those it created
/// are removed again on destruction when they are still empty, so a command
/// that fails leaves no empty folder behind (a folder with files in it, or one
/// that existed before, is never touched).
class OutputDirectory {
 public:
  /// OutputError naming the path and the system's reason when it cannot be made.
  explicit OutputDirectory(std::filesystem::path dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;
  OutputDirectory(OutputDirectory&&) noexcept;
  OutputDirectory& operator=(OutputDirectory&&) = delete;

  const std::filesystem::path& path() const { return dir_; }

 private:
  void remove_created() noexcept;

  std::filesystem::path dir_;
  std::vector<std::filesystem::path> created_;  ///< deepest last
};

class StagedOutput {
 public:
  /// Creates `dir` (and parents; removed again if still empty when the output
  /// is not committed) and a staging directory inside it named
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
  OutputDirectory dir_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

/// The staging directory name of process `pid` on this host: ".staging-HOST-PID".
std::string staging_name(long pid);

/// Removes the staging directories in `dir` of this host's processes that are
/// no longer running; returns how many.
int remove_stale_staging(const std::filesystem::path& dir);

/// Writes `text` to `path` through a temporary file and a rename; OutputError
/// naming the file and the system's reason when any step fails. A symbolic
/// link is followed and its target replaced; a path that names anything but
/// a regular file (a device, a FIFO, a directory) is refused
/// (output_file_target).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

/// Moves the finished file `staged` to `path` (links followed, as write_file_atomically): a rename,
/// or a copy through a temporary file when the target is on another file system.
void move_file_into_place(const std::filesystem::path& staged, const std::filesystem::path& path);

}  // namespace campo
