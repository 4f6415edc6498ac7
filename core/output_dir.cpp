#include "core/output_dir.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

namespace campo {

namespace {

namespace fs = std::filesystem;

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "localhost";
  // A name safe in a file name: the host name's own characters are letters, digits, '-' and '.'.
  std::string host(name);
  for (char& c : host) {
    if (c == '/' || c == '\\') c = '_';
  }
  return host;
}

// The filesystem's own errors already carry the system's reason; they become OutputErrors naming the file.
[[noreturn]] void rethrow_as_output_error(const fs::filesystem_error& e, const std::string& what) {
  throw OutputError(e.path1(), system_reason(what, e.code().value()));
}

bool running(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }

}  // namespace

std::string system_reason(const std::string& what, int errnum) { return what + ": " + std::strerror(errnum); }

std::string staging_name(long pid) { return ".staging-" + host_name() + "-" + std::to_string(pid); }

int remove_stale_staging(const fs::path& dir) {
  const std::string prefix = ".staging-" + host_name() + "-";
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid <= 0 || pid == ::getpid() || running(pid)) continue;
    std::error_code remove_error;
    if (fs::remove_all(it->path(), remove_error) != static_cast<std::uintmax_t>(-1) && !remove_error) ++removed;
  }
  return removed;
}

StagedOutput::StagedOutput(fs::path dir) : dir_(std::move(dir)) {
  try {
    fs::create_directories(dir_);
    remove_stale_staging(dir_);
    staging_ = dir_ / staging_name(::getpid());
    fs::remove_all(staging_);
    fs::create_directory(staging_);
  } catch (const fs::filesystem_error& e) {
    rethrow_as_output_error(e, "cannot create the output directory");
  }
}

StagedOutput::~StagedOutput() {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
}

void StagedOutput::commit() {
  try {
    for (const auto& entry : fs::directory_iterator(staging_)) {
      const fs::path target = dir_ / entry.path().filename();
      // A directory left by an earlier run into the same place is replaced whole,
      // so no stale files (an older run's depth maps) mix with the new ones.
      if (entry.is_directory() && fs::is_directory(target)) fs::remove_all(target);
      fs::rename(entry.path(), target);
    }
  } catch (const fs::filesystem_error& e) {
    rethrow_as_output_error(e, "cannot move into place");
  }
  committed_ = true;
}

void write_file_atomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw OutputError(path, system_reason("cannot write", errno));
  const auto fail = [&](int errnum) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw OutputError(path, system_reason("cannot write", errnum));
  };
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(errno);
    done += static_cast<std::size_t>(n);
  }
  // Some file systems report a full disk only when the file is closed.
  if (::close(fd) != 0) {
    const int errnum = errno;
    ::unlink(tmp.c_str());
    throw OutputError(path, system_reason("cannot write", errnum));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int errnum = errno;
    ::unlink(tmp.c_str());
    throw OutputError(path, system_reason("cannot move into place", errnum));
  }
}

}  // namespace campo
