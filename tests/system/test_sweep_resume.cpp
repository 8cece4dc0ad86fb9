// `fretwear sweep --resume` (docs/SCENES.md, "Sweeps"): a sweep killed part way (SIGKILL, as by a crash or a
// scheduler, at a chosen run through FRETWEAR_SWEEP_KILL_AFTER_RUNS) is finished by the same command with --resume;
// the runs that were complete are kept (not run again), the others run, and the table equals that of a sweep that
// was never stopped.
#include <algorithm>
#include <csignal>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <sys/stat.h>

#include "system/program.hpp"
#include "system/sweep_support.hpp"

using namespace fretwear::system_test;

namespace {

// A file's identity and age: a run that was kept keeps its summary.json (moved, never written again).
std::string identity(const fs::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return "missing";
  return std::to_string(st.st_ino) + "@" + std::to_string(st.st_mtim.tv_sec) + "." +
         std::to_string(st.st_mtim.tv_nsec);
}

std::vector<std::string> args(const std::string& scene, std::vector<std::string> extra) {
  std::vector<std::string> a{"sweep", scene};
  a.insert(a.end(), kSweepVary.begin(), kSweepVary.end());
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

}  // namespace

TEST_CASE("a sweep killed after 5 of 12 runs is finished by --resume: complete runs kept, the table as if never "
          "stopped") {
  Scratch s;
  s.write("whole.json", sweep_scene(s.work / "whole").dump());
  s.write("killed.json", sweep_scene(s.work / "killed").dump());
  const Outcome whole = s.fretwear(args("whole.json", {"--jobs", "2", "-q"}));
  REQUIRE_MESSAGE(whole.exited(kDone), whole.describe());

  // Two threads: when the fifth run finishes, the other is part way through one, whose folder is left partial.
  const Outcome killed =
      s.fretwear(args("killed.json", {"--jobs", "2", "-q"}), {{"FRETWEAR_SWEEP_KILL_AFTER_RUNS", "5"}});
  REQUIRE_MESSAGE(killed.signal == SIGKILL, killed.describe());
  CHECK_FALSE(fs::exists(s.work / "killed" / "sweep"));
  std::map<std::string, std::string> complete;  // run name → its summary.json's identity
  for (const auto& staging : fs::directory_iterator(s.work / "killed"))
    if (staging.path().filename().string().rfind("sweep.partial-", 0) == 0)
      for (const auto& run : fs::directory_iterator(staging.path() / "runs"))
        // A run under its own name is complete (staged and committed whole); a run's staging folder,
        // <name>.partial-<pid>, may already hold its summary when the kill comes, and is not.
        if (run.path().filename().string().find(".partial-") == std::string::npos &&
            fs::exists(run.path() / "summary.json"))
          complete[run.path().filename().string()] = identity(run.path() / "summary.json");
  REQUIRE(complete.size() >= 5);
  REQUIRE(complete.size() < 12);

  const Outcome resumed = s.fretwear(args("killed.json", {"--jobs", "2", "--resume"}));
  REQUIRE_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK_MESSAGE(resumed.err.find(std::to_string(complete.size()) + " kept from the sweep that was stopped") !=
                    std::string::npos,
                resumed.err);
  for (const auto& [name, before] : complete) {
    CAPTURE(name);
    CHECK(identity(s.work / "killed" / "sweep" / "runs" / name / "summary.json") == before);
    CHECK(resumed.err.find(name + ": done") == std::string::npos);  // not run again
  }
  CHECK(csv_rows(s.work / "killed" / "sweep" / "sweep.csv", "timings.total_s") ==
        csv_rows(s.work / "whole" / "sweep" / "sweep.csv", "timings.total_s"));
  // Nothing of the killed sweep is left: one folder, the sweep's, whose runs are all complete.
  std::vector<std::string> entries;
  for (const auto& e : fs::directory_iterator(s.work / "killed")) entries.push_back(e.path().filename().string());
  CHECK_MESSAGE(entries.size() == 2, join(entries));  // sweep/ and the marker
  int runs = 0;
  for (const auto& run : fs::directory_iterator(s.work / "killed" / "sweep" / "runs")) {
    CHECK_MESSAGE(fs::exists(run.path() / "summary.json"), run.path().string());
    ++runs;
  }
  CHECK(runs == 12);
}

TEST_CASE("--resume keeps the complete runs of a sweep killed while a run's folder was being made, before its marker") {
  // The run's staging folder exists, empty and unmarked, for an instant (OutputFolder::stage()): a kill then (under
  // mpirun under load it happened) must not make the whole stopped sweep look like the user's. Made here by hand,
  // named for a process that cannot exist (a pid above Linux's largest, 2^22).
  Scratch s;
  s.write("s.json", sweep_scene(s.work / "out").dump());
  const Outcome killed = s.fretwear(args("s.json", {"--jobs", "1", "-q"}), {{"FRETWEAR_SWEEP_KILL_AFTER_RUNS", "3"}});
  REQUIRE_MESSAGE(killed.signal == SIGKILL, killed.describe());
  std::vector<fs::path> staging;
  for (const auto& e : fs::directory_iterator(s.work / "out"))
    if (e.path().filename().string().rfind("sweep.partial-", 0) == 0) staging.push_back(e.path());
  REQUIRE(staging.size() == 1);
  fs::create_directory(staging.front() / "runs" / "sw__load.Q.ratio_1.2__load.P_400000.0.partial-4999999");
  const Outcome resumed = s.fretwear(args("s.json", {"--jobs", "2", "--resume"}));
  REQUIRE_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK_MESSAGE(resumed.err.find("3 kept from the sweep that was stopped") != std::string::npos, resumed.err);
  // A folder named so that holds anything is not taken for a staging folder: the stopped sweep is left alone.
  Scratch t;
  t.write("s.json", sweep_scene(t.work / "out").dump());
  REQUIRE(t.fretwear(args("s.json", {"--jobs", "1", "-q"}), {{"FRETWEAR_SWEEP_KILL_AFTER_RUNS", "3"}}).signal ==
          SIGKILL);
  fs::path stopped;
  for (const auto& e : fs::directory_iterator(t.work / "out"))
    if (e.path().filename().string().rfind("sweep.partial-", 0) == 0) stopped = e.path();
  REQUIRE(!stopped.empty());
  write_file(stopped / "runs" / "x.partial-4999999" / "notes.txt", "the user's\n");
  const Outcome again = t.fretwear(args("s.json", {"--jobs", "2", "--resume"}));
  REQUIRE_MESSAGE(again.exited(kDone), again.describe());
  CHECK_MESSAGE(again.err.find("0 kept") != std::string::npos, again.err);
  // It says why: the stopped sweep's folder, the user's file in it, and what to do.
  CHECK_MESSAGE(again.err.find(stopped.string() + "\" is a stopped sweep's folder but holds what fretwear did not "
                               "write (runs/x.partial-4999999/)") != std::string::npos,
                again.err);
  CHECK_MESSAGE(again.err.find("move that out of it to resume from it") != std::string::npos, again.err);
  CHECK_MESSAGE(again.err.find("no complete run of the same resolved scene") == std::string::npos, again.err);
  CHECK(read_file(stopped / "runs" / "x.partial-4999999" / "notes.txt") == "the user's\n");
}

TEST_CASE("--resume keeps no run of another scene, and with nothing to resume runs every run") {
  Scratch s;
  json scene = sweep_scene(s.work / "out");
  s.write("s.json", scene.dump());
  const Outcome killed = s.fretwear(args("s.json", {"--jobs", "1", "-q"}), {{"FRETWEAR_SWEEP_KILL_AFTER_RUNS", "3"}});
  REQUIRE_MESSAGE(killed.signal == SIGKILL, killed.describe());
  scene["friction"] = 0.6;  // the same run names, other results
  s.write("s.json", scene.dump());
  const Outcome resumed = s.fretwear(args("s.json", {"--jobs", "2", "--resume"}));
  REQUIRE_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK_MESSAGE(resumed.err.find("0 kept") != std::string::npos, resumed.err);

  Scratch fresh;
  fresh.write("s.json", sweep_scene(fresh.work / "out").dump());
  const Outcome first = fresh.fretwear(args("s.json", {"--jobs", "2", "--resume"}));
  REQUIRE_MESSAGE(first.exited(kDone), first.describe());
  CHECK(first.err.find("0 kept") != std::string::npos);
  CHECK(fs::exists(fresh.work / "out" / "sweep" / "sweep.csv"));
}

TEST_CASE("--resume keeps the runs of the last finished sweep, saying so, and no run whose scene has lost a key") {
  // A run is kept only when its resolved scene is the variant's: one that holds every value of the variant's scene
  // and more (here an effects.crack since taken out of the scene) is another run.
  Scratch s;
  json scene = sweep_scene(s.work / "out");
  scene["effects"]["crack"] = {{"at", "trailing_edge"}, {"lengths", {1e-5, 2e-5}}};
  s.write("s.json", scene.dump());
  const std::vector<std::string> vary{"sweep", "s.json", "--vary", "load.P=1e5,2e5", "--jobs", "2"};
  const Outcome first = s.fretwear(vary);
  REQUIRE_MESSAGE(first.exited(kDone), first.describe());
  auto with_resume = vary;
  with_resume.push_back("--resume");
  const Outcome again = s.fretwear(with_resume);
  REQUIRE_MESSAGE(again.exited(kDone), again.describe());
  CHECK_MESSAGE(again.err.find("2 kept from the last finished sweep") != std::string::npos, again.err);
  CHECK_MESSAGE(again.err.find("stopped") == std::string::npos, again.err);

  scene["effects"].erase("crack");
  s.write("s.json", scene.dump());
  const Outcome resumed = s.fretwear(with_resume);
  REQUIRE_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK_MESSAGE(resumed.err.find("0 kept") != std::string::npos, resumed.err);
  const auto rows = csv_rows(s.work / "out" / "sweep" / "sweep.csv", "timings.total_s");
  REQUIRE(rows.size() == 3);
  const auto column = std::find(rows[0].begin(), rows[0].end(), "crack.K_I_max_Pa_sqrt_m") - rows[0].begin();
  REQUIRE(std::size_t(column) < rows[0].size());
  for (std::size_t i = 1; i < rows.size(); ++i) {
    CHECK_MESSAGE(rows[i][std::size_t(column)].empty(), rows[i][std::size_t(column)]);
    const json resolved =
        json::parse(read_file(s.work / "out" / "sweep" / "runs" / rows[i][2] / "scene.resolved.json"));
    CHECK_FALSE(resolved["effects"].contains("crack"));
  }
}

// A sweep folder of the user's named like a killed sweep's staging folder (a copy of a finished sweep, cp -r taking
// its marker along) is not a killed sweep's: --resume neither takes its runs over nor removes it.
TEST_CASE("--resume leaves a copy of the user's named like a killed sweep's folder untouched") {
  Scratch s;
  s.write("s.json", sweep_scene(s.work / "out").dump());
  const Outcome first = s.fretwear(args("s.json", {"--jobs", "2", "-q"}));
  REQUIRE_MESSAGE(first.exited(kDone), first.describe());
  const fs::path copy = s.work / "out" / "sweep.partial-4000000";
  fs::copy(s.work / "out" / "sweep", copy, fs::copy_options::recursive);
  s.write("out/sweep.partial-4000000/mine.txt", "my notes\n");
  fs::remove_all(s.work / "out" / "sweep");  // nothing of a finished sweep to keep either
  const Snapshot before = fretwear::test::snapshot(copy);
  const Outcome resumed = s.fretwear(args("s.json", {"--jobs", "2", "--resume"}));
  REQUIRE_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK_MESSAGE(resumed.err.find("0 kept") != std::string::npos, resumed.err);
  CHECK(fretwear::test::snapshot(copy) == before);
}
