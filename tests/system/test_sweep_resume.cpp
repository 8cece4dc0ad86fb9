// `fretwear sweep --resume` (docs/SCENES.md, "Sweeps"): a sweep killed part way (SIGKILL, as by a crash or a
// scheduler, at a chosen run through FRETWEAR_SWEEP_KILL_AFTER_RUNS) is finished by the same command with --resume;
// the runs that were complete are kept (not run again), the others run, and the table equals that of a sweep that
// was never stopped.
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
  CHECK_MESSAGE(resumed.err.find(std::to_string(complete.size()) + " kept") != std::string::npos, resumed.err);
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
