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

// The load cycle marched in increments stops at its next increment: dissimilar bodies (steel on aluminium, the
// coupled march) at 20 000 increments a cycle, 45 000 in all, some ten seconds, stopped one second in, within two
// seconds, its progress shown as it marched, `said` on stderr, nothing written.
namespace {

void interrupt_the_march(json scene, const std::string& said) {
  Scratch s;
  scene["effects"]["tangential"]["increments"] = 20000;
  scene["output"] = {{"dir", "out"}, {"plots", false}};
  s.write("d.json", scene.dump());
  const Snapshot before = s.snapshot();
  Child child = s.start({"run", "d.json"}, {{"FRETWEAR_STAGE_QUIET_S", "0"}});
  std::this_thread::sleep_for(std::chrono::seconds(1));
  REQUIRE_MESSAGE(child.running(), "the run ended before the signal: " << child.wait().describe());
  const auto sent = std::chrono::steady_clock::now();
  child.signal(SIGINT);
  const Outcome r = child.wait();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  CHECK_MESSAGE(r.exited(kInterrupted), "want exit 130, got " << r.describe());
  CHECK_MESSAGE(seconds < 2.0, "stopped " << seconds << " s after the signal");
  CHECK_MESSAGE(r.err.find(" / 45000 increments, ") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find(said) != std::string::npos, r.err);
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "changed: " << join(changes(before, s.snapshot())));
}

json dissimilar_cycle() {
  return json::parse(read_file(fs::path(FRETWEAR_SOURCE_DIR) / "examples" / "dissimilar_cycle.json"));
}

}  // namespace

TEST_CASE("SIGINT while the load cycle is marched: exit 130 within an increment, nothing written") {
  interrupt_the_march(dissimilar_cycle(), "stopped in the tangential stage by signal 2; nothing written");
}

// A wear run's checks before solving march its first cycle (which the run then takes): a signal there stops them
// alike, and no checkpoint is begun.
TEST_CASE("SIGINT in the checks before a wear run marches its first cycle: exit 130, nothing written") {
  json scene = dissimilar_cycle();
  scene["effects"]["wear"] = {{"law", "archard"}, {"k", 1e-12}, {"cycles", 1e5}};
  interrupt_the_march(scene,
                      "stopped in the tangential stage (the checks before solving) by signal 2; nothing written");
}

// A stop outside the wear stage's step boundaries: in the stages after it (stress, crack, life) the run ends at
// their next part with exit 130 and nothing written, and the results already in output.dir stay as they were; the
// wear's checkpoint is kept, and `run --resume` gives the uninterrupted results. FRETWEAR_STOP_IN_STAGE=<stage>
// raises SIGINT where that stage first asks (main.cpp).
TEST_CASE("SIGINT in the stages after the wear: exit 130, nothing written, the earlier results kept") {
  Scratch s;
  json scene = wear_scene();
  scene["effects"]["stress"] = {{"nx", 41}, {"ny", 20}};
  scene["effects"]["crack"] = {{"lengths", {1e-5, 2e-5}}};
  scene["effects"]["life"] = json::parse(R"({"initiation": {"sigma_f": 1.817e9, "b": -0.08, "eps_f": 0.35, "c": -0.52,
      "critical_distance": 2e-5}, "growth": {"C": 5e-30, "m": 3.0, "dK_th": 2e6, "a_final": 1e-3}})");
  s.write("w.json", scene.dump());
  const Outcome first = s.fretwear({"run", "w.json", "-q"});
  REQUIRE_MESSAGE(first.exited(kDone), first.describe());
  Snapshot done = s.snapshot();
  for (const char* stage : {"stress", "crack", "life"}) {
    CAPTURE(stage);
    const Outcome r = s.fretwear({"run", "w.json"}, {{"FRETWEAR_STOP_IN_STAGE", stage}});
    CHECK_MESSAGE(r.exited(kInterrupted), "want exit 130, got " << r.describe());
    CHECK(r.err.find(std::string("stopped in the ") + stage + " stage by signal 2; nothing written") !=
          std::string::npos);
    const Snapshot stopped = s.snapshot();
    // Only the wear's checkpoint beside the results may be new; nothing else differs.
    std::vector<std::string> differ;
    for (const auto& line : changes(done, stopped))
      if (line.find(".checkpoint") == std::string::npos) differ.push_back(line);
    CHECK_MESSAGE(differ.empty(), "changed: " << join(differ));
    const Outcome resumed = s.fretwear({"run", "--resume", "w.json", "-q"});
    CHECK_MESSAGE(resumed.exited(kDone), resumed.describe());
    done = s.snapshot();
    CHECK(done.count("home/work/output/h/summary.json") == 1);
  }
}
