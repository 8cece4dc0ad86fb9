// gnuplot as the program runs it (engine/plot.hpp, run_gnuplot): started without a shell, so that no name of a
// folder is ever read as a command; in a process group of its own, so that a signal sent to the program's group (a
// terminal's Ctrl-C, `timeout -s INT`) reaches the program alone; and a signal that arrives while the results are
// being written, plots included, waits for them (docs/SCENES.md, "Output folders" and "Long runs"): the results are
// put in place whole, then the program ends with 128 + the signal's number. Without gnuplot on PATH a run completes
// with no plots. FRETWEAR_PLOT_PAUSE_MS (tests only) pauses before each gnuplot starts, so that a signal lands while
// the results are being drawn; a gnuplot of the test's own, first on PATH, takes half a second before it draws, so
// that a signal finds gnuplot itself running.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>
#include <unistd.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// Waits (at most `seconds`) until `ready` holds; false when it never did.
bool wait_until(const std::function<bool()>& ready, double seconds = 30.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!ready()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// Entries under `dir` named exactly `name`.
std::vector<std::string> named(const fs::path& dir, const std::string& name) {
  std::vector<std::string> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->path().filename() == name) found.push_back(it->path().lexically_relative(dir).string());
  return found;
}

// True once a staging folder (`<name>.partial-<pid>`) is among the entries of `dir`: the results are being written.
bool staging_in(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename().string().find(".partial-") != std::string::npos) return true;
  return false;
}

// The cycle scene of this tier with its results in `dir`: pressure, traction, slip (and the loop) drawn.
std::string plotted_scene(const std::string& dir, double P = 1e5) {
  json scene = cycle_scene();
  scene["load"]["P"] = P;
  scene["output"] = {{"dir", dir}};
  return scene.dump();
}

