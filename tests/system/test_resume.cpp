// Long runs (docs/SCENES.md, "Long runs"): a wear run stopped by a signal keeps what it recorded and its checkpoint,
// `run --resume` continues it to the result of an uninterrupted run, bit for bit, and a checkpoint of another scene is
// refused. The program runs as a child. It is interrupted at a chosen step, the same every time, through the hooks
// of engine/main.cpp: FRETWEAR_STOP_AT_STEP=N raises SIGINT at the boundary after N accepted steps (the stop a
// Ctrl-C there makes), FRETWEAR_KILL_AT_STEP=N ends the program there as SIGKILL would (nothing written after the
// last checkpoint). Real signals land on a run slowed by FRETWEAR_STEP_PAUSE_MS (2 ms a step) in the last case.
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/checkpoint.hpp"
#include "support.hpp"
#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// Ended by `sig` as a shell reports it (128 + sig): death by the signal, or that exit status, which the program gives
// itself when it handles the signal (and FRETWEAR_KILL_AT_STEP gives as SIGKILL's).
bool ended_by(const Outcome& o, int sig) { return o.signal == sig || o.exited(128 + sig); }

// Waits (up to 20 s) until the file exists.
bool wait_for_file(const fs::path& p) {
  for (int i = 0; i < 20000 && !fs::exists(p); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return fs::exists(p);
}

// The small wear run: Hertz, R = 10 mm, E = 200 GPa, ν = 0.3, P = 1e5 N/m, f = 0.5, Q/fP = 0.5, k = 1e-12 1/Pa,
// 1e6 cycles, 8 records, 256 cells, the implicit stepper (117 steps). The reference steppers run k = 1e-13 over 1e4
// cycles (explicit: 23 steps; cycle by cycle: 1e4).
std::string scene(const std::string& k = "1e-12", const std::string& cycles = "1e6",
                  const std::string& stepper = "implicit") {
  return R"({"name": "resume", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 256}, "effects": {"wear": {"k": )" +
         k + R"(, "cycles": )" + cycles + R"(, "record": 8, "stepper": ")" + stepper +
         R"("}}, "output": {"dir": "out/resume", "plots": false}})";
}

bool partial_left(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".partial") != std::string::npos) return true;
  return false;
}

}  // namespace

