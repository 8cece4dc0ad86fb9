// The fretwear program as a whole, for the system tier. The program is run by tests/program.hpp (the one runner:
// a folder of its own, a time limit, stdout and stderr kept apart, death by a signal told apart from an exit status);
// this tier adds what it holds the whole program to: a folder tree of the user's with sentinel files in it, what a
// run did to the tree found by comparing it before and after, small scenes, and case tables checked against the
// contract.
//
// The contract these tests hold the program to (exit status, output folders, what is never touched) is the one of
// the "Additions (second round)" of the workplace's SCENES.md; the tests name the rule each case checks.
#pragma once

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "../program.hpp"  // tests/program.hpp: a bare "program.hpp" would name this file

namespace fretwear::system_test {

namespace fs = std::filesystem;
using nlohmann::json;

// Exit statuses of the contract: 0 done, 2 invalid scene or refused output folder, 3 a solver did not converge,
// 130 a wear run stopped by SIGINT. 1 (internal error) is never right.
constexpr int kDone = 0, kInvalid = 2, kNotConverged = 3, kInterrupted = 130;

// Seconds a single run may take before it counts as hung and is killed. Every scene of this tier runs in well
// under a second; the limit only keeps a hung program from stalling the suite.
constexpr double kTimeLimit = 60.0;

// The runner of tests/program.hpp.
using test::Env;
using test::Outcome;
using test::read_file;
using test::Snapshot;
using test::write_file;
using Child = test::Running;  // a started run: running(), signal(), wait()

// ---------------------------------------------------------------------------------------------------------------
// The user's folder tree

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

// The executable `name` in a folder of PATH, as the program finds it; empty when there is none.
inline fs::path on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / name;
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate;
  }
  return {};
}

// A folder tree of the user's own for one case, with sentinel files the program must never touch:
//   <root>/tree/notes.txt
//   <root>/tree/home/notes.txt
//   <root>/tree/home/work/notes.txt          the working folder of every run
//   <root>/tree/home/work/keep/inner.txt     a folder of the user's with a file in it
// (The runner keeps stdout and stderr of the runs in a folder of its own, outside the tree.)
// Every path a case hands the program resolves inside <root>/tree, so that even a program that wrongly replaces
// the folder it was given can only harm the tree.
class Scratch {
 public:
  fs::path root, tree, home, work;

  Scratch() {
    static int serial = 0;
    const std::string unique = std::to_string(::getpid()) + "-" + std::to_string(++serial) + "-" +
                               std::to_string(std::random_device{}() % 100000);
    root = fs::temp_directory_path() / ("fretwear-system-" + unique);
    tree = root / "tree";
    home = tree / "home";
    work = home / "work";
    fs::create_directories(work / "keep");
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

  Snapshot snapshot() const { return test::snapshot(tree); }

  // Runs the program in the working folder.
  Outcome fretwear(const std::vector<std::string>& args, const Env& env = {}, double time_limit = kTimeLimit) const {
    return test::run_program(work, args, env, time_limit);
  }
  // Runs the program in the working folder with files limited to `blocks` blocks of the shell's ulimit -f: past it
  // a write fails (EFBIG), as on a full disk (ENOSPC), once SIGXFSZ, which would end the process first, is ignored
  // (an ignored signal stays so across exec).
  Outcome fretwear_file_limited(int blocks, const std::vector<std::string>& args, const Env& env = {}) const {
    const std::string limit = "ulimit -f " + std::to_string(blocks) + " && trap '' XFSZ && exec \"$@\"";
    test::Command limited{{"/bin/sh", "-c", limit, "sh", FRETWEAR_EXE}};
    limited.words.insert(limited.words.end(), args.begin(), args.end());
    return test::run_program(limited, work, env, kTimeLimit);
  }
  // Starts the program in the working folder: wait() for it.
  Child start(const std::vector<std::string>& args, const Env& env = {}, double time_limit = kTimeLimit) const {
    return Child(work, args, env, time_limit);
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
