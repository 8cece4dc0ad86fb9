// The fretwear program as a whole, run as a user runs it, for the system tier: in a folder tree of its own with
// the user's files in it, under a time limit, stdout and stderr kept apart, death by a signal told apart from an
// exit status (a shell reports both as 128 + n), and what the run did to the tree found by comparing it before and
// after.
//
// The contract these tests hold the program to (exit status, output folders, what is never touched) is the one of
// the "Additions (second round)" of the workplace's SCENES.md; the tests name the rule each case checks.
#pragma once

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fretwear::system_test {

namespace fs = std::filesystem;
using nlohmann::json;

// Exit statuses of the contract: 0 done, 2 invalid scene or refused output folder, 3 a solver did not converge,
// 130 a wear run stopped by SIGINT. 1 (internal error) is never right.
constexpr int kDone = 0, kInvalid = 2, kNotConverged = 3, kInterrupted = 130;

// Seconds a single run may take before it counts as hung and is killed. Every scene of this tier runs in well
// under a second; the limit only keeps a hung program from stalling the suite.
constexpr double kTimeLimit = 60.0;

// ---------------------------------------------------------------------------------------------------------------
// Running the program

// How one run of the program ended.
struct Outcome {
  int status = -1;         // the exit status, when it exited
  int signal = 0;          // the signal that ended it; 0 when it exited
  bool timed_out = false;  // still running at the time limit, and killed
  std::string out, err;    // what it wrote on stdout and on stderr

  bool exited(int want) const { return signal == 0 && !timed_out && status == want; }
  // A crash by the contract: exit 1 (internal error), death by a signal, or a hang.
  bool crashed() const { return timed_out || signal != 0 || status == 1; }

  std::string describe() const {
    std::string said = err.substr(0, 400) + (err.size() > 400 ? "..." : "");
    for (auto nl = said.find('\n'); nl != std::string::npos; nl = said.find('\n', nl)) said.replace(nl, 1, " | ");
    if (timed_out) return "still running at the time limit (killed)";
    if (signal != 0) return "killed by signal " + std::to_string(signal) + " (" + ::strsignal(signal) + ")";
    return "exit " + std::to_string(status) + (said.empty() ? std::string() : ": " + said);
  }
};

// What to start: the arguments after the program's name, variables added to its environment, a time limit.
struct Launch {
  std::vector<std::string> args;
  std::vector<std::pair<std::string, std::string>> env = {};
  double time_limit = kTimeLimit;  // s
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline void write_file(const fs::path& p, const std::string& bytes) {
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

// The program running as a child in its own process group, stdout and stderr into two files of `logs`.
class Child {
 public:
  Child(const fs::path& dir, const fs::path& logs, Launch launch) : launch_(std::move(launch)) {
    static int serial = 0;
    const std::string stem = "run" + std::to_string(++serial);
    out_ = logs / (stem + ".out");
    err_ = logs / (stem + ".err");
    std::vector<std::string> argv_text = {FRETWEAR_EXE};
    argv_text.insert(argv_text.end(), launch_.args.begin(), launch_.args.end());
    started_ = std::chrono::steady_clock::now();
    pid_ = ::fork();
    REQUIRE(pid_ >= 0);
    if (pid_ == 0) {  // the child: only system calls from here on
      ::setpgid(0, 0);
      const int in = ::open("/dev/null", O_RDONLY);
      const int out = ::open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (in < 0 || out < 0 || err < 0 || ::chdir(dir.c_str()) != 0) ::_exit(127);
      ::dup2(in, 0);
      ::dup2(out, 1);
      ::dup2(err, 2);
      for (const auto& [name, value] : launch_.env) ::setenv(name.c_str(), value.c_str(), 1);
      std::vector<char*> argv;
      for (auto& a : argv_text) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(FRETWEAR_EXE, argv.data());
      ::_exit(127);
    }
    ::setpgid(pid_, pid_);  // also here, so that the group exists before either side goes on
  }
  ~Child() {
    if (!reaped_) {
      ::kill(-pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  pid_t pid() const { return pid_; }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  }

  // True while it runs; reaps it (keeping its status) when it has ended.
  bool running() {
    if (reaped_) return false;
    const pid_t r = ::waitpid(pid_, &status_, WNOHANG);
    if (r == pid_) reaped_ = true;
    return !reaped_;
  }

  void signal(int sig) const { ::kill(pid_, sig); }

  // Waits for the end, or kills the whole group (the program and a plotting child) at the time limit.
  Outcome wait() {
    Outcome o;
    while (running()) {
      if (seconds() > launch_.time_limit) {
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
    o.out = read_file(out_);
    o.err = read_file(err_);
    fs::remove(out_);
    fs::remove(err_);
    return o;
  }

 private:
  Launch launch_;
  fs::path out_, err_;
  pid_t pid_ = -1;
  int status_ = 0;
  bool reaped_ = false;
  std::chrono::steady_clock::time_point started_;
};

// ---------------------------------------------------------------------------------------------------------------
// The user's folder tree

// Every entry of a tree by its path relative to the tree: a file's bytes, "<folder>", "-> target" for a link.
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
      s[key] = "<special>";  // a FIFO is never read
  }
  return s;
}

// What changed from `before` to `after`, one line per entry ("removed x", "changed x", "new x"). Entries under
// one of `exempt` (folders the run may write, relative to the tree) are left out.
inline std::vector<std::string> changes(const Snapshot& before, const Snapshot& after,
                                        const std::vector<std::string>& exempt = {}) {
  auto is_exempt = [&](const std::string& key) {
    for (const auto& e : exempt)
      if (key == e || key.rfind(e + "/", 0) == 0) return true;
    return false;
  };
  std::vector<std::string> lines;
  for (const auto& [key, value] : before) {
    if (is_exempt(key)) continue;
    const auto it = after.find(key);
    if (it == after.end())
      lines.push_back("removed " + key);
    else if (it->second != value)
      lines.push_back("changed " + key);
  }
  for (const auto& [key, value] : after)
    if (!before.count(key) && !is_exempt(key)) lines.push_back("new " + key);
  return lines;
}

// Entries of `after` that are not in `before` and look like a staging folder or a temporary file.
inline std::vector<std::string> leftovers(const Snapshot& before, const Snapshot& after) {
  std::vector<std::string> found;
  for (const auto& [key, value] : after) {
    const std::string name = fs::path(key).filename().string();
    if (!before.count(key) && (name.find(".partial-") != std::string::npos || name.find(".tmp") != std::string::npos))
      found.push_back(key);
  }
  return found;
}

inline std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += (s.empty() ? "" : ", ") + l;
  return s.empty() ? "none" : s;
}

// A folder tree of the user's own for one case, with sentinel files the program must never touch:
//   <root>/tree/notes.txt
//   <root>/tree/home/notes.txt
//   <root>/tree/home/work/notes.txt          the working folder of every run
//   <root>/tree/home/work/keep/inner.txt     a folder of the user's with a file in it
//   <root>/logs/                             stdout and stderr of the runs: outside the tree
// Every path a case hands the program resolves inside <root>/tree, so that even a program that wrongly replaces
// the folder it was given can only harm the tree.
class Scratch {
 public:
  fs::path root, tree, home, work, logs;

  Scratch() {
    static int serial = 0;
    const std::string unique = std::to_string(::getpid()) + "-" + std::to_string(++serial) + "-" +
                               std::to_string(std::random_device{}() % 100000);
    root = fs::temp_directory_path() / ("fretwear-system-" + unique);
    tree = root / "tree";
    home = tree / "home";
    work = home / "work";
    logs = root / "logs";
    fs::create_directories(work / "keep");
    fs::create_directories(logs);
    write_file(tree / "notes.txt", "the user's notes, at the top of the tree\n");
    write_file(home / "notes.txt", "the user's notes, in home\n");
    write_file(work / "notes.txt", "the user's notes, in the working folder\n");
    write_file(work / "keep" / "inner.txt", "a file in a folder of the user's\n");
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  // A file of the working folder (its folders made as needed).
  fs::path write(const std::string& relative, const std::string& bytes) const {
    write_file(work / relative, bytes);
    return work / relative;
  }

  Snapshot snapshot() const { return system_test::snapshot(tree); }

  // Runs the program in the working folder.
  Outcome fretwear(std::vector<std::string> args, std::vector<std::pair<std::string, std::string>> env = {},
                   double time_limit = kTimeLimit) const {
    Child child(work, logs, Launch{std::move(args), std::move(env), time_limit});
    return child.wait();
  }
  Child start(std::vector<std::string> args, std::vector<std::pair<std::string, std::string>> env = {},
              double time_limit = kTimeLimit) const {
    return Child(work, logs, Launch{std::move(args), std::move(env), time_limit});
  }
};

// ---------------------------------------------------------------------------------------------------------------
// Scenes

// The small valid base of the suite: Hertz, E = 200 GPa, ν = 0.3, R = 10 mm, P = 1e5 N/m, 256 cells (milliseconds).
inline json base_scene() {
  return json::parse(R"({"name": "h", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "grid": {"cells": 256}})");
}

// The base with a load cycle: f = 0.5, Q/fP = 0.5, partial slip.
inline json cycle_scene() {
  json j = base_scene();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"tangential", json::object()}};
  return j;
}

// The base worn: Archard, k = 1e-15 1/Pa, 1e4 cycles (about twenty implicit steps).
inline json wear_scene() {
  json j = base_scene();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"wear", {{"k", 1e-15}, {"cycles", 1e4}}}};
  return j;
}

// `scene` as text with each dotted key set to the raw JSON text given for it (objects made as needed), so that a
// value JSON cannot hold as a number (1e309, 123456789012345678901234567890) reaches the file exactly as written.
inline std::string with(json scene, std::initializer_list<std::pair<std::string, std::string>> edits) {
  int n = 0;
  std::vector<std::pair<std::string, std::string>> marks;
  for (const auto& [key, raw] : edits) {
    json* at = &scene;
    std::stringstream path(key);
    std::vector<std::string> parts;
    for (std::string part; std::getline(path, part, '.');) parts.push_back(part);
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (!at->contains(parts[i]) || !(*at)[parts[i]].is_object()) (*at)[parts[i]] = json::object();
      at = &(*at)[parts[i]];
    }
    const std::string mark = "@edit" + std::to_string(n++) + "@";
    (*at)[parts.back()] = mark;
    marks.emplace_back("\"" + mark + "\"", raw);
  }
  std::string text = scene.dump();
  for (const auto& [mark, raw] : marks) text.replace(text.find(mark), mark.size(), raw);
  return text;
}