namespace {

// The uninterrupted run of scene() in dir: its summary and wear history.
struct Whole {
  json summary;
  std::string history;
  int steps = 0;  // accepted steps
};

Whole whole_run(const Scratch& s) {
  const fs::path out = s.work / "out" / "resume";
  const Outcome r = s.fretwear({"run", "s.json", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  Whole w{json::parse(read_file(out / "summary.json")), read_file(out / "wear_history.csv"), 0};
  CHECK(w.summary["status"] == "completed");
  CHECK(!fs::exists(s.work / "out" / "resume.checkpoint"));  // a completed run leaves none
  w.steps = w.summary["wear"]["steps"].get<int>();
  REQUIRE(w.steps > 2);
  return w;
}

// Where to interrupt: the first step, one in the middle, and the last (its boundary comes before the last record).
std::set<int> chosen_steps(int steps) { return {1, steps / 2, steps}; }

// `run --resume` in the working folder ends as the uninterrupted run, to the bit, and leaves nothing behind.
void check_resumes_to(const Scratch& s, const Whole& whole, std::optional<double> from = std::nullopt) {
  const fs::path out = s.work / "out" / "resume";
  const Outcome r = s.fretwear({"run", "--resume", "s.json"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  CHECK(r.all().find("resuming at cycle") != std::string::npos);
  const json resumed = json::parse(read_file(out / "summary.json"));
  if (from) CHECK(resumed["wear"]["resumed_from"].get<double>() == *from);
  CHECK(fretwear::test::compare_summaries(resumed, whole.summary, "", "resumed_from") > 40);
  CHECK(read_file(out / "wear_history.csv") == whole.history);
  CHECK(!fs::exists(s.work / "out" / "resume.checkpoint"));
  CHECK(!partial_left(s.work / "out"));
}

}  // namespace

TEST_CASE("Ctrl-C stops a wear run with status 130, keeps what was recorded, and --resume ends as an uninterrupted run") {
  Scratch s;
  s.write("s.json", scene());
  const fs::path out = s.work / "out" / "resume", checkpoint = s.work / "out" / "resume.checkpoint";
  const Whole whole = whole_run(s);
  for (const int step : chosen_steps(whole.steps)) {
    INFO("stopped at step " << step << " of " << whole.steps);
    const Outcome r = s.fretwear({"run", "s.json"}, {{"FRETWEAR_STOP_AT_STEP", std::to_string(step)}});
    REQUIRE_MESSAGE(r.exited(kInterrupted), r.describe());
    CHECK(r.all().find("--resume") != std::string::npos);
    const json stopped = json::parse(read_file(out / "summary.json"));
    CHECK(stopped["status"] == "interrupted");
    CHECK(stopped["wear"]["steps"].get<int>() == step);
    const double reached = stopped["wear"]["cycles_reached"].get<double>();
    CHECK(reached > 0.0);
    CHECK(reached <= 1e6);
    CHECK(stopped["wear"]["cycles"].get<double>() <= reached);  // the last record
    CHECK(!stopped.contains("crack"));
    // What was recorded is written: a row per record so far, each as the uninterrupted run's.
    const std::string history = read_file(out / "wear_history.csv");
    CHECK(whole.history.rfind(history, 0) == 0);
    CHECK(history.size() < whole.history.size());
    CHECK(fs::exists(checkpoint));  // written at the stop, whatever --checkpoint-every says
    CHECK(!partial_left(s.work / "out"));
    check_resumes_to(s, whole, reached);
  }
}

TEST_CASE("a run killed at a chosen step resumes from its last checkpoint to the uninterrupted result") {
  Scratch s;
  s.write("s.json", scene());
  const fs::path checkpoint = s.work / "out" / "resume.checkpoint";
  const Whole whole = whole_run(s);
  for (const int step : chosen_steps(whole.steps)) {
    INFO("killed at step " << step << " of " << whole.steps << ", a checkpoint at every boundary");
    const Outcome r = s.fretwear({"run", "s.json", "-q", "--checkpoint-every", "0"},
                                 {{"FRETWEAR_KILL_AT_STEP", std::to_string(step)}});
    REQUIRE_MESSAGE(ended_by(r, SIGKILL), r.describe());
    REQUIRE(fs::exists(checkpoint));
    // A killed run may leave its staging folder; the next run removes it.
    check_resumes_to(s, whole);
  }
  // With checkpoints at the records only (the default interval of a minute is not reached), from the last record.
  INFO("killed at step " << whole.steps / 2 << ", checkpoints at records only");
  const Outcome r = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_KILL_AT_STEP", std::to_string(whole.steps / 2)}});
  REQUIRE_MESSAGE(ended_by(r, SIGKILL), r.describe());
  REQUIRE(fs::exists(checkpoint));
  const json saved = json::from_cbor(read_file(checkpoint));
  CHECK(saved["steps"].get<int>() < whole.steps / 2);
  check_resumes_to(s, whole);
}

TEST_CASE("the reference steppers' checkpoints resume to the bit too") {
  for (const std::string stepper : {"explicit", "cycle_by_cycle"}) {
    INFO(stepper);
    Scratch s;
    s.write("s.json", scene("1e-13", "1e4", stepper));
    const Whole whole = whole_run(s);
    const int step = whole.steps / 2;
    const Outcome r = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", std::to_string(step)}});
    REQUIRE_MESSAGE(r.exited(kInterrupted), r.describe());
    const json stopped = json::parse(read_file(s.work / "out" / "resume" / "summary.json"));
    CHECK(stopped["wear"]["steps"].get<int>() == step);
    check_resumes_to(s, whole, stopped["wear"]["cycles_reached"].get<double>());
  }
}

TEST_CASE("a gross-slip run with each body in its own frame, killed mid-run, resumes to the bit") {
  // examples/gross_slip_displacement_wear.json shortened: 256 cells, 3000 cycles, 4 records; the checkpoint carries
  // the two profiles and the positions' warm starts (engine/body_frames.hpp), and under the stepper "explicit" the
  // last rate Dormand–Prince carries.
  for (const std::string stepper : {"implicit", "explicit"}) {
    INFO(stepper);
    Scratch s;
    s.write("s.json", R"({"name": "resume", "materials": {"both": {"E": 2e11, "nu": 0.3}},
      "profile": {"type": "cylinder", "R": 6e-3}, "friction": 0.9,
      "load": {"P": 18500, "control": "displacement", "delta": 25e-6},
      "grid": {"cells": 256, "window": [-0.6e-3, 0.6e-3], "reference_depth": 6e-3},
      "effects": {"wear": {"k": 5e-14, "cycles": 3000, "record": 4, "stepper": ")" +
                          stepper + R"("}}, "output": {"dir": "out/resume", "plots": false}})");
    const Whole whole = whole_run(s);
    REQUIRE(whole.summary["wear"]["bodies"]["frames"] == "own");
    const int step = whole.steps / 2;
    INFO("killed at step " << step << " of " << whole.steps);
    const Outcome r = s.fretwear({"run", "s.json", "-q", "--checkpoint-every", "0"},
                                 {{"FRETWEAR_KILL_AT_STEP", std::to_string(step)}});
    REQUIRE_MESSAGE(ended_by(r, SIGKILL), r.describe());
    check_resumes_to(s, whole);
  }
}

namespace {

// A run under load.blocks stopped (then killed) at each given step of its blocks, {step, after, before}: it stops
// between cycles `after` and `before`, and resumes to the uninterrupted run `whole`.
void check_blocks_resume(const Scratch& s, const Whole& whole,
                         std::initializer_list<std::tuple<int, double, double>> stops) {
  for (const auto& [step, first_cycle, last_cycle] : stops) {
    INFO("stopped at step " << step << " of its block");
    const Outcome stopped = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", std::to_string(step)}});
    REQUIRE_MESSAGE(stopped.exited(kInterrupted), stopped.describe());
    const double reached = json::parse(read_file(s.work / "out" / "resume" / "summary.json"))["wear"]["cycles_reached"];
    CHECK(reached > first_cycle);
    CHECK(reached < last_cycle);
    check_resumes_to(s, whole, reached);
    INFO("killed at step " << step << " of its block");
    const Outcome killed = s.fretwear({"run", "s.json", "-q", "--checkpoint-every", "0"},
                                      {{"FRETWEAR_KILL_AT_STEP", std::to_string(step)}});
    REQUIRE_MESSAGE(ended_by(killed, SIGKILL), killed.describe());
    check_resumes_to(s, whole);
  }
}

}  // namespace

TEST_CASE("a run under load.blocks stopped or killed in any block resumes to the uninterrupted result") {
  // Three blocks (Q/fP = 0.5 for 200 cycles, a history of P and Q for 5000, Q/fP = 0.7 for 2000; 256 cells, 123
  // steps in all): the step hooks count each block's steps, so step 1 stops in the first block and step 30 in the
  // second, after the first block's records.
  Scratch s;
  s.write("s.json", R"({"name": "resume", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
    "load": {"P": 1e5, "blocks": [{"Q": {"ratio": 0.5}, "cycles": 200},
      {"history": [[0, 1e5, 2e4, 0], [0.25, 1.2e5, 0, 0], [0.5, 1e5, -2e4, 0], [0.75, 0.8e5, 0, 0], [1, 1e5, 2e4, 0]],
       "cycles": 5000}, {"Q": {"ratio": 0.7}, "cycles": 2000}]},
    "grid": {"cells": 256, "window": [-0.2e-3, 0.2e-3]},
    "effects": {"wear": {"k": 1e-12, "cycles": 7200, "record": 8}}, "output": {"dir": "out/resume", "plots": false}})");
  check_blocks_resume(s, whole_run(s), {{1, 0.0, 200.0}, {30, 200.0, 5200.0}});
}

TEST_CASE("load.blocks with each body in its own frame, stopped or killed in a block, resumes to the bit") {
  // The gross-slip scene shortened, in three blocks: partial slip (δ = 0.5 µm) for 50 cycles, gross slip (25 µm) for
  // 10, worn in the bodies' own frames, then partial slip for 20 000, its wear split onto the two profiles (48 steps
  // in all). Step 10 stops in the second block (whose state is the two profiles), step 20 in the third (the shared
  // profile on top of the two the second block left, which the checkpoint carries).
  Scratch s;
  s.write("s.json", R"({"name": "resume", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 6e-3}, "friction": 0.9,
    "load": {"P": 18500, "blocks": [{"delta": 0.5e-6, "cycles": 50}, {"delta": 25e-6, "cycles": 10},
      {"delta": 0.5e-6, "cycles": 20000}]},
    "grid": {"cells": 256, "window": [-0.6e-3, 0.6e-3], "reference_depth": 6e-3},
    "effects": {"wear": {"k": 5e-14, "cycles": 20060, "record": 8}}, "output": {"dir": "out/resume", "plots": false}})");
  const Whole whole = whole_run(s);
  REQUIRE(whole.summary["wear"]["bodies"]["frames"] == "own");
  check_blocks_resume(s, whole, {{10, 50.0, 60.0}, {20, 60.0, 20060.0}});
}

TEST_CASE("--resume refuses a damaged checkpoint, and a run without --resume says which checkpoint it replaces") {
  Scratch s;
  s.write("s.json", scene());
  const fs::path out = s.work / "out" / "resume", checkpoint = s.work / "out" / "resume.checkpoint";
  const Outcome stopped = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", "5"}});
  REQUIRE_MESSAGE(stopped.exited(kInterrupted), stopped.describe());
  REQUIRE(fs::exists(checkpoint));
  const std::string bytes = read_file(checkpoint);
  // One number changed after the checkpoint was written, as a flipped bit in a double would change it.
  json j = json::from_cbor(bytes);
  REQUIRE(j.contains("checksum"));
  j["cycles"] = j["cycles"].get<double>() * (1.0 + 1e-12);
  const std::vector<std::uint8_t> changed = json::to_cbor(j);
  write_file(checkpoint, std::string(changed.begin(), changed.end()));
  const std::string kept = read_file(out / "summary.json");
  const Outcome damaged = s.fretwear({"run", "--resume", "s.json"});
  CHECK_MESSAGE(damaged.exited(kInvalid), damaged.describe());
  CHECK_MESSAGE(damaged.all().find("resume.checkpoint: damaged") != std::string::npos, damaged.all());
  CHECK(read_file(out / "summary.json") == kept);  // nothing written
  // Without --resume the run says what it replaces: the damaged one, then this scene's own.
  const Outcome over_damaged = s.fretwear({"run", "s.json"});
  REQUIRE_MESSAGE(over_damaged.exited(kDone), over_damaged.describe());
  CHECK_MESSAGE(over_damaged.all().find("a checkpoint this scene cannot resume") != std::string::npos,
                over_damaged.all());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", "5"}}).exited(kInterrupted));
  const Outcome over = s.fretwear({"run", "s.json"});
  REQUIRE_MESSAGE(over.exited(kDone), over.describe());
  CHECK_MESSAGE(over.all().find("holds this scene's wear run stopped at cycle") != std::string::npos, over.all());
  CHECK(over.all().find("fretwear run --resume s.json") != std::string::npos);
  CHECK(!fs::exists(checkpoint));  // replaced, and removed once the run completed
  // A run with nothing to replace says nothing of checkpoints.
  const Outcome again = s.fretwear({"run", "s.json"});
  CHECK(again.all().find("checkpoint") == std::string::npos);
}

namespace {

using Edits = std::vector<std::pair<std::string, std::function<void(json&)>>>;

// A blob of k doubles of 0: a vector of the wrong length for any grid here.
json doubles(std::size_t k) { return json::binary(std::vector<std::uint8_t>(8 * k, 0)); }

// Stops the run of `scene` after `step` steps; then each edit of its checkpoint, re-signed, is refused by --resume
// (exit 2, "checkpoint: damaged", the stopped run's results untouched), and the checkpoint as written resumes.
void check_edits_refused(const std::string& scene, int step, const Edits& edits) {
  Scratch s;
  s.write("s.json", scene);
  const fs::path out = s.work / "out" / "resume", checkpoint = s.work / "out" / "resume.checkpoint";
  REQUIRE(s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", std::to_string(step)}})
              .exited(kInterrupted));
  const std::string original = read_file(checkpoint), kept = read_file(out / "summary.json");
  const json j0 = json::from_cbor(original);
  REQUIRE(j0.at("checksum") == fretwear::checkpoint_checksum(j0));
  for (const auto& [what, edit] : edits) {
    CAPTURE(what);
    json j = j0;
    edit(j);
    j["checksum"] = fretwear::checkpoint_checksum(j);
    const std::vector<std::uint8_t> bytes = json::to_cbor(j);
    write_file(checkpoint, std::string(bytes.begin(), bytes.end()));
    const Outcome o = s.fretwear({"run", "--resume", "s.json", "-q"});
    CHECK_MESSAGE(o.exited(kInvalid), o.describe());
    CHECK_MESSAGE(o.all().find("checkpoint: damaged") != std::string::npos, o.all());
    CHECK(read_file(out / "summary.json") == kept);
  }
  write_file(checkpoint, original);  // as written, it resumes
  CHECK(s.fretwear({"run", "--resume", "s.json", "-q"}).exited(kDone));
}

}  // namespace

// The checksum tells a checkpoint damaged after it was written, but anyone can write one: a checkpoint re-signed after
// an edit is still checked against the scene, and refused (exit 2, nothing written) where it does not fit it. Its wear
// emptied was a segmentation fault, one value of it a read past its end; its records replaced by numbers an internal
// error (exit 1); its place past the last record a run reported completed at a fraction of its cycles; a warm start
// of the wrong length was taken for none, and the run went on from a state it had not been in.
TEST_CASE("--resume refuses a re-signed checkpoint whose content does not fit the scene") {
  check_edits_refused(
      scene(), 5,
      {{"wear emptied", [](json& j) { j["w"] = json::binary({}); }},
       {"wear of one value", [](json& j) { j["w"] = doubles(1); }},
       {"wear not a number",
        [](json& j) {
          auto bytes = j["w"].get_binary();
          const double nan = std::nan("");
          std::memcpy(bytes.data(), &nan, sizeof nan);
          j["w"] = json::binary(bytes);
        }},
       {"records replaced by numbers", [](json& j) { j["records"] = {1, 2, 3}; }},
       {"records dropped", [](json& j) { j["records"] = json::array(); }},
       {"past the last record", [](json& j) { j["next_record"] = 1000; }},
       {"past the last cycle", [](json& j) { j["cycles"] = 1e300; }},
       {"its contact gone", [](json& j) { j.erase("contact"); }},
       {"its contact's pressure of one value", [](json& j) { j["contact"]["normal"]["p"] = doubles(1); }},
       {"its contact's gap of three values", [](json& j) { j["contact"]["implicit"]["gap"] = doubles(3); }},
       {"its stepper's pressure of one value", [](json& j) { j["stepper_state"]["p_full"] = doubles(1); }},
       {"its stepper's half-step pressure of three values", [](json& j) { j["stepper_state"]["p_half"] = doubles(3); }},
       {"a record's stick zone of one end", [](json& j) { j["records"][0]["stick_zone"] = {1.0}; }},
       {"a record's contact a string", [](json& j) { j["records"][0]["contact"] = "wide"; }}});
}

TEST_CASE("--resume refuses a re-signed checkpoint whose lagged coupling or body frames do not fit the grid") {
  // Dissimilar bodies (the lag's references and corrections, read on every cell once it lags: γ ≥ 0).
  std::string dissimilar = scene();
  const std::string both = R"("materials": {"both": {"E": 2e11, "nu": 0.3}})";
  dissimilar.replace(dissimilar.find(both), both.size(),
                     R"("materials": {"pad": {"E": 2e11, "nu": 0.3}, "specimen": {"E": 7.1e10, "nu": 0.33}})");
  const auto lagging = [](json& j) -> json& {
    json& l = j["contact"]["lagged"];
    l["gain"] = 0.5;
    return l;
  };
  check_edits_refused(
      dissimilar, 5,
      {{"the lag's slip correction of one value", [&](json& j) { lagging(j)["slip_correction"] = {0.0}; }},
       {"the lag's shear correction emptied", [&](json& j) { lagging(j)["shear_correction"] = json::array(); }},
       {"the lag's coupled reference of two cells", [&](json& j) { lagging(j)["coupled_ref"]["p"] = {1.0, 2.0}; }},
       {"the cycle's top shear of one value", [](json& j) { j["contact"]["q_top"] = {0.0}; }}});
  // Each body in its own frame, under both steppers that carry the positions' pressures.
  for (const std::string stepper : {"implicit", "explicit"}) {
    INFO(stepper);
    const std::string frames = R"({"name": "resume", "materials": {"both": {"E": 2e11, "nu": 0.3}},
      "profile": {"type": "cylinder", "R": 6e-3}, "friction": 0.9,
      "load": {"P": 18500, "control": "displacement", "delta": 25e-6},
      "grid": {"cells": 256, "window": [-0.6e-3, 0.6e-3], "reference_depth": 6e-3},
      "effects": {"wear": {"k": 5e-14, "cycles": 3000, "record": 4, "stepper": ")" +
                               stepper + R"("}}, "output": {"dir": "out/resume", "plots": false}})";
    const std::string key = stepper == "implicit" ? "p_start" : "p";
    Edits edits = {{"a position's pressure of one value", [key](json& j) { j["stepper_state"][key][0] = doubles(1); }}};
    if (stepper == "explicit")
      edits.push_back({"the last rate of three values", [](json& j) { j["stepper_state"]["rate"] = doubles(3); }});
    check_edits_refused(frames, 3, edits);
  }
}

