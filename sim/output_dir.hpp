#pragma once
/// All-or-nothing output: files are written into a hidden staging directory
/// inside the destination and moved into place by commit(). If the run fails
/// before commit(), the staging directory is removed and nothing is left
/// half-written.
#include <filesystem>
#include <string>

namespace campo {

class StagedOutput {
 public:
  /// Creates `dir` (and parents) and a unique staging directory inside it.
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

/// Writes `text` to `path` through a temporary file and a rename.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace campo
