#include "core/output_dir.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
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

// What a file's mode makes it, for messages: "a directory", "a character device" ...
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISREG(mode)) return "a regular file";
  return "not a regular file";
}

// The path with "(links to TARGET)" when a link led elsewhere, so a refusal says what was found where.
std::string named(const fs::path& path, const fs::path& target) {
  return path == target ? path.string() : path.string() + " (links to " + target.string() + ")";
}

// The nearest folder that exists on the way to `path` (the path itself when it exists); ENOTDIR
// when a component on the way is not a folder.
fs::path nearest_existing(const fs::path& path) {
  fs::path at = path.empty() ? fs::path(".") : path;
  for (int depth = 0; depth < 4096; ++depth) {
    struct stat st {};
    if (::stat(at.c_str(), &st) == 0) return at;
    if (errno != ENOENT) return at;  // stat's own error is reported by the caller's check
    const fs::path parent = at.has_relative_path() ? at.parent_path() : at;
    if (parent == at || parent.empty()) return fs::path(".");
    at = parent;
  }
  return at;
}

// The nearest existing folder on the way to `path` must be a folder campo can write into.
void check_writable_folder(const fs::path& path, const std::string& what, const fs::path& shown) {
  const fs::path folder = nearest_existing(path);
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0) throw OutputError(shown, system_reason(what + ": cannot use", errno));
  if (!S_ISDIR(st.st_mode)) {
    throw OutputError(shown, what + ": " + folder.string() + " is " + kind_of(st.st_mode) + ", expected a directory");
  }
  // access() reports a read-only file system (EROFS) even to root, who passes every permission check.
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw OutputError(shown, system_reason(what + ": cannot write in " + folder.string(), errno));
  }
}

}  // namespace

fs::path output_file_target(const fs::path& path) {
  if (path.empty()) throw OutputError("\"\" (empty path)", "expected the path of a file to write, got an empty path");
  fs::path at = path;
  // The system allows 40 links in one resolution (ELOOP); a chain longer than that is a loop here too.
  for (int links = 0; links <= 40; ++links) {
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) {
      if (errno == ENOENT) return at;  // a new file (its folder is checked when it is written)
      throw OutputError(named(path, at), system_reason("cannot write", errno));
    }
    if (S_ISREG(st.st_mode)) return at;
    if (!S_ISLNK(st.st_mode)) {
      throw OutputError(named(path, at), "is " + kind_of(st.st_mode) + "; expected a regular file or a new path");
    }
    std::error_code ec;
    const fs::path link = fs::read_symlink(at, ec);
    if (ec) throw OutputError(named(path, at), system_reason("cannot follow the symbolic link", ec.value()));
    at = link.is_absolute() ? link : at.parent_path() / link;
  }
  throw OutputError(path, "cannot write: too many levels of symbolic links (a loop?)");
}

void check_output_file(const fs::path& path, const std::string& what) {
  if (path.empty()) throw InputError("command line", what, "expected the path of a file to write, got an empty path");
  const fs::path target = output_file_target(path);
  check_writable_folder(target.has_parent_path() ? target.parent_path() : fs::path("."), what, path);
}

void check_output_directory(const fs::path& path, const std::string& what) {
  if (path.empty()) throw InputError("command line", what, "expected a directory to write into, got an empty path");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISDIR(st.st_mode)) {
    throw OutputError(path, what + ": is " + kind_of(st.st_mode) + ", expected a directory (or a new path)");
  }
  if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode) && ::stat(path.c_str(), &st) != 0) {
    throw OutputError(path, system_reason(what + ": cannot follow the symbolic link", errno));
  }
  check_writable_folder(path, what, path);
}

void create_output_directories(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw OutputError(dir, system_reason("cannot create the directory", ec.value()));
}

namespace {

// Copies one regular file's bytes; the system's errno of the first failure, 0 when done.
int copy_bytes(const fs::path& from, const fs::path& to) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) return errno;
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (out < 0) {
    const int errnum = errno;
    ::close(in);
    return errnum;
  }
  int errnum = 0;
  std::vector<char> buffer(1 << 16);
  for (ssize_t n; errnum == 0 && (n = ::read(in, buffer.data(), buffer.size())) != 0;) {
    if (n < 0) {
      if (errno != EINTR) errnum = errno;
      continue;
    }
    for (ssize_t done = 0; errnum == 0 && done < n;) {
      const ssize_t w = ::write(out, buffer.data() + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno != EINTR) errnum = errno;
      if (w > 0) done += w;
    }
  }
  ::close(in);
  // Some file systems report a full disk only when the file is closed.
  if (::close(out) != 0 && errnum == 0) errnum = errno;
  return errnum;
}

}  // namespace