// A checkpoint is insurance: one that cannot be written (a full disk) leaves the last one written, and the run goes
// on; before, the run ended there as an internal error. Results that cannot be written then keep that checkpoint
// (free some space and --resume), or, with none written, leave nothing at all.
TEST_CASE("a wear run on a full disk goes on past a checkpoint it cannot write, and keeps the last one written") {
  Scratch s;
  s.write("s.json", scene());
  const fs::path checkpoint = s.work / "out" / "resume.checkpoint";
  // Room for the first checkpoint (cycle 0), not the later ones, nor the results.
  const Outcome full = s.fretwear_file_limited(60, {"run", "s.json", "-q"});
  CHECK_MESSAGE(full.exited(kInvalid), full.describe());
  CHECK(full.err.find("internal error") == std::string::npos);
  CHECK_MESSAGE(full.err.find("fretwear: the results cannot be written:\n  output.dir: cannot write ") !=
                    std::string::npos,
                full.describe());
  CHECK_MESSAGE(full.err.find("(the wear stage's checkpoint is kept: once the results can be written, fretwear run "
                              "--resume s.json takes the run up from cycle 0)") != std::string::npos,
                full.describe());
  REQUIRE(fs::exists(checkpoint));
  CHECK(!fs::exists(s.work / "out" / "resume"));
  CHECK(!partial_left(s.work / "out"));
  const Outcome resumed = s.fretwear({"run", "--resume", "s.json", "-q"});
  CHECK_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK(!fs::exists(checkpoint));
  // Room for nothing: no checkpoint, no results, and not the folder made for them.
  fs::remove_all(s.work / "out");
  const Outcome none = s.fretwear_file_limited(8, {"run", "s.json", "-q"});
  CHECK_MESSAGE(none.exited(kInvalid), none.describe());
  CHECK(none.err.find("fretwear: the results cannot be written:") != std::string::npos);
  CHECK(none.err.find("checkpoint") == std::string::npos);
  CHECK(!fs::exists(s.work / "out"));
  // Stopped where its checkpoint does not fit (dissimilar bodies, whose checkpoint holds the lag's vectors too, 49 kB
  // against 22 kB for the largest result at two records): the stop says --resume cannot start from there.
  std::string dissimilar = scene();
  const std::string eight = R"("record": 8)";
  dissimilar.replace(dissimilar.find(eight), eight.size(), R"("record": 2)");
  const std::string both = R"("materials": {"both": {"E": 2e11, "nu": 0.3}})";
  dissimilar.replace(dissimilar.find(both), both.size(),
                     R"("materials": {"pad": {"E": 2e11, "nu": 0.3}, "specimen": {"E": 7.1e10, "nu": 0.33}})");
  s.write("s.json", dissimilar);
  const Outcome stopped = s.fretwear_file_limited(60, {"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", "5"}});
  CHECK_MESSAGE(stopped.exited(kInterrupted), stopped.describe());
  CHECK_MESSAGE(stopped.err.find("continue with: fretwear run --resume s.json (but the checkpoint of this stop could "
                                 "not be written: cannot write the checkpoint ") != std::string::npos,
                stopped.describe());
  CHECK(stopped.err.find("File too large; --resume starts from the last one that was, or from the start)") !=
        std::string::npos);
}

