// A second Ctrl-C while a checkpoint was being written left <name>.checkpoint.tmp-PID that nothing removed, and a
// run interrupted before its first record printed a gnuplot error about a folder that no longer existed. Signals now
// wait while a checkpoint or the results are put in place, and a run with no record past cycle 0 plots nothing
// against cycles. The hooks FRETWEAR_STEP_PAUSE_MS and FRETWEAR_CHECKPOINT_PAUSE_MS hold the run at a step boundary
// and inside the checkpoint write, so that the signals land there every time.
#include <chrono>
#include <thread>

#include <doctest/doctest.h>

#include "program.hpp"

using namespace fretwear::test;

namespace {

const char* kWear = R"({"name": "w", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
  "grid": {"cells": 256}, "effects": {"wear": {"k": 1e-12, "cycles": 1e6, "record": 8}}})";

// Waits until a file whose name holds `mark` appears under dir (at most 20 s).
bool appears(const fs::path& dir, const std::string& mark) {
  for (int i = 0; i < 4000; ++i) {
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.path().filename().string().find(mark) != std::string::npos) return true;
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
  REQUIRE(appears(scratch.path, ".tmp-"));  // inside write_checkpoint, the temporary file written
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
