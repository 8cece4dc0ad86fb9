// Long runs (docs/SCENES.md, "Long runs"): a wear run stopped by a signal keeps what it recorded and its checkpoint,
// `run --resume` continues it to the result of an uninterrupted run, and a checkpoint of another scene is refused.
// Real signals to a real process: the program runs as a child, and the test signals it once its first checkpoint
// exists. FRETWEAR_STEP_PAUSE_MS slows its steps (2 ms each) so that the signal lands part way through the run.
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "support.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("fretwear-resume-" + std::to_string(::getpid()) + "-" + std::to_string(std::random_device{}()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

// The program started in dir with args (stdout and stderr into dir/log.txt); its pid.
pid_t spawn(const fs::path& dir, std::vector<std::string> args, int pause_ms = 0) {
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(127);
    const int fd = ::open("log.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    if (pause_ms > 0) ::setenv("FRETWEAR_STEP_PAUSE_MS", std::to_string(pause_ms).c_str(), 1);
    args.insert(args.begin(), FRETWEAR_EXE);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(FRETWEAR_EXE, argv.data());
    ::_exit(127);
  }
  return pid;
}

// The exit status (128 + n when killed by signal n, as a shell reports it).
int wait_for(pid_t pid) {
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int run(const fs::path& dir, std::vector<std::string> args, std::string* log = nullptr) {
  const int status = wait_for(spawn(dir, std::move(args)));
  if (log) {
    std::ifstream in(dir / "log.txt");
    log->assign(std::istreambuf_iterator<char>(in), {});
  }
  return status;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Waits (up to 20 s) until the file exists.
bool wait_for_file(const fs::path& p) {
  for (int i = 0; i < 20000 && !fs::exists(p); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return fs::exists(p);
}

// The small wear run of the issue: Hertz, R = 10 mm, E = 200 GPa, ν = 0.3, P = 1e5 N/m, f = 0.5, Q/fP = 0.5,
// k = 1e-12 1/Pa, 1e6 cycles, 8 records, 256 cells.
std::string scene(const std::string& k = "1e-12") {
  return R"({"name": "resume", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 256}, "effects": {"wear": {"k": )" +
         k + R"(, "cycles": 1e6, "record": 8}}, "output": {"dir": "out/resume", "plots": false}})";
}

// Every value of `want` other than timings (and the resumed run's own note) agrees with `got`: numbers to 1e-10
// relative, the rest exactly. Returns how many numbers were compared.
int compare(const json& got, const json& want, const std::string& at = "") {
  int numbers = 0;
  if (want.is_object()) {
    CHECK_MESSAGE(got.is_object(), at);
    for (const auto& [key, value] : want.items()) {
      if (key == "timings" || key == "seconds" || key == "brief") continue;  // wall time
      CHECK_MESSAGE(got.contains(key), (at + "." + key));
      if (got.contains(key)) numbers += compare(got[key], value, at + "." + key);
    }
    for (const auto& [key, value] : got.items())
      CHECK_MESSAGE((want.contains(key) || key == "resumed_from"), (at + "." + key + " only in the resumed run"));
  } else if (want.is_array()) {
    REQUIRE_MESSAGE(got.size() == want.size(), at);
    for (std::size_t i = 0; i < want.size(); ++i) numbers += compare(got[i], want[i], at + "[" + std::to_string(i) + "]");
  } else if (want.is_number() && got.is_number()) {
    const double a = got.get<double>(), b = want.get<double>();
    if (b == 0.0)
      CHECK_MESSAGE(a == 0.0, at);
    else
      CHECK_MESSAGE(a == fretwear::test::rel(b, 1e-10), at);
    ++numbers;
  } else {
    CHECK_MESSAGE(got == want, at);
  }
  return numbers;
}

bool partial_left(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".partial") != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("Ctrl-C stops a wear run with status 130, keeps what was recorded, and --resume ends as an uninterrupted run") {
  TempDir tmp;
  std::ofstream(tmp.path / "s.json") << scene();
  const fs::path out = tmp.path / "out" / "resume", checkpoint = tmp.path / "out" / "resume.checkpoint";
  REQUIRE(run(tmp.path, {"run", "s.json", "-q"}) == 0);
  const json whole = json::parse(read(out / "summary.json"));
  const std::string whole_history = read(out / "wear_history.csv");
  CHECK(whole["status"] == "completed");
  CHECK(!fs::exists(checkpoint));  // a completed run leaves none

  const pid_t pid = spawn(tmp.path, {"run", "s.json", "--checkpoint-every", "0"}, 2);
  REQUIRE(wait_for_file(checkpoint));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ::kill(pid, SIGINT);
  REQUIRE(wait_for(pid) == 130);
  const std::string log = read(tmp.path / "log.txt");
  CHECK(log.find("--resume") != std::string::npos);
  const json stopped = json::parse(read(out / "summary.json"));
  CHECK(stopped["status"] == "interrupted");
  const double reached = stopped["wear"]["cycles_reached"].get<double>();
  CHECK(reached > 0.0);
  CHECK(reached < 1e6);
  CHECK(stopped["wear"]["cycles"].get<double>() <= reached);  // the last record
  CHECK(!stopped.contains("crack"));
  // What was recorded is written: a row per record so far, each as the uninterrupted run's.
  const std::string history = read(out / "wear_history.csv");
  CHECK(whole_history.rfind(history, 0) == 0);
  CHECK(fs::exists(checkpoint));
  CHECK(!partial_left(tmp.path / "out"));

  std::string resumed_log;
  REQUIRE(run(tmp.path, {"run", "--resume", "s.json"}, &resumed_log) == 0);
  CHECK(resumed_log.find("resuming at cycle") != std::string::npos);
  const json resumed = json::parse(read(out / "summary.json"));
  CHECK(resumed["wear"]["resumed_from"].get<double>() == fretwear::test::rel(reached, 1e-15));
  CHECK(compare(resumed, whole) > 40);
  CHECK(read(out / "wear_history.csv") == whole_history);
  CHECK(!fs::exists(checkpoint));
  CHECK(!partial_left(tmp.path / "out"));
}

TEST_CASE("a run killed at a random point resumes from its last checkpoint to the uninterrupted result") {
  TempDir tmp;
  std::ofstream(tmp.path / "s.json") << scene();
  const fs::path out = tmp.path / "out" / "resume", checkpoint = tmp.path / "out" / "resume.checkpoint";
  REQUIRE(run(tmp.path, {"run", "s.json", "-q"}) == 0);
  const json whole = json::parse(read(out / "summary.json"));
  std::mt19937 random(std::random_device{}());
  const int delay_ms = std::uniform_int_distribution<int>(0, 300)(random);
  INFO("killed " << delay_ms << " ms after the first checkpoint");
  const pid_t pid = spawn(tmp.path, {"run", "s.json", "-q", "--checkpoint-every", "0"}, 2);
  REQUIRE(wait_for_file(checkpoint));
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  ::kill(pid, SIGKILL);
  wait_for(pid);
  // A killed run may leave its staging folder; the next run removes it.
  REQUIRE(run(tmp.path, {"run", "--resume", "s.json", "-q"}) == 0);
  CHECK(compare(json::parse(read(out / "summary.json")), whole) > 40);
  CHECK(!fs::exists(checkpoint));
  CHECK(!partial_left(tmp.path / "out"));
}

TEST_CASE("--resume refuses another scene's checkpoint, and without one runs from the start") {
  TempDir tmp;
  std::ofstream(tmp.path / "s.json") << scene();
  const fs::path checkpoint = tmp.path / "out" / "resume.checkpoint";
  std::string log;
  REQUIRE(run(tmp.path, {"run", "--resume", "s.json"}, &log) == 0);
  CHECK(log.find("no checkpoint") != std::string::npos);

  const pid_t pid = spawn(tmp.path, {"run", "s.json", "-q", "--checkpoint-every", "0"}, 2);
  REQUIRE(wait_for_file(checkpoint));
  ::kill(pid, SIGTERM);
  CHECK(wait_for(pid) == 143);
  const std::string kept = read(tmp.path / "out" / "resume" / "summary.json");
  std::ofstream(tmp.path / "other.json") << scene("2e-12");  // another k, the same output folder
  CHECK(run(tmp.path, {"run", "--resume", "other.json"}, &log) == 2);
  CHECK(log.find("belongs to another scene") != std::string::npos);
  CHECK(read(tmp.path / "out" / "resume" / "summary.json") == kept);  // nothing written
  CHECK(fs::exists(checkpoint));
  // A file that is not a checkpoint is refused too.
  std::ofstream(checkpoint, std::ios::trunc) << "not a checkpoint";
  CHECK(run(tmp.path, {"run", "--resume", "s.json"}, &log) == 2);
  CHECK(log.find("not a fretwear checkpoint") != std::string::npos);
}