TEST_CASE("--resume refuses another scene's checkpoint, and without one runs from the start") {
  Scratch s;
  s.write("s.json", scene());
  const fs::path checkpoint = s.work / "out" / "resume.checkpoint";
  const Outcome fresh = s.fretwear({"run", "--resume", "s.json"});
  REQUIRE_MESSAGE(fresh.exited(kDone), fresh.describe());
  CHECK(fresh.all().find("no checkpoint") != std::string::npos);

  Child run = s.start({"run", "s.json", "-q", "--checkpoint-every", "0"}, {{"FRETWEAR_STEP_PAUSE_MS", "2"}});
  REQUIRE(wait_for_file(checkpoint));
  run.signal(SIGTERM);
  const Outcome terminated = run.wait();
  CHECK_MESSAGE(ended_by(terminated, SIGTERM), terminated.describe());
  const std::string kept = read_file(s.work / "out" / "resume" / "summary.json");
  s.write("other.json", scene("2e-12"));  // another k, the same output folder
  const Outcome other = s.fretwear({"run", "--resume", "other.json"});
  CHECK_MESSAGE(other.exited(kInvalid), other.describe());
  CHECK(other.all().find("belongs to another scene") != std::string::npos);
  CHECK(read_file(s.work / "out" / "resume" / "summary.json") == kept);  // nothing written
  CHECK(fs::exists(checkpoint));
  // One cut short (a copy interrupted, a disk full) is said to be fretwear's and damaged, and the way out it gives,
  // a run without --resume, starts afresh over it.
  const std::string whole = read_file(checkpoint);
  write_file(checkpoint, whole.substr(0, whole.size() - 10));
  const Outcome cut = s.fretwear({"run", "--resume", "s.json"});
  CHECK_MESSAGE(cut.exited(kInvalid), cut.describe());
  CHECK_MESSAGE(cut.all().find("a fretwear checkpoint that is damaged or cut short") != std::string::npos,
                cut.describe());
  CHECK_MESSAGE(cut.all().find("or run without --resume, which starts afresh") != std::string::npos, cut.describe());
  const Outcome afresh = s.fretwear({"run", "s.json", "-q"});
  CHECK_MESSAGE(afresh.exited(kDone), afresh.describe());
  // A file that is not a checkpoint is refused too.
  write_file(checkpoint, "not a checkpoint");
  const Outcome foreign = s.fretwear({"run", "--resume", "s.json"});
  CHECK_MESSAGE(foreign.exited(kInvalid), foreign.describe());
  CHECK(foreign.all().find("not a fretwear checkpoint") != std::string::npos);
}