// A gnuplot for PATH that appends its process id to `started`, takes half a second, then becomes the real one
// (`gnuplot`, an absolute path): a window in which a signal finds gnuplot itself running.
struct SlowGnuplot {
  fs::path bin, started;
  SlowGnuplot(const fs::path& root, const fs::path& gnuplot) : bin(root / "bin"), started(root / "gnuplot-started") {
    write_file(bin / "gnuplot", "#!/bin/sh\necho \"$$\" >> '" + started.string() + "'\nsleep 0.5\nexec '" +
                                    gnuplot.string() + "' \"$@\"\n");
    fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  }
  // The environment that puts it first on PATH.
  Env env() const {
    const char* path = std::getenv("PATH");
    return {{"PATH", bin.string() + ":" + (path ? path : "")}};
  }
  // The process ids of the gnuplots started so far.
  std::vector<pid_t> pids() const {
    std::vector<pid_t> found;
    std::stringstream lines(read_file(started));
    for (pid_t pid; lines >> pid;) found.push_back(pid);
    return found;
  }
  // True once every gnuplot started has ended (a process gone, or a zombie whose parent is gone).
  bool all_ended() const {
    for (const pid_t pid : pids()) {
      const std::string stat = read_file(fs::path("/proc") / std::to_string(pid) / "stat");
      const auto close = stat.rfind(')');
      if (close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z') return false;
    }
    return true;
  }
};

// Holds a completed run's folder to its summary: "completed", every plot the summary lists is in the folder and the
// first stage's are among them, and gnuplot said nothing (no gnuplot.log).
void check_plotted(const fs::path& dir) {
  INFO("results in " << dir.string());
  REQUIRE(fs::exists(dir / "summary.json"));
  const json summary = json::parse(read_file(dir / "summary.json"));
  CHECK(summary["status"] == "completed");
  REQUIRE(summary["plots"].is_array());
  CHECK_MESSAGE(!summary["plots"].empty(), "no plots listed");
  for (const auto& plot : summary["plots"]) CHECK_MESSAGE(fs::exists(dir / plot.get<std::string>()), plot);
  std::set<std::string> listed;
  for (const auto& plot : summary["plots"]) listed.insert(plot.get<std::string>());
  for (const char* want : {"pressure.png", "traction.png", "slip.png"})
    CHECK_MESSAGE(listed.count(want) == 1, want << " is not among the plots");
  CHECK_FALSE(fs::exists(dir / "gnuplot.log"));
}

// A signal sent to the program's whole process group (as a terminal's Ctrl-C, or `timeout -s`, sends it) once
// the results are being written, plots paused before each gnuplot: the results replace the earlier ones whole and
// the program then ends with 128 + the signal's number, saying so.
void signal_while_drawing(int sig) {
  const fs::path gnuplot = on_path("gnuplot");
  if (gnuplot.empty()) {
    MESSAGE("gnuplot is not on PATH: nothing is drawn, so there is nothing to interrupt");
    return;
  }
  Scratch s;
  s.write("c.json", plotted_scene("output/c", 1e5));
  REQUIRE(s.fretwear({"run", "c.json", "-q"}).exited(kDone));
  s.write("c.json", plotted_scene("output/c", 2e5));
  const Snapshot before = s.snapshot();
  Child child = s.start({"run", "c.json", "-q"}, {{"FRETWEAR_PLOT_PAUSE_MS", "500"}});
  REQUIRE_MESSAGE(wait_until([&] { return staging_in(s.work / "output") || !child.running(); }),
                  "the results were never written");
  REQUIRE_MESSAGE(child.running(), "the run ended before the signal: " << child.wait().describe());
  ::kill(-child.pid(), sig);  // the group: the program and any child left in it
  const Outcome r = child.wait();
  CHECK_MESSAGE(r.exited(128 + sig), "want exit " << 128 + sig << ", got " << r.describe());
  CHECK_MESSAGE(r.err.find("stopped by signal " + std::to_string(sig) + " after the results were written") !=
                    std::string::npos,
                r.describe());
  CHECK_MESSAGE(r.err.find("gnuplot failed") == std::string::npos, r.describe());
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
  CHECK_MESSAGE(named(s.root, "gnuplot.log").empty(), "gnuplot.log in " << join(named(s.root, "gnuplot.log")));
  // The results of this run, whole: the earlier run's are replaced, not mixed with these.
  const fs::path dir = s.work / "output" / "c";
  check_plotted(dir);
  CHECK(json::parse(read_file(dir / "scene.resolved.json"))["load"]["P"] == 2e5);
  const std::vector<std::string> outside = changes(before, after, {"home/work/output"});
  CHECK_MESSAGE(outside.empty(), "written outside output/: " << join(outside));
}

}  // namespace

// output.dir reaches gnuplot as a folder, never as text for a shell: quoted into a shell command, an apostrophe in
// it would end the quotes, the rest of the name would run as commands, and a folder named like "bob's runs" would
// get no plots.
TEST_CASE("an output.dir with an apostrophe or shell syntax in its name: no command runs, and every plot is drawn") {
  const fs::path gnuplot = on_path("gnuplot");
  for (const std::string dir :
       {"out'; touch INJECTED; echo '", "bob's runs", "-x \"q\" $(touch INJECTED) `touch INJECTED`"}) {
    CAPTURE(dir);
    Scratch s;
    s.write("c.json", plotted_scene(dir));
    const Snapshot before = s.snapshot();
    const Outcome r = s.fretwear({"run", "c.json", "-q"});
    CHECK_MESSAGE(r.exited(kDone), r.describe());
    CHECK_MESSAGE(named(s.root, "INJECTED").empty(), "a command ran: " << join(named(s.root, "INJECTED")));
    CHECK_MESSAGE(named(s.root, "gnuplot.log").empty(), "gnuplot.log in " << join(named(s.root, "gnuplot.log")));
    const Snapshot after = s.snapshot();
    CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
    CHECK_MESSAGE(changes(before, after, {"home/work/" + dir}).empty(),
                  "written outside output.dir: " << join(changes(before, after, {"home/work/" + dir})));
    if (gnuplot.empty())
      MESSAGE("gnuplot is not on PATH: the plots are not checked");
    else
      check_plotted(s.work / dir);
  }
}

TEST_CASE("SIGINT to the program's process group while its plots are drawn: the results whole, then exit 130") {
  signal_while_drawing(SIGINT);
}

