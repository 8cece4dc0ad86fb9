// A second Ctrl-C while a checkpoint was being written left <name>.checkpoint.tmp-PID that nothing removed, and a
// run interrupted before its first record printed a gnuplot error about a folder that no longer existed. Signals now
// wait while a checkpoint or the results are put in place, and a run with no record past cycle 0 plots nothing
// against cycles. The hooks FRETWEAR_STEP_PAUSE_MS and FRETWEAR_CHECKPOINT_PAUSE_MS hold the run at a step boundary
// and inside the checkpoint write, so that the signals land there every time.
#include <chrono>
#include <csignal>
#include <string>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <doctest/doctest.h>

#include "program.hpp"

using namespace fretwear::test;

namespace {

const char* kWear = R"({"name": "w", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
  "grid": {"cells": 256}, "effects": {"wear": {"k": 1e-12, "cycles": 1e6, "record": 8}}})";

// Waits (at most 20 s) until the process is inside write_checkpoint, its bytes written: it holds open a file in the
// output folder that has no name yet (O_TMPFILE: /proc shows it as "#inode (deleted)") or, where the file system
// has no O_TMPFILE, the temporary file <name>.checkpoint.tmp-PID.
bool writing_checkpoint(pid_t pid, const fs::path& dir) {
  const std::string output = fs::canonical(dir).string() + "/output/";
  for (int i = 0; i < 4000; ++i) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(fs::path("/proc") / std::to_string(pid) / "fd", ec)) {
      const std::string target = fs::read_symlink(e.path(), ec).string();
      if (target.rfind(output, 0) == 0 &&
          (target.find("(deleted)") != std::string::npos || target.find(".tmp-") != std::string::npos))
        return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace

TEST_CASE("two Ctrl-C while a checkpoint is written leave no temporary file, and --resume completes the run") {
  Scratch scratch{"sigckpt"};
  write_file(scratch.path / "w.json", kWear);
  Running run(scratch.path, {"run", "-q", "--checkpoint-every", "0", "w.json"},
              {{"FRETWEAR_CHECKPOINT_PAUSE_MS", "300"}, {"FRETWEAR_STEP_PAUSE_MS", "20"}});
  REQUIRE(writing_checkpoint(run.pid(), scratch.path));
  run.signal(SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // handled apart, not merged into one
  run.signal(SIGINT);
  const Outcome o = run.wait();
  CAPTURE(o.all());
  // The first signal asks for a stop; the second, held while the file was put in place, ends the program after it.
  CHECK((o.status == 130 || o.signal == SIGINT));
  CHECK(leftovers(scratch.path).empty());
  CHECK(fs::exists(scratch.path / "output" / "w.checkpoint"));
  const Outcome resumed = run_program(scratch.path, {"run", "-q", "--resume", "w.json"});
  CAPTURE(resumed.all());
  CHECK(resumed.status == 0);
  CHECK(fs::exists(scratch.path / "output" / "w" / "summary.json"));
  CHECK(leftovers(scratch.path).empty());
}

TEST_CASE("a run killed while a checkpoint is written leaves no temporary file, and --resume completes the run") {
  // SIGKILL cannot be held back: the checkpoint's bytes go into a file with no name until they are synced, so the
  // kill leaves nothing but the previous checkpoint, from which the run resumes.
  Scratch scratch{"killckpt"};
  write_file(scratch.path / "w.json", kWear);
  Running run(scratch.path, {"run", "-q", "--checkpoint-every", "0", "w.json"},
              {{"FRETWEAR_CHECKPOINT_PAUSE_MS", "300"}, {"FRETWEAR_STEP_PAUSE_MS", "20"}});
  for (int i = 0; i < 4000 && !fs::exists(scratch.path / "output" / "w.checkpoint"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  REQUIRE(writing_checkpoint(run.pid(), scratch.path));  // the next one, after the first is in place
  run.signal(SIGKILL);
  const Outcome o = run.wait();
  CHECK(o.signal == SIGKILL);
  // Only a file system with O_TMPFILE (ext4, xfs, btrfs, tmpfs) can give this; elsewhere the temporary file is named
  // while it is written, and a SIGKILL then leaves it.
  const int probe = ::open(scratch.path.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  if (probe >= 0) {
    ::close(probe);
    for (const auto& e : fs::recursive_directory_iterator(scratch.path))
      CHECK_MESSAGE(e.path().filename().string().find(".tmp-") == std::string::npos, e.path().string());
  } else {
    MESSAGE("this file system has no O_TMPFILE: a SIGKILL during a checkpoint write may leave its temporary file");
  }
  REQUIRE(fs::exists(scratch.path / "output" / "w.checkpoint"));
  const Outcome resumed = run_program(scratch.path, {"run", "-q", "--resume", "w.json"});
  CAPTURE(resumed.all());
  CHECK(resumed.status == 0);
  CHECK(resumed.err.find("no checkpoint") == std::string::npos);
  CHECK(fs::exists(scratch.path / "output" / "w" / "summary.json"));
}

TEST_CASE("a run interrupted before its first record: exit 130, no gnuplot error, no stray file") {
  Scratch scratch{"sigfirst"};
  write_file(scratch.path / "w.json", kWear);
  Running run(scratch.path, {"run", "w.json"}, {{"FRETWEAR_STEP_PAUSE_MS", "2000"}});
  // The first step boundary comes after the first cycle (cycle 0 recorded); stop there.
  for (int i = 0; i < 4000 && run.err_so_far().find("normal contact on") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  run.signal(SIGINT);
  const Outcome o = run.wait();
  CAPTURE(o.all());
  CHECK(o.status == 130);
  CHECK(o.err.find("gnuplot") == std::string::npos);
  CHECK(fs::exists(scratch.path / "output" / "w" / "summary.json"));
  CHECK(leftovers(scratch.path).empty());
}
