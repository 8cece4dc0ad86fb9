// The fretwear program run as a user runs it, for the tests that drive the whole program: in a folder of its own,
// with arguments and environment, under a time limit; how it ended and what it printed. Header-only; the tests
// define FRETWEAR_EXE (the program) and FRETWEAR_SOURCE_DIR.
#pragma once

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace fretwear::test {

namespace fs = std::filesystem;

// How the program ended: its exit status, or the signal that killed it (or the time limit).
struct Outcome {
  int status = -1;     // exit status; -1 when it did not exit
  int signal = 0;      // the signal that ended it, if one did
  bool timed_out = false;
  std::string out, err;  // stdout, stderr
  std::string all() const { return out + err; }
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A started program: wait() for its outcome.
class Running {
 public:
  Running(const fs::path& dir, const std::vector<std::string>& args, const std::vector<std::string>& env = {})
      : logs_(fs::temp_directory_path() / ("fretwear-test-" + std::to_string(::getpid()) + "-" +
                                          std::to_string(counter()++))) {
    fs::create_directories(logs_);
    std::vector<std::string> words{FRETWEAR_EXE};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    std::vector<std::string> vars;
    for (char** e = environ; *e; ++e) vars.emplace_back(*e);
    vars.insert(vars.end(), env.begin(), env.end());
    std::vector<char*> envp;
    for (auto& v : vars) envp.push_back(v.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (logs_ / "out").c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, (logs_ / "err").c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    if (posix_spawn(&pid_, FRETWEAR_EXE, &actions, nullptr, argv.data(), envp.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Running() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    std::error_code ec;
    fs::remove_all(logs_, ec);
  }
  Running(const Running&) = delete;
  Running& operator=(const Running&) = delete;

  void signal(int sig) const { ::kill(pid_, sig); }
  // What stderr holds so far.
  std::string err_so_far() const { return read_file(logs_ / "err"); }

  // Waits at most `limit`, then kills it (timed_out).
  Outcome wait(std::chrono::seconds limit = std::chrono::seconds(120)) {
    Outcome o;
    if (pid_ <= 0) return o;
    const auto deadline = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        o.timed_out = true;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    pid_ = -1;
    if (WIFEXITED(status)) o.status = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
    o.out = read_file(logs_ / "out");
    o.err = read_file(logs_ / "err");
    return o;
  }

 private:
  static int& counter() {
    static int n = 0;
    return n;
  }
  pid_t pid_ = -1;
  fs::path logs_;
};

// Runs the program in `dir` to its end (or the time limit).
inline Outcome run_program(const fs::path& dir, const std::vector<std::string>& args,
                           const std::vector<std::string>& env = {},
                           std::chrono::seconds limit = std::chrono::seconds(120)) {
  return Running(dir, args, env).wait(limit);
}

// A scratch folder, removed with everything in it at the end of the test.
struct Scratch {
  fs::path path;
  explicit Scratch(const std::string& name = "scratch")
      : path(fs::temp_directory_path() /
             ("fretwear-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(++count()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  static int& count() {
    static int n = 0;
    return n;
  }
};

inline void write_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// Every file under dir (relative path → content), to compare before and after a command.
inline std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    files[fs::relative(e.path(), dir).string() + (e.is_directory() ? "/" : "")] =
        e.is_regular_file() ? read_file(e.path()) : std::string();
  return files;
}

// Entries under dir whose name holds ".partial-", ".old-" or ".tmp": what an interrupted command may leave behind.
inline std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    for (const char* mark : {".partial-", ".old-", ".tmp"})
      if (name.find(mark) != std::string::npos) found.push_back(fs::relative(e.path(), dir).string());
  }
  return found;
}

}  // namespace fretwear::test
