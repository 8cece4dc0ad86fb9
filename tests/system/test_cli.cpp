// The fretwear program as a user meets it: exit status, what is written and what is not.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "support.hpp"
#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

const char* kGood = R"({"name": "cli", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "grid": {"cells": 256}})";

}  // namespace

TEST_CASE("run writes summary, resolved scene, CSV, plots and index into output/<name>") {
  Scratch s;
  s.write("s.json", kGood);
  const Outcome r = s.fretwear({"run", "s.json"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const fs::path dir = s.work / "output" / "cli";
  for (const char* f : {"summary.json", "scene.resolved.json", "contact.csv", "index.html"})
    CHECK_MESSAGE(fs::exists(dir / f), f);
  const json summary = json::parse(std::ifstream(dir / "summary.json"));
  CHECK(summary["scene"] == "cli");
  CHECK(summary["contact"]["extent"].size() == 2);
  CHECK(summary["timings"]["total"].get<double>() > 0.0);
  // The resolved scene reproduces the run: same window, same result.
  std::string csv_first;
  std::getline(std::ifstream(dir / "contact.csv") >> std::ws, csv_first);
  CHECK(csv_first.rfind("x_m,gap0_m,p_Pa", 0) == 0);
  fs::copy_file(dir / "scene.resolved.json", s.work / "again.json");
  const Outcome again_run = s.fretwear({"run", "again.json", "-q"});
  REQUIRE_MESSAGE(again_run.exited(kDone), again_run.describe());
  const json again = json::parse(std::ifstream(dir / "summary.json"));
  // The same window to the last digit JSON keeps; the cell width is recomputed from it, so agreement is to
  // round-off of the grid, far inside the solver's tolerance.
  for (int k = 0; k < 2; ++k)
    CHECK(again["contact"]["extent"][k].get<double>() ==
          fretwear::test::rel(summary["contact"]["extent"][k].get<double>(), 1e-10));
  // No staging folder is left behind.
  for (const auto& e : fs::directory_iterator(s.work / "output"))
    CHECK(e.path().filename().string().find(".partial") == std::string::npos);
}

TEST_CASE("an invalid scene exits with status 2, names every problem and writes nothing") {
  Scratch s;
  s.write("bad.json", R"({"name": "bad", "materials": {"both": {"E": -1, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "gird": {}})");
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear({"run", "bad.json"});
  CHECK_MESSAGE(r.exited(kInvalid), r.describe());
  CHECK(r.all().find("materials.both.E") != std::string::npos);
  CHECK(r.all().find("gird: unknown key (did you mean \"grid\"?)") != std::string::npos);
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "wrote: " << join(changes(before, s.snapshot())));
}

TEST_CASE("a solve stopped short of its tolerance exits with status 3, naming its residual, and says so in summary") {
  // The test hook FRETWEAR_NORMAL_MAX_ITERATIONS caps the normal solve at two iterations: no real scene fails to
  // converge on demand. The user's files beside the scene are left as they were.
  Scratch s;
  s.write("s.json", kGood);
  s.write("notes.txt", "mine");
  const Outcome r = s.fretwear({"run", "s.json"}, {{"FRETWEAR_NORMAL_MAX_ITERATIONS", "2"}});
  CHECK_MESSAGE(r.exited(kNotConverged), r.describe());
  CHECK(r.err.find("normal contact: the solve stopped (max_iterations) with residual") != std::string::npos);
  const fs::path dir = s.work / "output" / "cli";
  const json summary = json::parse(std::ifstream(dir / "summary.json"));
  CHECK(summary["status"] == "not_converged");
  CHECK(summary["message"].get<std::string>().find("residual") != std::string::npos);
  std::vector<std::string> written;
  for (const auto& e : fs::directory_iterator(dir)) written.push_back(e.path().filename().string());
  std::sort(written.begin(), written.end());
  CHECK(written == std::vector<std::string>{".fretwear", "summary.json"});  // the folder's mark and the summary
  CHECK(fretwear::test::read_file(s.work / "notes.txt") == "mine");
  // Without the cap the same scene runs.
  const Outcome again = s.fretwear({"run", "s.json", "-q"});
  CHECK_MESSAGE(again.exited(kDone), again.describe());
}

TEST_CASE("file problems exit with status 2 and write nothing") {
  Scratch s;
  fs::create_directory(s.work / "adir.json");
  s.write("syntax.json", "{\"name\": ");
  s.write("bytes.json", "{\"name\": \"\xff\xfe\"}");
  for (const auto& [scene, said] : {std::pair{"missing.json", "no such file"}, {"adir.json", "is a directory"},
                                    {"syntax.json", "not valid JSON"}, {"bytes.json", "UTF-8"}}) {
    CAPTURE(scene);
    const Outcome r = s.fretwear({"run", scene});
    CHECK_MESSAGE(r.exited(kInvalid), r.describe());
    CHECK(r.all().find(said) != std::string::npos);
  }
  fs::remove(s.work / "adir.json");
  CHECK(!fs::exists(s.work / "output"));
}

// `fretwear ARGS < file`, the file given as standard input by a shell (the words reach the program as they are).
Outcome with_stdin(const Scratch& s, const std::vector<std::string>& args, const std::string& file,
                   const fretwear::test::Env& env = {}) {
  fretwear::test::Command command{{"/bin/sh", "-c", "f=$1; shift; exec \"$@\" < \"$f\"", "sh", file, FRETWEAR_EXE}};
  command.words.insert(command.words.end(), args.begin(), args.end());
  return fretwear::test::run_program(command, s.work, env);
}

TEST_CASE("the scene - is read from standard input, and a pipe or a device given by its path is refused") {
  Scratch s;
  s.write("s.json", kGood);
  const Outcome valid = with_stdin(s, {"validate", "-"}, "s.json");
  CHECK_MESSAGE(valid.exited(kDone), valid.describe());
  CHECK(valid.out.find("standard input: valid scene \"cli\"") != std::string::npos);
  const Outcome ran = with_stdin(s, {"run", "-", "-q"}, "s.json");
  CHECK_MESSAGE(ran.exited(kDone), ran.describe());
  CHECK(fs::exists(s.work / "output" / "cli" / "summary.json"));
  // Without a name of its own the scene is "stdin", and its results go to output/stdin.
  json unnamed = json::parse(kGood);
  unnamed.erase("name");
  s.write("unnamed.json", unnamed.dump());
  const Outcome named = with_stdin(s, {"run", "-", "-q"}, "unnamed.json");
  CHECK_MESSAGE(named.exited(kDone), named.describe());
  CHECK(fs::exists(s.work / "output" / "stdin" / "summary.json"));
  // A wear run stopped (a Ctrl-C after two steps) tells how to resume it: the same scene on standard input again.
  s.write("wear.json", wear_scene().dump());
  const Outcome stopped = with_stdin(s, {"run", "-", "-q"}, "wear.json", {{"FRETWEAR_STOP_AT_STEP", "2"}});
  CHECK_MESSAGE(stopped.exited(kInterrupted), stopped.describe());
  CHECK(stopped.err.find("continue with: fretwear run --resume - (the same scene on standard input)") !=
        std::string::npos);
  const Outcome resumed = with_stdin(s, {"run", "--resume", "-"}, "wear.json");
  CHECK_MESSAGE(resumed.exited(kDone), resumed.describe());
  CHECK(resumed.err.find("resuming at cycle") != std::string::npos);
  // Bad text from standard input is named so, and nothing is written.
  s.write("cut.json", "{\"name\": ");
  const Snapshot before = fretwear::test::snapshot(s.work);
  const Outcome cut = with_stdin(s, {"run", "-"}, "cut.json");
  CHECK_MESSAGE(cut.exited(kInvalid), cut.describe());
  CHECK(cut.err.find("standard input: not valid JSON") != std::string::npos);
  // Nothing on standard input is said so (the runner's own standard input is /dev/null).
  const Outcome empty = s.fretwear({"validate", "-"});
  CHECK_MESSAGE(empty.exited(kInvalid), empty.describe());
  CHECK(empty.err.find("standard input: is empty; give the scene on it") != std::string::npos);
  // A sweep's ranks each read the scene, which standard input cannot give them.
  const Outcome sweep = with_stdin(s, {"sweep", "-", "--vary", "friction=0.3,0.4"}, "s.json");
  CHECK_MESSAGE(sweep.exited(kInvalid), sweep.describe());
  CHECK(sweep.err.find("give the scene's file") != std::string::npos);
  // A named pipe is refused at once, without waiting for a writer, and told how to give a scene on standard input.
  REQUIRE(::mkfifo((s.work / "pipe.json").c_str(), 0600) == 0);
  const Outcome pipe = s.fretwear({"validate", "pipe.json"}, {}, 20.0);
  CHECK_MESSAGE(pipe.exited(kInvalid), pipe.describe());
  CHECK(pipe.err.find("is not a regular file (a pipe or a device); give a scene file, or - to read") !=
        std::string::npos);
  fs::remove(s.work / "pipe.json");
  CHECK(changes(before, fretwear::test::snapshot(s.work)).empty());
}

TEST_CASE("an unwritable output folder is reported before any work, with status 2") {
  Scratch s;
  s.write("s.json", std::string(kGood).replace(std::string(kGood).find("\"grid\""), 6,
                                               "\"output\": {\"dir\": \"/proc/fretwear\"}, \"grid\""));
  const Outcome r = s.fretwear({"run", "s.json"});
  CHECK_MESSAGE(r.exited(kInvalid), r.describe());
  CHECK(r.all().find("output.dir") != std::string::npos);
}

TEST_CASE("a stress map of millions of points is estimated before it runs, by validate and by run") {
  // 2001 x 2001 points a phase under the default Hertz cycle at 1024 cells: minutes of strip-load sums. The estimate
  // times a column, so it is said before any map is computed; the default 161 x 82 map is not worth a word.
  Scratch s;
  const std::string big = R"({"name": "big", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 1024}, "effects": {"tangential": {}, "stress": {"nx": 2001, "ny": 2000}}})";
  s.write("big.json", big);
  const Outcome validated = s.fretwear({"validate", "big.json"});
  CHECK_MESSAGE(validated.exited(kDone), validated.describe());
  CHECK_MESSAGE(validated.all().find("its stress maps will take about") != std::string::npos, validated.all());
  s.write("small.json", R"({"name": "small", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 1024}, "effects": {"tangential": {}, "stress": {}}})");
  const Outcome small = s.fretwear({"validate", "small.json"});
  CHECK_MESSAGE(small.exited(kDone), small.describe());
  CHECK(small.all().find("stress maps") == std::string::npos);
  // run says it on stderr before solving; stopped there by the test hook, it writes nothing.
  const Outcome run = s.fretwear({"run", "big.json"}, {{"FRETWEAR_STOP_IN_STAGE", "stress"}});
  CHECK(run.err.find("the stress maps (2001 x 2001 points) will take about") != std::string::npos);
  CHECK(!fs::exists(s.work / "output" / "big"));
}

TEST_CASE("a wear run under load.blocks reports its progress against all its cycles, naming the block") {
  // Each block's end is not the run's: the lines count to the blocks' sum, and a log (stderr not a terminal) gets a
  // line at every tenth of it, through every block.
  Scratch s;
  json scene = json::parse(read_file(fs::path(FRETWEAR_SOURCE_DIR) / "examples" / "hertz_wear_blocks.json"));
  scene["output"] = {{"dir", "out"}, {"plots", false}};
  s.write("blocks.json", scene.dump());
  const Outcome r = s.fretwear({"run", "blocks.json"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  std::vector<std::string> lines;
  std::istringstream in(r.err);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("wear: ", 0) == 0) lines.push_back(line);
  REQUIRE(lines.size() >= 10);
  for (const std::string& line : lines) CHECK_MESSAGE(line.find(" / 10000 cycles (load.blocks[") != std::string::npos, line);
  for (const char* block : {"(load.blocks[0] of 3)", "(load.blocks[1] of 3)", "(load.blocks[2] of 3)"})
    CHECK_MESSAGE(r.err.find(block) != std::string::npos, r.err);
  CHECK_MESSAGE(lines.back().rfind("wear: 10000 / 10000 cycles (load.blocks[2] of 3)", 0) == 0, lines.back());
}

TEST_CASE("the stress, crack and life stages report their parts once they run for a few seconds") {
  // Worn, with maps, SWT, cracks and a life: 9 records. FRETWEAR_STAGE_QUIET_S=0 shows the lines of stages that take
  // milliseconds; by default (2 s) this run shows none of them.
  Scratch s;
  json scene = json::parse(read_file(fs::path(FRETWEAR_SOURCE_DIR) / "examples" / "life_slip_amplitude.json"));
  scene["grid"]["cells"] = 256;
  scene["effects"]["stress"] = {{"nx", 41}, {"ny", 20}};
  scene["effects"]["crack"] = {{"at", "trailing_edge"}, {"lengths", {1e-5, 2e-5}}};
  scene["output"] = {{"dir", "out"}, {"plots", false}};
  s.write("life.json", scene.dump());
  const Outcome r = s.fretwear({"run", "life.json"}, {{"FRETWEAR_STAGE_QUIET_S", "0"}});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const json summary = json::parse(read_file(s.work / "out" / "summary.json"));
  const int records = summary["wear"]["records"].get<int>();  // the unworn state and 8 records
  REQUIRE(records == 9);
  // Each state's top and bottom maps, the last on all 41 columns and 21 rows (the surface and 20 below it), the
  // earlier ones on every second (21 and 11).
  const int columns = (records - 1) * 2 * 21 + 2 * 41, rows = (records - 1) * 11 + 21;
  const std::pair<std::string, int> parts[] = {{"stress: ", columns}, {"stress: ", rows}, {"crack: ", records},
                                               {"life: ", 2}};
  const char* units[] = {"map columns", "rows of the SWT maps", "records", "parts (initiation, growth)"};
  for (int k = 0; k < 4; ++k) {
    const std::string suffix = fmt::format(" / {} {}, ", parts[k].second, units[k]);
    std::vector<double> done;
    std::istringstream in(r.err);
    for (std::string line; std::getline(in, line);)
      if (line.rfind(parts[k].first, 0) == 0 && line.find(suffix) != std::string::npos)
        done.push_back(std::stod(line.substr(parts[k].first.size())));
    INFO(units[k], "\n", r.err);
    REQUIRE(!done.empty());
    CHECK(std::is_sorted(done.begin(), done.end()));
    CHECK(int(done.size()) >= std::min(10, parts[k].second));  // in a log, a line at each tenth of the stage
    CHECK(done.back() == parts[k].second);  // the stage's last line: all of it done
  }
  const Outcome quiet = s.fretwear({"run", "life.json"});
  REQUIRE_MESSAGE(quiet.exited(kDone), quiet.describe());
  for (const char* stage : {"\nstress: ", "\ncrack: ", "\nlife: "})
    CHECK_MESSAGE(quiet.err.find(stage) == std::string::npos, quiet.err);
}

TEST_CASE("a run with large stress maps says it is writing them before it does, and a small one does not") {
  // 2 phases of 801 x 401 points: 642 402, past the 500 000 that take seconds to write.
  Scratch s;
  const std::string scene = R"({"name": "maps", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 64}, "output": {"dir": "out", "plots": false}, "effects": {"tangential": {}, "stress": )";
  s.write("large.json", scene + R"({"nx": 801, "ny": 400}}})");
  s.write("small.json", scene + R"({}}})");
  const Outcome large = s.fretwear({"run", "large.json"});
  REQUIRE_MESSAGE(large.exited(kDone), large.describe());
  CHECK_MESSAGE(large.err.find("fretwear: maps: writing the results (642402 points of stress maps) to out/") !=
                    std::string::npos,
                large.err);
  const Outcome small = s.fretwear({"run", "small.json"});
  REQUIRE_MESSAGE(small.exited(kDone), small.describe());
  CHECK_MESSAGE(small.err.find("writing the results") == std::string::npos, small.err);
}

TEST_CASE("validate writes nothing, defaults prints a valid scene, --version, and usage errors exit 2") {
  Scratch s;
  s.write("s.json", kGood);
  const Outcome validated = s.fretwear({"validate", "s.json"});
  CHECK_MESSAGE(validated.exited(kDone), validated.describe());
  CHECK(validated.all().find("valid scene") != std::string::npos);
  CHECK(!fs::exists(s.work / "output"));
  const Outcome defaults = s.fretwear({"defaults"});
  CHECK_MESSAGE(defaults.exited(kDone), defaults.describe());
  s.write("d.json", defaults.out);
  CHECK(s.fretwear({"validate", "d.json"}).exited(kDone));
  const Outcome version = s.fretwear({"--version"});
  CHECK_MESSAGE(version.exited(kDone), version.describe());
  CHECK(version.all().find("fretwear ") == 0);
  CHECK(s.fretwear({"run"}).exited(kInvalid));
  CHECK(s.fretwear({"frobnicate"}).exited(kInvalid));
  CHECK(s.fretwear({"--help"}).exited(kDone));
}

TEST_CASE("convergence writes its table into the convergence subfolder of output.dir") {
  Scratch s;
  s.write("s.json", kGood);
  const Outcome r = s.fretwear({"convergence", "s.json", "--from", "128", "--to", "512"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  CHECK(r.all().find("errors against hertz") != std::string::npos);
  std::ifstream csv(s.work / "output" / "cli" / "convergence" / "convergence.csv");
  std::string line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 4);  // header and 128, 256, 512
}

TEST_CASE("convergence with -q prints nothing, and writes its table") {
  Scratch s;
  s.write("s.json", kGood);
  const Outcome r = s.fretwear({"convergence", "s.json", "--from", "128", "--to", "256", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  CHECK(r.all().empty());
  CHECK(std::filesystem::exists(s.work / "output" / "cli" / "convergence" / "convergence.csv"));
}

TEST_CASE("convergence refuses a range of grids that holds none, with the earlier results kept") {
  // The grids are the powers of two from bit_ceil(--from) to --to: --from above --to, or rounding up past it,
  // leaves none, which is the user's mistake (exit 2, the options named), not an empty table over the last one.
  Scratch s;
  s.write("s.json", kGood);
  REQUIRE(s.fretwear({"convergence", "s.json", "--from", "128", "--to", "256", "-q"}).exited(kDone));
  const Snapshot before = s.snapshot();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--from", "512", "--to", "128"}, "--from 512 is above --to 128"},
      {{"--from", "200", "--to", "250"}, "--from 200 rounds up to 256 cells"},
  };
  for (const auto& [range, says] : cases) {
    INFO(says);
    std::vector<std::string> args = {"convergence", "s.json"};
    args.insert(args.end(), range.begin(), range.end());
    const Outcome r = s.fretwear(args);
    CHECK_MESSAGE(r.exited(kInvalid), r.describe());
    CHECK_MESSAGE(r.err.find(says) != std::string::npos, r.describe());
    CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "changed: " << join(changes(before, s.snapshot())));
  }
}

TEST_CASE("a wear run writes wear_history.csv, profiles.csv and the wear plots") {
  Scratch s;
  s.write("w.json", R"({"name": "wear", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 256}, "effects": {"wear": {"k": 1e-12, "cycles": 1e5, "record": 4}}})");
  const Outcome r = s.fretwear({"run", "w.json", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const fs::path dir = s.work / "output" / "wear";
  auto lines = [](const fs::path& p) {
    std::vector<std::string> v;
    std::ifstream in(p);
    for (std::string line; std::getline(in, line);) v.push_back(line);
    return v;
  };
  const auto history = lines(dir / "wear_history.csv");
  REQUIRE(history.size() == 6);  // the header, record 0 and the 4 asked for
  CHECK(history[0] == "cycles,worn_area_m2,max_depth_m,fraction_of_asymptote,stick_left_m,stick_right_m,"
                      "contact_left_m,contact_right_m,p_max_Pa");
  CHECK(history[1].rfind("0,0,0,0,", 0) == 0);  // record 0: nothing worn yet
  CHECK(history[5].rfind("100000,", 0) == 0);   // the last record is the last cycle
  // The summary's final worn area is the last row's.
  const json summary = json::parse(std::ifstream(dir / "summary.json"));
  CHECK(std::stod(history[5].substr(history[5].find(',') + 1)) ==
        fretwear::test::rel(summary["wear"]["worn_area"].get<double>(), 1e-9));
  // profiles.csv: one row per record and cell, then the asymptote (cycles = inf).
  const auto profiles = lines(dir / "profiles.csv");
  REQUIRE(profiles.size() == 1 + 6 * 256);
  CHECK(profiles[0] == "cycles,x_m,gap0_m,wear_m,wear_pad_m,wear_specimen_m,p_Pa,slip_per_cycle_m");
  CHECK(profiles[1 + 5 * 256].rfind("inf,", 0) == 0);
  CHECK(profiles.back().rfind("inf,", 0) == 0);
  if (!on_path("gnuplot").empty()) {
    for (const char* f : {"wear.gp", "wear_depth.svg", "wear_depth.png", "wear_pressure.svg", "wear_pressure.png",
                          "wear_stick_zone.svg", "wear_stick_zone.png", "wear_area.svg", "wear_area.png"})
      CHECK_MESSAGE(fs::exists(dir / f), f);
    CHECK(!fs::exists(dir / "gnuplot.log"));  // gnuplot said nothing: no warnings from the script
    std::ifstream html(dir / "index.html");
    const std::string index(std::istreambuf_iterator<char>(html), {});
    CHECK(index.find("wear_area.svg") != std::string::npos);
    CHECK(index.find("profiles.csv") != std::string::npos);
  }
}

TEST_CASE("run reports each stage that ran, and --verbose adds how it was solved and where the results are") {
  Scratch s;
  s.write("s.json", R"({"name": "cli", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
    "load": {"P": 1e5, "Q": {"ratio": 0.5}, "bulk_stress": {"amplitude": 1e8}}, "grid": {"cells": 256},
    "effects": {"wear": {"law": "archard", "k": 1e-12, "cycles": 1e4, "record": 3}, "stress": {"nx": 21, "ny": 11},
                "crack": {"lengths": [1e-5, 2e-5]}}})");
  const Outcome plain = s.fretwear({"run", "s.json"});
  REQUIRE_MESSAGE(plain.exited(kDone), plain.describe());
  for (const char* line : {"cli: contact [", "  cycle (partial_slip, analogy route)", "  wear (archard, implicit stepper, analogy route)",
                           "  stress at the top of the cycle", "  crack at x = ", "results in "})
    CHECK_MESSAGE(plain.all().find(line) != std::string::npos, line);
  CHECK(plain.all().find("timings") == std::string::npos);
  const Outcome verbose = s.fretwear({"run", "s.json", "-v"});
  REQUIRE_MESSAGE(verbose.exited(kDone), verbose.describe());
  for (const char* line : {"  grid: 256 cells", "  against the closed form (hertz)", "  wear asymptote (computed directly)",
                           "  wear steps: ", "  timings (s):", "  plots: pressure.svg"})
    CHECK_MESSAGE(verbose.all().find(line) != std::string::npos, line);
  // Quiet: nothing on stdout; on stderr only the warnings (this run wears to its limit, where the stress maxima sit
  // at the stick zone's singular ends).
  const Outcome quiet = s.fretwear({"run", "s.json", "-q"});
  REQUIRE_MESSAGE(quiet.exited(kDone), quiet.describe());
  CHECK(quiet.out.empty());
  std::istringstream err(quiet.err);
  for (std::string line; std::getline(err, line);) CHECK_MESSAGE(line.rfind("warning: ", 0) == 0, line);
}

TEST_CASE("the life line gives a failure's total, and says a run out lasts beyond cycles_max") {
  Scratch s;
  const Outcome defaults = s.fretwear({"defaults", "--effect", "life"});
  REQUIRE_MESSAGE(defaults.exited(kDone), defaults.describe());
  json scene = json::parse(defaults.out);
  scene["grid"]["cells"] = 256;
  s.write("out.json", scene.dump());
  const Outcome out = s.fretwear({"run", "out.json"});
  REQUIRE_MESSAGE(out.exited(kDone), out.describe());
  CHECK(out.out.find("  life (runout): beyond 1e+09 cycles (effects.life.cycles_max); initiation after ") !=
        std::string::npos);
  // A bulk stress of 300 MPa starts a crack and grows it to a_final within cycles_max.
  scene["load"]["bulk_stress"] = {{"amplitude", 3e8}};
  s.write("fails.json", scene.dump());
  const Outcome fails = s.fretwear({"run", "fails.json"});
  REQUIRE_MESSAGE(fails.exited(kDone), fails.describe());
  const json life = json::parse(read_file(s.work / "output" / "hertz_life" / "summary.json"))["life"];
  REQUIRE(life["fate"] == "failure");
  CHECK(fails.out.find(fmt::format("  life (failure): total {:.4g} cycles; initiation after ",
                                   life["total_cycles"].get<double>())) != std::string::npos);
}

TEST_CASE("the report says a peak pressure at a singular edge is a grid measure, and a bounded one plainly") {
  // A sharp flat punch's p_max is its corner cell's share of an unbounded pressure (summary: contact.p_max_singular).
  Scratch s;
  const std::string materials = R"("materials": {"both": {"E": 2e11, "nu": 0.3}}, "load": {"P": 2e5},)";
  s.write("punch.json", R"({"name": "punch", )" + materials + R"( "profile": {"type": "flat", "b": 5e-4},
    "grid": {"cells": 256}})");
  s.write("hertz.json", R"({"name": "hertz", )" + materials + R"( "profile": {"type": "cylinder", "R": 0.01},
    "grid": {"cells": 256}})");
  const Outcome punch = s.fretwear({"run", "punch.json"});
  REQUIRE_MESSAGE(punch.exited(kDone), punch.describe());
  CHECK_MESSAGE(punch.out.find(" Pa at a singular edge (a grid measure) (") != std::string::npos, punch.describe());
  const Outcome hertz = s.fretwear({"run", "hertz.json"});
  REQUIRE_MESSAGE(hertz.exited(kDone), hertz.describe());
  CHECK_MESSAGE(hertz.out.find("singular") == std::string::npos, hertz.describe());
}

TEST_CASE("a gross-slip wear run with each body in its own frame reports each body's scar on stdout") {
  // Sliding 8.8 µm each way on cells of 7.8 µm: the specimen's scar is worn in its own frame (engine/body_frames.hpp),
  // wider than the pad's by the stroke, and the line says both.
  Scratch s;
  s.write("s.json", R"({"name": "frames", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
    "load": {"P": 1e5, "control": "displacement", "delta": 1e-5}, "grid": {"cells": 128, "window": [-5e-4, 5e-4]},
    "effects": {"wear": {"law": "archard", "k": 2e-15, "cycles": 1e4}}})");
  const Outcome run = s.fretwear({"run", "s.json"});
  REQUIRE_MESSAGE(run.exited(kDone), run.describe());
  const std::size_t at = run.out.find("  each body in its own frame (");
  REQUIRE_MESSAGE(at != std::string::npos, run.out);
  const std::string line = run.out.substr(at, run.out.find('\n', at) - at);
  CHECK_MESSAGE(line.find("pad ") != std::string::npos, line);
  CHECK_MESSAGE(line.find("specimen ") != std::string::npos, line);
  const json summary = json::parse(std::ifstream(s.work / "output" / "frames" / "summary.json"));
  const json& bodies = summary["wear"]["bodies"];
  CHECK(bodies["frames"] == "own");
  for (const char* body : {"pad", "specimen"})
    CHECK_MESSAGE(line.find(fmt::format("{} {:.4e} m deep", body, bodies[body]["max_depth"].get<double>())) !=
                      std::string::npos,
                  line);
}

TEST_CASE("several contact and stick zones are reported zone by zone on stdout and in the sweep's map") {
  // Two cylinders 0.4 mm apart under one pad (paper 002's two-zone case): two contacts, a stick zone in each.
  const json scene = {{"name", "two"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "envelope"},
                                   {"terms", {{{"type", "cylinder"}, {"R", 0.01}, {"offset_x", -0.2e-3}},
                                              {{"type", "cylinder"}, {"R", 0.01}, {"offset_x", 0.2e-3}}}}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
                      {"grid", {{"cells", 512}}},
                      {"effects", {{"tangential", json::object()}}}};  // with plots: the sweep draws its map
  Scratch s;
  s.write("two.json", scene.dump());
  const Outcome r = s.fretwear({"run", "two.json"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  CHECK(r.out.find("contact in 2 zones [") != std::string::npos);
  CHECK(r.out.find("stick zones [") != std::string::npos);
  const json summary = json::parse(std::ifstream(s.work / "output" / "two" / "summary.json"));
  REQUIRE(summary["cycle"]["stick_zones"].size() == 2);

  // The sweep's map value is the stick zones' share of the contact zones' width, the gap between them left out.
  const Outcome sw = s.fretwear({"sweep", "two.json", "--vary", "load.Q.ratio=0.5", "-q"});
  REQUIRE_MESSAGE(sw.exited(kDone), sw.describe());
  double stick = 0.0, contact = 0.0;
  for (const auto& z : summary["cycle"]["stick_zones"]) stick += z[1].get<double>() - z[0].get<double>();
  for (const auto& z : summary["contact"]["zones"]) contact += z[1].get<double>() - z[0].get<double>();
  std::ifstream map(s.work / "output" / "two" / "sweep" / "sweep_map.dat");
  double ratio = 0.0, unused = 0.0, value = 0.0;
  map >> ratio >> unused >> value;
  REQUIRE(map.good());
  CHECK(value == fretwear::test::rel(stick / contact, 1e-12));
  const std::string csv_header = [&] {
    std::string h;
    std::getline(std::ifstream(s.work / "output" / "two" / "sweep" / "sweep.csv"), h);
    return h;
  }();
  CHECK(csv_header.find("cycle.stick_zones") != std::string::npos);
}

TEST_CASE("defaults writes every effect's keys, --effect one of them, and each is a valid scene") {
  Scratch s;
  const Outcome all = s.fretwear({"defaults"});
  REQUIRE_MESSAGE(all.exited(kDone), all.describe());
  const json scene = json::parse(all.out);
  for (const char* effect : {"tangential", "wear", "stress", "crack", "life"})
    CHECK_MESSAGE(scene["effects"].contains(effect), effect);
  CHECK(scene["effects"]["wear"].contains("stepper"));          // a default written out
  CHECK(scene["effects"]["life"]["growth"].contains("dK_th"));  // likewise
  for (const char* effect : {"normal", "tangential", "wear", "stress", "crack", "life"}) {
    const Outcome one = s.fretwear({"defaults", "--effect", effect});
    REQUIRE_MESSAGE(one.exited(kDone), one.describe());
    const json j = json::parse(one.out);
    CHECK(j["effects"].size() == (std::string(effect) == "normal" ? 0u : std::string(effect) == "tangential" ? 1u : 2u));
    s.write("one.json", one.out);
    const Outcome valid = s.fretwear({"validate", "one.json", "-q"});
    CHECK_MESSAGE(valid.exited(kDone), effect, ": ", valid.describe());
  }
  const Outcome bad = s.fretwear({"defaults", "--effect", "fatigue"});
  CHECK(bad.exited(kInvalid));
  CHECK(bad.err.find("\"fatigue\" is not an effect") != std::string::npos);
}
