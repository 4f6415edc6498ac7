#include "reproduce/workbench.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <stdexcept>

#include "campo/json_reader.hpp"
#include "core/output_dir.hpp"

namespace campo {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarker = ".campo-reproduce";

bool needs_quotes(const std::string& word) {
  if (word.empty()) return true;
  for (char c : word) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || std::string_view("/._-=,:+@%").find(c) != std::string_view::npos)) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::string command_line(const std::vector<std::string>& args) {
  std::string out;
  for (const std::string& word : args) {
    if (!out.empty()) out += ' ';
    if (!needs_quotes(word)) {
      out += word;
      continue;
    }
    out += '\'';
    for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

Workbench::Workbench(WorkbenchConfig config) : config_(std::move(config)) {
  const fs::path& work = config_.work_dir;
  if (fs::exists(work) && !fs::is_empty(work)) {
    if (!fs::exists(work / kMarker)) {
      throw InputError("command line", "--work",
                       "\"" + work.string() + "\" is not empty and was not made by campo reproduce; expected a new "
                       "or empty directory");
    }
    fs::remove_all(work);
  }
  create_output_directories(work);
  write_file_atomically(work / kMarker, "campo reproduce work directory: emptied by every campo reproduce\n");
  create_output_directories(config_.figure_dir);
}

std::string Workbench::campo(const std::vector<std::string>& args) const { return run(args, nullptr); }

std::string Workbench::campo(const std::vector<std::string>& args, std::string& output) const {
  return run(args, &output);
}

std::string Workbench::run(const std::vector<std::string>& args, std::string* output) const {
  std::vector<std::string> argv_text{config_.campo_binary.string()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<std::string> shown{"campo"};
  shown.insert(shown.end(), args.begin(), args.end());
  const std::string shown_line = command_line(shown);

  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  int pipe_fds[2] = {-1, -1};
  if (output && pipe(pipe_fds) != 0) throw std::runtime_error("cannot start " + shown_line);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start " + shown_line);
  if (pid == 0) {
    if (output) {
      dup2(pipe_fds[1], STDOUT_FILENO);
      close(pipe_fds[0]);
      close(pipe_fds[1]);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  if (output) {
    close(pipe_fds[1]);
    output->clear();
    char buffer[4096];
    for (ssize_t got; (got = read(pipe_fds[0], buffer, sizeof buffer)) != 0;) {
      if (got > 0) output->append(buffer, static_cast<std::size_t>(got));
      else if (errno != EINTR) break;
    }
    close(pipe_fds[0]);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("lost " + shown_line);
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                              : "signal " + std::to_string(WTERMSIG(status));
    throw std::runtime_error("\"" + shown_line + "\" failed (" + how + ")");
  }
  return shown_line;
}

fs::path Workbench::spec(const fs::path& file, const std::function<void(nlohmann::json&)>& reduce) const {
  if (!config_.quick) return file;
  nlohmann::json document = read_json_file(file);
  for (auto& scene : document.at("scenes")) {
    const std::string name = scene.is_string() ? scene.get<std::string>() : scene.value("file", "");
    if (name.ends_with(".json")) {
      const fs::path absolute = fs::absolute(file.parent_path() / name);
      if (scene.is_string()) scene = absolute.string();
      else scene["file"] = absolute.string();
    }
  }
  reduce(document);
  const fs::path reduced = work(file.stem().string() + "_quick.json");
  write_file_atomically(reduced, document.dump(2) + "\n");
  return reduced;
}

std::string Workbench::publish(const fs::path& png, const std::string& name) const {
  fs::copy_file(png, config_.figure_dir / name, fs::copy_options::overwrite_existing);
  return config_.figure_prefix + name;
}

}  // namespace campo
