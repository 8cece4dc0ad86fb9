// A run whose solver does not converge (exit 3) replaces output.dir with a folder holding summary.json (and, where
// the wear stage failed part way, the tables of its records), with status "not_converged": that summary names the
// stage that failed (failed_stage) and keeps what the stages before it found, in the sections a completed run's
// summary gives them, with the warnings so far (docs/SCENES.md, "Output"; docs/OUTPUTS.md). No real scene fails on demand in a chosen stage: the test hook
// FRETWEAR_NOT_CONVERGED_IN_STAGE=<stage> (main.cpp) throws a ConvergenceError where that stage first asks whether to
// stop, FRETWEAR_NOT_CONVERGED_AT_STEP=N the wear stage after N accepted steps, and FRETWEAR_NORMAL_MAX_ITERATIONS=k
// stops the normal solve short.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "support.hpp"
#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// The files of a folder, by name.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The warnings of a summary for which `later` (a stage after the failure gave it) is false.
template <class Later>
json warnings_but(const json& summary, Later later) {
  json kept = json::array();
  for (const json& w : summary["warnings"])
    if (!later(w["code"].get<std::string>(), w["message"].get<std::string>())) kept.push_back(w);
  return kept;
}

// The scene run to its end, then with a ConvergenceError in `stage`: the two summaries.
struct Runs {
  json completed, failed;
  Outcome failure;
};

Runs complete_then_fail(Scratch& s, const json& scene, const std::string& stage) {
  s.write("s.json", scene.dump());
  const Outcome done = s.fretwear({"run", "s.json", "-q"});
  REQUIRE_MESSAGE(done.exited(kDone), done.describe());
  const fs::path dir = s.work / "output" / scene["name"].get<std::string>();
  Runs runs;
  runs.completed = json::parse(std::ifstream(dir / "summary.json"));
  runs.failure = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_NOT_CONVERGED_IN_STAGE", stage}});
  CHECK_MESSAGE(runs.failure.exited(kNotConverged), runs.failure.describe());
  CHECK(runs.failure.err.find(stage + ": the solve stopped short of its tolerance") != std::string::npos);
  // The completed run's folder is replaced by the summary alone.
  CHECK(files_in(dir) == std::vector<std::string>{".fretwear", "summary.json"});
  runs.failed = json::parse(std::ifstream(dir / "summary.json"));
  CHECK(runs.failed["status"] == "not_converged");
  CHECK(runs.failed["failed_stage"] == stage);
  CHECK(runs.failed["message"].get<std::string>().find(stage + ": the solve stopped short") != std::string::npos);
  CHECK(runs.failed["scene"] == runs.completed["scene"]);
  CHECK(runs.failed["version"] == runs.completed["version"]);
  CHECK_FALSE(runs.failed.contains("plots"));  // none drawn
  return runs;
}

}  // namespace

TEST_CASE("a solve that fails in the crack stage keeps the contact, cycle, wear and stresses of a completed run") {
  Scratch s;
  json scene = wear_scene();
  scene["effects"]["stress"] = {{"nx", 41}, {"ny", 20}};
  scene["effects"]["crack"] = {{"lengths", {1e-5, 2e-5}}};
  scene["output"] = {{"plots", false}};
  const Runs runs = complete_then_fail(s, scene, "crack");
  const json& failed = runs.failed;
  CHECK(failed["effects_run"] == json::array({"normal", "tangential", "wear", "stress"}));
  std::set<std::string> timed;
  for (const auto& [stage, seconds] : failed["timings"].items()) timed.insert(stage);
  CHECK(timed == std::set<std::string>{"total", "normal", "tangential", "wear", "stress"});
  CHECK_FALSE(failed.contains("crack"));
  int numbers = 0;
  for (const char* section : {"contact", "materials", "grid", "solver", "cycle", "wear", "stress", "effects_implied"}) {
    CAPTURE(section);
    REQUIRE(runs.completed.contains(section));
    REQUIRE(failed.contains(section));
    numbers += fretwear::test::compare_summaries(failed[section], runs.completed[section], section);
  }
  CHECK(numbers > 100);  // the records of the wear and the stress maxima of every state among them
  // The warnings of the stages that completed (the crack's own are not reached).
  CHECK(failed["warnings"] == warnings_but(runs.completed, [](const std::string& code, const std::string&) {
          return code.rfind("crack_", 0) == 0;
        }));
}