TEST_CASE("SIGTERM to the program's process group while its plots are drawn: the results whole, then exit 143") {
  signal_while_drawing(SIGTERM);
}

// The signal lands while gnuplot itself runs: gnuplot, in a group of its own, is not ended by it and draws every plot.
TEST_CASE("Ctrl-C to the program's process group while gnuplot runs does not end gnuplot") {
  const fs::path gnuplot = on_path("gnuplot");
  if (gnuplot.empty()) {
    MESSAGE("gnuplot is not on PATH: nothing is drawn, so there is nothing to interrupt");
    return;
  }
  Scratch s;
  const SlowGnuplot slow(s.root, gnuplot);
  s.write("c.json", plotted_scene("output/c"));
  const Snapshot before = s.snapshot();
  Child child = s.start({"run", "c.json", "-q"}, slow.env());
  REQUIRE_MESSAGE(wait_until([&] { return !slow.pids().empty() || !child.running(); }), "gnuplot never started");
  REQUIRE_MESSAGE(child.running(), "the run ended before the signal: " << child.wait().describe());
  ::kill(-child.pid(), SIGINT);
  const Outcome r = child.wait();
  CHECK_MESSAGE(r.exited(kInterrupted), "want exit 130, got " << r.describe());
  CHECK_MESSAGE(r.err.find("gnuplot failed") == std::string::npos, r.describe());
  check_plotted(s.work / "output" / "c");
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
}

// A sweep has no stop of its own: a signal ends it at once, as a kill does (docs/SCENES.md, "Resuming"), so that it
// starts no further run, whichever part of a run it finds running (here gnuplot, drawing the second run's plots);
// --resume then finishes it.
TEST_CASE("SIGINT to a sweep's process group while gnuplot runs: no further run, and --resume finishes the sweep") {
  const fs::path gnuplot = on_path("gnuplot");
  if (gnuplot.empty()) {
    MESSAGE("gnuplot is not on PATH: nothing is drawn, so there is nothing to interrupt");
    return;
  }
  Scratch s;
  const SlowGnuplot slow(s.root, gnuplot);
  json scene = cycle_scene();
  scene["output"] = {{"dir", "output/sw"}};
  s.write("sw.json", scene.dump());
  const std::vector<std::string> args = {"sweep", "sw.json", "--jobs", "1", "--vary", "load.Q.ratio=0.2,0.4,0.6,0.8"};
  Child child = s.start(args, slow.env());
  const fs::path root = s.work / "output" / "sw";
  // The first run is complete in the sweep's staging folder, and the second one's results are being written.
  auto second_run_writing = [&] {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(root, ec))
      if (e.path().filename().string().find("sweep.partial-") == 0) {
        int complete = 0;
        bool staging = false;
        for (const auto& run : fs::directory_iterator(e.path() / "runs", ec)) {
          const bool partial = run.path().filename().string().find(".partial-") != std::string::npos;
          staging = staging || partial;
          complete += !partial;
        }
        return staging && complete == 1;
      }
    return false;
  };
  REQUIRE_MESSAGE(wait_until([&] { return second_run_writing() || !child.running(); }, 60.0),
                  "the second run never wrote");
  const std::size_t drawn = slow.pids().size();
  REQUIRE_MESSAGE(wait_until([&] { return slow.pids().size() > drawn || !child.running(); }),
                  "gnuplot never started for the second run");
  REQUIRE_MESSAGE(child.running(), "the sweep ended before the signal: " << child.wait().describe());
  ::kill(-child.pid(), SIGINT);
  const Outcome r = child.wait();
  CHECK_MESSAGE((r.exited(kInterrupted) || (r.signal == SIGINT && !r.timed_out)),
                "want exit 130 or death by SIGINT, got " << r.describe());
  CHECK_MESSAGE(r.err.find("[3/4]") == std::string::npos, "the sweep ran on: " << r.describe());
  CHECK_FALSE(fs::exists(root / "sweep"));
  // gnuplot, left running, finishes its plot into the stopped sweep's staging folder before --resume takes it over.
  REQUIRE_MESSAGE(wait_until([&] { return slow.all_ended(); }), "gnuplot still runs");

  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  const Outcome resumed = s.fretwear(resume);
  CHECK_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK_MESSAGE(resumed.err.find("1 kept from the sweep that was stopped") != std::string::npos, resumed.describe());
  for (const auto& e : fs::directory_iterator(root / "sweep" / "runs")) check_plotted(e.path());
  CHECK(fs::exists(root / "sweep" / "sweep_map.png"));
  CHECK_MESSAGE(fretwear::test::leftovers(s.work).empty(), "left behind: " << join(fretwear::test::leftovers(s.work)));
}

