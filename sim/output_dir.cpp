#include "sim/output_dir.hpp"

#include <fstream>
#include <stdexcept>

#include <unistd.h>

namespace campo {

StagedOutput::StagedOutput(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::filesystem::create_directories(dir_);
  staging_ = dir_ / (".staging-" + std::to_string(::getpid()));
  std::filesystem::remove_all(staging_);
  std::filesystem::create_directory(staging_);
}

StagedOutput::~StagedOutput() {
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);
}

void StagedOutput::commit() {
  for (const auto& entry : std::filesystem::directory_iterator(staging_)) {
    const std::filesystem::path target = dir_ / entry.path().filename();
    // A directory left by an earlier run into the same place is replaced whole,
    // so no stale files (an older run's depth maps) mix with the new ones.
    if (entry.is_directory() && std::filesystem::is_directory(target)) std::filesystem::remove_all(target);
    std::filesystem::rename(entry.path(), target);
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace campo