TEST_CASE("a solve that fails in the load cycle keeps the normal contact and its warnings") {
  // 256 cells over a given window of 4 mm: the Hertz contact (2a = 0.22 mm) spans 14, under-resolved.
  Scratch s;
  json scene = cycle_scene();
  scene["grid"]["window"] = {-2e-3, 2e-3};
  const Runs runs = complete_then_fail(s, scene, "tangential");
  const json& failed = runs.failed;
  CHECK(failed["effects_run"] == json::array({"normal"}));
  CHECK_FALSE(failed.contains("cycle"));
  for (const char* section : {"contact", "materials", "grid", "solver"}) {
    CAPTURE(section);
    fretwear::test::compare_summaries(failed[section], runs.completed[section], section);
  }
  // The cycle's own warnings (the slip and stick zones, the Mindlin stick zone missed) are not reached.
  CHECK(failed["warnings"] ==
        warnings_but(runs.completed, [](const std::string& code, const std::string& message) {
          return code == "slip_zone_under_resolved" || code == "stick_zone_under_resolved" ||
                 (code == "closed_form_missed" && message.rfind("the stick zone", 0) == 0);
        }));
  const json codes = failed["warnings"];
  CHECK(std::any_of(codes.begin(), codes.end(), [](const json& w) { return w["code"] == "contact_under_resolved"; }));
  // The warnings found are said on stderr too, as a completed run says them.
  for (const json& w : failed["warnings"])
    CHECK(runs.failure.err.find("warning: " + w["code"].get<std::string>() + ": " +
                                w["message"].get<std::string>()) != std::string::npos);
}

TEST_CASE("a normal solve that fails names the normal stage and has no stage's results") {
  Scratch s;
  s.write("s.json", cycle_scene().dump());
  const Outcome r = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_NORMAL_MAX_ITERATIONS", "2"}});
  CHECK_MESSAGE(r.exited(kNotConverged), r.describe());
  const json summary = json::parse(std::ifstream(s.work / "output" / "h" / "summary.json"));
  CHECK(summary["status"] == "not_converged");
  CHECK(summary["failed_stage"] == "normal");
  CHECK(summary["effects_run"] == json::array());
  CHECK(summary["warnings"] == json::array());
  CHECK_FALSE(summary.contains("contact"));
  CHECK_FALSE(summary.contains("timings"));
}

TEST_CASE("a wear scene's trial solve that fails names the trial grid it ran on, and how to skip it") {
  // A wearing scene without grid.window has its window sized by the asymptote on a trial grid of 1024 cells
  // (engine/setup.cpp); its solve is the first to fail, on cells the scene never asked for.
  Scratch s;
  json scene = wear_scene();
  scene["grid"]["cells"] = 256;
  s.write("s.json", scene.dump());
  const Outcome r = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_NORMAL_MAX_ITERATIONS", "2"}});
  CHECK_MESSAGE(r.exited(kNotConverged), r.describe());
  const std::string said = "grid.window: sizing the default window for the worn contact on a trial grid of 1024 cells";
  CHECK(r.err.find(said) != std::string::npos);
  CHECK(r.err.find("residual") != std::string::npos);
  CHECK(r.err.find("; give grid.window to skip this trial") != std::string::npos);
  const json summary = json::parse(std::ifstream(s.work / "output" / "h" / "summary.json"));
  CHECK(summary["failed_stage"] == "normal");
  CHECK(summary["message"].get<std::string>().starts_with(said));
  // With the window given there is no trial: the scene's own solve fails, on its own 256 cells.
  scene["grid"]["window"] = {-4e-4, 4e-4};
  s.write("s.json", scene.dump());
  const Outcome given = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_NORMAL_MAX_ITERATIONS", "2"}});
  CHECK_MESSAGE(given.exited(kNotConverged), given.describe());
  CHECK(given.err.find("trial") == std::string::npos);
  CHECK(given.err.find("on 256 cells") != std::string::npos);
}