// Without gnuplot (PATH holds an empty folder and the program's own): the scripts are written, nothing is drawn,
// stderr says why, and the run and a sweep complete all the same.
TEST_CASE("a script's failure stays in gnuplot.log when later scripts run clean") {
  // A gnuplot of the test's own: pressure.gp, the first script a run draws, fails with a message; the others succeed
  // and print nothing. The log keeps the failure.
  Scratch s;
  const fs::path bin = s.root / "bin";
  write_file(bin / "gnuplot", "#!/bin/sh\nif [ \"$1\" = pressure.gp ]; then echo 'the first script failed' >&2; "
                              "exit 1; fi\nexit 0\n");
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  const char* path = std::getenv("PATH");
  s.write("c.json", plotted_scene("output/c"));
  const Outcome r = s.fretwear({"run", "c.json", "-q"}, {{"PATH", bin.string() + ":" + (path ? path : "")}});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  CHECK_MESSAGE(r.err.find("gnuplot failed on pressure.gp; see gnuplot.log") != std::string::npos, r.describe());
  const fs::path log = s.work / "output" / "c" / "gnuplot.log";
  REQUIRE(fs::exists(log));
  CHECK(read_file(log).find("the first script failed") != std::string::npos);
}

TEST_CASE("without gnuplot on PATH a run completes with no plots and says gnuplot was not found") {
  Scratch s;
  const fs::path empty = s.root / "empty";
  fs::create_directories(empty);
  const Env no_gnuplot = {{"PATH", empty.string() + ":" + fs::path(FRETWEAR_EXE).parent_path().string()}};
  s.write("c.json", plotted_scene("output/c"));
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear({"run", "c.json", "-q"}, no_gnuplot);
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  CHECK_MESSAGE(r.err.find("fretwear: gnuplot not found; plots skipped") != std::string::npos, r.describe());
  // Said once, however many plot scripts the run has (the normal contact's and the cycle's here).
  CHECK_MESSAGE(r.err.find("gnuplot not found") == r.err.rfind("gnuplot not found"), r.describe());
  const fs::path dir = s.work / "output" / "c";
  REQUIRE(fs::exists(dir / "summary.json"));
  const json summary = json::parse(read_file(dir / "summary.json"));
  CHECK(summary["status"] == "completed");
  CHECK(summary["plots"] == json::array());
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string ext = e.path().extension().string();
    CHECK_MESSAGE((ext != ".png" && ext != ".svg"), e.path().filename().string() << " drawn");
  }
  for (const char* kept : {"pressure.gp", "cycle.gp", "index.html", "contact.csv", "cycle.csv", "scene.resolved.json"})
    CHECK_MESSAGE(fs::exists(dir / kept), kept);
  CHECK_FALSE(fs::exists(dir / "gnuplot.log"));
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));

  json scene = cycle_scene();
  scene["output"] = {{"dir", "output/sw"}};
  s.write("sw.json", scene.dump());
  const Outcome sweep = s.fretwear({"sweep", "sw.json", "-q", "--vary", "load.Q.ratio=0.2,0.4"}, no_gnuplot);
  CHECK_MESSAGE(sweep.exited(kDone), sweep.describe());
  CHECK(fs::exists(s.work / "output" / "sw" / "sweep" / "sweep.csv"));
  CHECK(fs::exists(s.work / "output" / "sw" / "sweep" / "sweep.gp"));
  CHECK_FALSE(fs::exists(s.work / "output" / "sw" / "sweep" / "sweep_map.png"));
  CHECK(named(s.root, "gnuplot.log").empty());
}
