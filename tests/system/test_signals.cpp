// Ctrl-C during a wear run (main.cpp: 130 a wear run stopped by SIGINT, what was recorded written, a checkpoint
// kept). A second Ctrl-C ends the program at once (docs/SCENES.md, "Long runs"), unless the two arrive together
// (then they are one) or the second while a checkpoint or the results are put in place (it waits for that): exit 130
// or death by SIGINT, and in either case no temporary file, and `run --resume` then completes. FRETWEAR_STEP_PAUSE_MS slows each wear step so that the
// signals land part way through the run.
#include <chrono>
#include <csignal>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// The pause at each wear step boundary (ms), and when the signals are sent (ms after the start): the wear scene
// takes about twenty steps, so the run lasts seconds and the signals find it between its first steps.
const std::vector<std::pair<std::string, std::string>> kPause = {{"FRETWEAR_STEP_PAUSE_MS", "200"}};
constexpr auto kMidRun = std::chrono::milliseconds(700);

void interrupt(int times) {
  const bool first_only = times == 1;
  INFO("SIGINT sent " << times << " time(s)");
  Scratch s;
  s.write("w.json", wear_scene().dump());
  const Snapshot before = s.snapshot();
  Child child = s.start({"run", "w.json", "-q"}, kPause);
  std::this_thread::sleep_for(kMidRun);
  REQUIRE_MESSAGE(child.running(), "the run ended before the signal: " << child.wait().describe());
  for (int i = 0; i < times; ++i) {
    child.signal(SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const Outcome r = child.wait();
  if (first_only)
    CHECK_MESSAGE(r.exited(kInterrupted), "want exit 130, got " << r.describe());
  else
    CHECK_MESSAGE((r.exited(kInterrupted) || (r.signal == SIGINT && !r.timed_out)),
                  "want exit 130 or death by SIGINT, got " << r.describe());
  const Snapshot stopped = s.snapshot();
  CHECK_MESSAGE(leftovers(before, stopped).empty(), "left behind: " << join(leftovers(before, stopped)));

  const Outcome resumed = s.fretwear({"run", "--resume", "w.json", "-q"});
  CHECK_MESSAGE(resumed.exited(kDone), "run --resume: " << resumed.describe());
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(after.count("home/work/output/h/summary.json") == 1, "no summary after --resume");
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
  std::vector<std::string> touched;
  for (const auto& line : changes(before, after))
    if (line.rfind("new ", 0) != 0) touched.push_back(line);
  CHECK_MESSAGE(touched.empty(), "the user's files were touched: " << join(touched));
}

}  // namespace

TEST_CASE("SIGINT once during a wear run: exit 130, and run --resume completes") { interrupt(1); }

TEST_CASE("SIGINT twice in quick succession: no temporary file, and run --resume completes") {
  interrupt(2);
}