namespace {

// A wear run made to fail at the first step boundary after `step` accepted steps (FRETWEAR_NOT_CONVERGED_AT_STEP),
// against the same run stopped there (FRETWEAR_STOP_AT_STEP, a Ctrl-C at that boundary): the failed run's summary
// holds the stopped run's wear section, key for key, and its folder the stopped run's wear tables, byte for byte; no
// stage after the wear. `tables`: the wear tables a run of this scene writes; it fails after cycle `after`, with the
// bodies' `frames` ("own" or "shared").
void check_fails_as_stopped(Scratch& s, const std::string& scene, int step, const std::vector<std::string>& tables,
                            double after, const std::string& frames) {
  INFO("failed at step " << step);
  s.write("s.json", scene);
  const fs::path dir = s.work / "out" / "fail";
  const Outcome stopped = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", std::to_string(step)}});
  REQUIRE_MESSAGE(stopped.exited(kInterrupted), stopped.describe());
  const json interrupted = json::parse(read_file(dir / "summary.json"));
  std::vector<std::string> kept;
  for (const std::string& table : tables) kept.push_back(read_file(dir / table));

  const Outcome failure = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_NOT_CONVERGED_AT_STEP", std::to_string(step)}});
  REQUIRE_MESSAGE(failure.exited(kNotConverged), failure.describe());
  const json failed = json::parse(read_file(dir / "summary.json"));
  CHECK(failed["status"] == "not_converged");
  CHECK(failed["failed_stage"] == "wear");
  CHECK(failed["effects_run"] == json::array({"normal", "tangential"}));
  CHECK(failed["timings"].contains("wear"));
  CHECK_FALSE(failed.contains("stress"));
  const double reached = failed["wear"]["cycles_reached"].get<double>();
  CHECK(reached > after);
  CHECK(reached < failed["wear"]["cycles_target"].get<double>());
  CHECK(failed["wear"]["bodies"]["frames"] == frames);
  CHECK(failed["message"].get<std::string>().find(fmt::format("in the wear stage at cycle {:.0f} of", reached)) !=
        std::string::npos);
  CHECK(fretwear::test::compare_summaries(failed["wear"], interrupted["wear"], "wear") > 20);
  std::vector<std::string> files{".fretwear", "summary.json"};
  files.insert(files.end(), tables.begin(), tables.end());
  std::sort(files.begin(), files.end());
  CHECK(files_in(dir) == files);  // the tables of the records, no plot
  for (std::size_t k = 0; k < tables.size(); ++k) {
    CAPTURE(tables[k]);
    CHECK(read_file(dir / tables[k]) == kept[k]);
  }
}

}  // namespace

TEST_CASE("a wear stage that fails part way keeps its records, as a run stopped there") {
  Scratch s;
  SUBCASE("one load, the bodies sharing one profile; the stress asked for is not reached") {
    json scene = wear_scene();
    scene["effects"]["stress"] = {{"nx", 21}, {"ny", 10}};
    scene["output"] = {{"dir", "out/fail"}, {"plots", false}};
    check_fails_as_stopped(s, scene.dump(), 12, {"profiles.csv", "wear_history.csv"}, 0.0, "shared");
  }
  SUBCASE("load.blocks, failing in the second block after the first block's records") {
    // 30 steps in the first block; the step hooks count each block's steps.
    check_fails_as_stopped(s, R"({"name": "fail", "materials": {"both": {"E": 2e11, "nu": 0.3}},
      "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
      "load": {"P": 1e5, "blocks": [{"Q": {"ratio": 0.5}, "cycles": 200}, {"Q": {"ratio": 0.7}, "cycles": 5000}]},
      "grid": {"cells": 256, "window": [-0.2e-3, 0.2e-3]},
      "effects": {"wear": {"k": 1e-12, "cycles": 5200, "record": 8}}, "output": {"dir": "out/fail", "plots": false}})",
                           31, {"profiles.csv", "wear_history.csv"}, 200.0, "shared");
  }
  SUBCASE("gross slip, each body in its own frame") {
    check_fails_as_stopped(s, R"({"name": "fail", "materials": {"both": {"E": 2e11, "nu": 0.3}},
      "profile": {"type": "cylinder", "R": 6e-3}, "friction": 0.9,
      "load": {"P": 18500, "control": "displacement", "delta": 25e-6},
      "grid": {"cells": 256, "window": [-0.6e-3, 0.6e-3], "reference_depth": 6e-3},
      "effects": {"wear": {"k": 5e-14, "cycles": 3000, "record": 4}}, "output": {"dir": "out/fail", "plots": false}})",
                           10, {"profiles.csv", "wear_history.csv"}, 0.0, "own");
  }
}