// ---------------------------------------------------------------------------------------------------------------
// The verdicts

// The set of exit statuses a case allows, printable.
struct Exits {
  std::set<int> allowed;
  Exits(std::initializer_list<int> s) : allowed(s) {}
  bool has(int status) const { return allowed.count(status) != 0; }
  std::string text() const {
    std::string s;
    for (int a : allowed) s += (s.empty() ? "" : " or ") + std::to_string(a);
    return s;
  }
};

// Non-finite numbers of a completed run's summary.json, by path: the quantities every run reports must be finite
// numbers (a NaN or an infinity reaches JSON as null), and no value anywhere may be the text of one.
inline std::vector<std::string> non_finite(const json& summary) {
  std::vector<std::string> bad;
  auto need = [&](const json& j, const std::string& at) {
    if (!j.is_number() || !std::isfinite(j.get<double>())) bad.push_back(at + " = " + j.dump());
  };
  auto need_all = [&](const json& j, const std::string& at) {
    if (!j.is_array()) return need(j, at);
    for (std::size_t i = 0; i < j.size(); ++i) need(j[i], at + "[" + std::to_string(i) + "]");
  };
  const json& c = summary.value("contact", json::object());
  for (const char* k : {"p_max", "load", "extent"}) need_all(c.value(k, json()), std::string("contact.") + k);
  const json& g = summary.value("grid", json::object());
  for (const char* k : {"h", "window"}) need_all(g.value(k, json()), std::string("grid.") + k);
  if (summary.contains("cycle")) need(summary["cycle"].value("Q_over_fP", json()), "cycle.Q_over_fP");
  if (summary.contains("wear"))
    for (const char* k : {"worn_area", "max_depth"}) need(summary["wear"].value(k, json()), std::string("wear.") + k);
  std::vector<std::pair<const json*, std::string>> todo = {{&summary, ""}};
  while (!todo.empty()) {
    const auto [j, at] = todo.back();
    todo.pop_back();
    if (j->is_structured())
      for (const auto& [k, v] : j->items()) todo.emplace_back(&v, at + "." + k);
    else if (j->is_string() && (*j == "nan" || *j == "inf" || *j == "-inf" || *j == "-nan"))
      bad.push_back(at + " = " + j->dump());
  }
  return bad;
}