void copy_output_tree(const fs::path& from, const fs::path& to) {
  create_output_directories(to);
  std::error_code ec;
  for (fs::recursive_directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path target = to / it->path().lexically_relative(from);
    const fs::file_status status = it->symlink_status(ec);
    if (ec) break;
    if (fs::is_directory(status)) {
      create_output_directories(target);
    } else if (fs::is_symlink(status)) {
      fs::copy_symlink(it->path(), target, ec);
      if (ec) throw OutputError(target, system_reason("cannot write", ec.value()));
    } else if (fs::is_regular_file(status)) {
      if (const int errnum = copy_bytes(it->path(), target)) {
        throw OutputError(target, system_reason("cannot copy " + it->path().string(), errnum));
      }
    }
  }
  if (ec) throw OutputError(from, system_reason("cannot read", ec.value()));
}

OutputDirectory::OutputDirectory(fs::path dir) : dir_(std::move(dir)) {
  if (dir_.empty()) throw OutputError("\"\" (empty path)", "expected a directory to write into, got an empty path");
  // The missing folders on the way, outermost first, made one by one so each one made is known.
  std::vector<fs::path> missing;
  for (fs::path at = dir_; !at.empty(); at = at.parent_path()) {
    struct stat st {};
    if (::stat(at.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) throw OutputError(at, "is " + kind_of(st.st_mode) + ", expected a directory");
      break;
    }
    if (errno != ENOENT) throw OutputError(at, system_reason("cannot create the output directory", errno));
    missing.push_back(at);
    if (!at.has_relative_path() || at.parent_path() == at) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) != 0 && errno != EEXIST) {
      const int errnum = errno;
      remove_created();
      throw OutputError(*it, system_reason("cannot create the output directory", errnum));
    }
    created_.push_back(*it);
  }
}

OutputDirectory::OutputDirectory(OutputDirectory&& other) noexcept
    : dir_(std::move(other.dir_)), created_(std::move(other.created_)) {
  other.created_.clear();
}

OutputDirectory::~OutputDirectory() { remove_created(); }

void OutputDirectory::remove_created() noexcept {
  // rmdir removes a folder only when it is empty: whatever was written into them stays.
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());
  created_.clear();
}

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
    remove_stale_staging(dir_.path());
    staging_ = dir_.path() / staging_name(::getpid());
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
      const fs::path target = dir_.path() / entry.path().filename();
      if (entry.is_directory()) {
        // A directory left by an earlier run into the same place is replaced whole,
        // so no stale files (an older run's depth maps) mix with the new ones.
        if (fs::is_directory(target)) fs::remove_all(target);
        fs::rename(entry.path(), target);
      } else {
        move_file_into_place(entry.path(), target);
      }
    }
  } catch (const fs::filesystem_error& e) {
    rethrow_as_output_error(e, "cannot move into place");
  }
  committed_ = true;
}

void move_file_into_place(const fs::path& staged, const fs::path& path) {
  const fs::path target = output_file_target(path);
  if (::rename(staged.c_str(), target.c_str()) == 0) return;
  if (errno != EXDEV) throw OutputError(path, system_reason("cannot move into place", errno));
  // A link to another file system: the bytes are copied there, through a temporary file of its own.
  const fs::path tmp = target.string() + ".tmp-" + std::to_string(::getpid());
  std::error_code ec;
  fs::copy_file(staged, tmp, fs::copy_options::overwrite_existing, ec);
  if (!ec && ::rename(tmp.c_str(), target.c_str()) != 0) ec.assign(errno, std::generic_category());
  if (ec) {
    ::unlink(tmp.c_str());
    throw OutputError(path, system_reason("cannot write", ec.value()));
  }
  ::unlink(staged.c_str());
}

void write_file_atomically(const fs::path& link, const std::string& text) {
  // The bytes go to what a link names, so the link stays; the temporary file sits beside the target.
  const fs::path path = output_file_target(link);
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
