// A run whose solver does not converge (exit 3) replaces output.dir with a folder holding summary.json alone, with
// status "not_converged": that summary names the stage that failed (failed_stage) and keeps what the stages before
// it found, in the sections a completed run's summary gives them, with the warnings so far (docs/SCENES.md, "Output";
// docs/OUTPUTS.md). No real scene fails on demand in a chosen stage: the test hook
// FRETWEAR_NOT_CONVERGED_IN_STAGE=<stage> (main.cpp) throws a ConvergenceError where that stage first asks whether to
// stop, and FRETWEAR_NORMAL_MAX_ITERATIONS=k stops the normal solve short.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <doctest/doctest.h>
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
