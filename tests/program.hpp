// The fretwear program run as a user runs it, for every test that drives the whole program (the regression tier
// here, the system tier through system/program.hpp): in a folder of its own, with arguments and variables added to
// its environment, under a time limit; how it ended (an exit status told apart from death by a signal, which a
// shell would report alike as 128 + n, and from the time limit) and what it wrote on stdout and on stderr, kept
// apart. Header-only; the tests define FRETWEAR_EXE (the program) and FRETWEAR_SOURCE_DIR.
#pragma once

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace fretwear::test {

namespace fs = std::filesystem;

// Seconds a run may take before it counts as hung and is killed. Only a guard against a hung program stalling the
// suite; a test that must not wait so long passes its own limit.
constexpr double kHungAfter = 120.0;

// Variables added to the program's environment, as (name, value); each replaces one of the same name.
using Env = std::vector<std::pair<std::string, std::string>>;

// How one run of the program ended.
struct Outcome {
  int status = -1;         // the exit status, when it exited
  int signal = 0;          // the signal that ended it; 0 when it exited or was killed at the time limit
  bool timed_out = false;  // still running at the time limit, and killed
  std::string out, err;    // what it wrote on stdout and on stderr

  std::string all() const { return out + err; }
  bool exited(int want) const { return signal == 0 && !timed_out && status == want; }
  // A crash: exit 1 (the program's internal error), death by a signal, or a hang.
  bool crashed() const { return timed_out || signal != 0 || status == 1; }

  // One line: how it ended, and the start of what it said on stderr.
  std::string describe() const {
    std::string said = err.substr(0, 400) + (err.size() > 400 ? "..." : "");
    for (auto nl = said.find('\n'); nl != std::string::npos; nl = said.find('\n', nl)) said.replace(nl, 1, " | ");
    if (timed_out) return "still running at the time limit (killed)";
    if (signal != 0) return "killed by signal " + std::to_string(signal) + " (" + ::strsignal(signal) + ")";
    return "exit " + std::to_string(status) + (said.empty() ? std::string() : ": " + said);
  }
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline void write_file(const fs::path& p, const std::string& bytes) {
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

// A program other than fretwear and its arguments, the program first (a path, or a name looked up on PATH): each
// word reaches it as it is, never through a shell.
struct Command {
  std::vector<std::string> words;
};

// The program started in `dir`: in a process group of its own (so that the time limit ends its children too),
// stdin from /dev/null, stdout and stderr into two files outside `dir`, signals at their defaults whatever the test
// runner's. wait() for its outcome; the destructor kills it if it still runs.
class Running {
 public:
  Running(const fs::path& dir, const std::vector<std::string>& args, const Env& env = {},
          double time_limit = kHungAfter)
      : Running(with_fretwear(args), dir, env, time_limit) {}
  // Another program (a helper the tests drive: an MPI launcher, a browser), run the same way.
  Running(const Command& command, const fs::path& dir, const Env& env = {}, double time_limit = kHungAfter)
      : time_limit_(time_limit),
        logs_(fs::temp_directory_path() / ("fretwear-test-" + std::to_string(::getpid()) + "-" +
                                          std::to_string(++counter()))) {
    fs::create_directories(logs_);
    std::vector<std::string> words = command.words;
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);

    std::vector<std::string> vars;
    for (char** e = environ; *e; ++e) {
      const std::string var = *e;
      const std::string name = var.substr(0, var.find('='));
      if (std::none_of(env.begin(), env.end(), [&](const auto& added) { return added.first == name; }))
        vars.push_back(var);
    }
    for (const auto& [name, value] : env) vars.push_back(name + "=" + value);
    std::vector<char*> envp;
    for (auto& v : vars) envp.push_back(v.data());
    envp.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE}) sigaddset(&defaults, sig);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setpgroup(&attributes, 0);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    const int failed = posix_spawnp(&pid_, argv[0], &actions, &attributes, argv.data(), envp.data());
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    started_ = std::chrono::steady_clock::now();
    if (failed) {
      pid_ = -1;
      std::error_code ec;
      fs::remove_all(logs_, ec);
    }
    REQUIRE_MESSAGE(!failed, "could not start " << words[0] << " in " << dir.string() << ": " << std::strerror(failed));
  }
  ~Running() {
    if (pid_ > 0 && !reaped_) {
      ::kill(-pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    std::error_code ec;
    fs::remove_all(logs_, ec);
  }
  Running(const Running&) = delete;
  Running& operator=(const Running&) = delete;

  pid_t pid() const { return pid_; }
  // Seconds since the start.
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  }

  // True while it runs; reaps it (keeping its status) when it has ended.
  bool running() {
    if (reaped_ || pid_ <= 0) return false;
    if (::waitpid(pid_, &status_, WNOHANG) == pid_) reaped_ = true;
    return !reaped_;
  }

  // Sends `sig` to the program (not to its group).
  void signal(int sig) const { ::kill(pid_, sig); }

  // What stderr holds so far.
  std::string err_so_far() const { return read_file(err_path()); }

  // Waits for the end, or kills the whole group at the time limit.
  Outcome wait() {
    Outcome o;
    while (running()) {
      if (seconds() > time_limit_) {
        ::kill(-pid_, SIGKILL);
        ::waitpid(pid_, &status_, 0);
        reaped_ = true;
        o.timed_out = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (!o.timed_out) {
      if (WIFEXITED(status_)) o.status = WEXITSTATUS(status_);
      if (WIFSIGNALED(status_)) o.signal = WTERMSIG(status_);
    }
    o.out = read_file(out_path());
    o.err = read_file(err_path());
    return o;
  }

 private:
  static Command with_fretwear(const std::vector<std::string>& args) {
    Command c{{FRETWEAR_EXE}};
    c.words.insert(c.words.end(), args.begin(), args.end());
    return c;
  }
  static int& counter() {
    static int n = 0;
    return n;
  }
  fs::path out_path() const { return logs_ / "out"; }
  fs::path err_path() const { return logs_ / "err"; }

  double time_limit_;  // s
  fs::path logs_;
  pid_t pid_ = -1;
  int status_ = 0;
  bool reaped_ = false;
  std::chrono::steady_clock::time_point started_;
};

// Runs the program in `dir` to its end (or the time limit).
inline Outcome run_program(const fs::path& dir, const std::vector<std::string>& args, const Env& env = {},
                           double time_limit = kHungAfter) {
  return Running(dir, args, env, time_limit).wait();
}
inline Outcome run_program(const Command& command, const fs::path& dir, const Env& env = {},
                           double time_limit = kHungAfter) {
  return Running(command, dir, env, time_limit).wait();
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

// Every entry of a tree by its path relative to the tree: a file's bytes, "<folder>", "-> target" for a link
// (never followed), "<special>" for anything else (a FIFO is never read). Compare two to see what a command did.
using Snapshot = std::map<std::string, std::string>;

inline Snapshot snapshot(const fs::path& tree) {
  Snapshot s;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(tree, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path& p = it->path();
    const std::string key = p.lexically_relative(tree).generic_string();
    const auto st = fs::symlink_status(p);
    if (fs::is_symlink(st))
      s[key] = "-> " + fs::read_symlink(p).string();
    else if (fs::is_directory(st))
      s[key] = "<folder>";
    else if (fs::is_regular_file(st))
      s[key] = read_file(p);
    else
      s[key] = "<special>";
  }
  return s;
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