// Whether the message names one of the '|'-separated alternatives of `fragment` (empty: any message).
inline bool names(const std::string& message, const std::string& fragment) {
  std::stringstream alternatives(fragment);
  for (std::string a; std::getline(alternatives, a, '|');)
    if (message.find(a) != std::string::npos) return true;
  return fragment.empty();
}

// A scene case: the bytes of a scene file, the exit statuses the contract allows for `run`, and words stderr must
// hold when the program refuses it (the JSON path of the problem, or alternatives "a|b"; empty: any).
struct SceneCase {
  std::string label;
  std::string text;
  Exits exits;
  std::string fragment;
};

// Validates, then runs, the scene in a fresh tree, and holds both to the contract: neither crashes; `run` exits
// with an allowed status; `validate` writes nothing; a refusal names the path and writes nothing; the two agree
// (validate 2 ⇒ run 2; validate 0 ⇒ run 0 or 3); a completed run's summary is finite; no sentinel is touched and no
// staging folder or temporary file is left. `extra` are arguments after the scene's name.
inline void check_scene(const SceneCase& c, const std::vector<std::string>& extra = {"-q"}) {
  INFO("case: " << c.label);
  Scratch s;
  s.write("s.json", c.text);
  const Snapshot before = s.snapshot();

  std::vector<std::string> args = {"validate", "s.json"};
  args.insert(args.end(), extra.begin(), extra.end());
  const Outcome v = s.fretwear(args);
  CHECK_MESSAGE(!v.crashed(), "validate: " << v.describe());
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "validate wrote: " << join(changes(before, s.snapshot())));

  args[0] = "run";
  const Outcome r = s.fretwear(args);
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(!r.crashed(), "run: " << r.describe());
  CHECK_MESSAGE(c.exits.has(r.status), "run: want exit " << c.exits.text() << ", got " << r.describe());
  if (v.exited(kInvalid))
    CHECK_MESSAGE(r.exited(kInvalid), "validate refused the scene, run did not: " << r.describe());
  if (v.exited(kDone))
    CHECK_MESSAGE((r.exited(kDone) || r.exited(kNotConverged)),
                  "validate accepted the scene, run did not complete: " << r.describe());
  if (r.exited(kInvalid)) {
    CHECK_MESSAGE(names(r.err, c.fragment), "run: the message should name \"" << c.fragment << "\": " << r.describe());
    CHECK_MESSAGE(changes(before, after).empty(), "run refused the scene but wrote: " << join(changes(before, after)));
  }
  if (r.exited(kDone)) {
    int summaries = 0;
    for (const auto& [key, bytes] : after) {
      if (fs::path(key).filename() != "summary.json" || before.count(key)) continue;
      ++summaries;
      const json summary = json::parse(bytes, nullptr, false);
      CHECK_MESSAGE(!summary.is_discarded(), key << " is not JSON");
      if (!summary.is_discarded())
        CHECK_MESSAGE(non_finite(summary).empty(), key << ": not finite: " << join(non_finite(summary)));
    }
    CHECK_MESSAGE(summaries == 1, "a completed run wrote " << summaries << " summary.json");
  }
  std::vector<std::string> touched;
  for (const auto& line : changes(before, after))
    if (line.rfind("new ", 0) != 0) touched.push_back(line);
  CHECK_MESSAGE(touched.empty(), "the user's files were touched: " << join(touched));
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
}

}  // namespace fretwear::system_test
