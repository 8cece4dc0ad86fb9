// The fretwear program as a user meets it: exit status, what is written and what is not.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "support.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("fretwear-cli-" + std::to_string(::getpid()) + "-" + std::to_string(rand()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

// Runs the program with args inside dir; returns its exit status, stdout+stderr in output.
int run_cli(const fs::path& dir, const std::string& args, std::string* output = nullptr) {
  const fs::path log = dir / "cli.log";
  const std::string cmd = "cd '" + dir.string() + "' && '" FRETWEAR_EXE "' " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  if (output) {
    std::ifstream in(log);
    output->assign(std::istreambuf_iterator<char>(in), {});
  }
  fs::remove(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kGood = R"({"name": "cli", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "grid": {"cells": 256}})";

// Entries in dir other than the scene files the test wrote.
int written(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() != ".json";
  return n;
}

}  // namespace

TEST_CASE("run writes summary, resolved scene, CSV, plots and index into output/<name>") {
  TempDir tmp;
  write(tmp.path / "s.json", kGood);
  std::string out;
  REQUIRE(run_cli(tmp.path, "run s.json", &out) == 0);
  const fs::path dir = tmp.path / "output" / "cli";
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
  fs::copy_file(dir / "scene.resolved.json", tmp.path / "again.json");
  REQUIRE(run_cli(tmp.path, "run again.json -q") == 0);
  const json again = json::parse(std::ifstream(dir / "summary.json"));
  // The same window to the last digit JSON keeps; the cell width is recomputed from it, so agreement is to
  // round-off of the grid, far inside the solver's tolerance.
  for (int k = 0; k < 2; ++k)
    CHECK(again["contact"]["extent"][k].get<double>() ==
          fretwear::test::rel(summary["contact"]["extent"][k].get<double>(), 1e-10));
  // No staging folder is left behind.
  for (const auto& e : fs::directory_iterator(tmp.path / "output"))
    CHECK(e.path().filename().string().find(".partial") == std::string::npos);
}

TEST_CASE("an invalid scene exits with status 2, names every problem and writes nothing") {
  TempDir tmp;
  write(tmp.path / "bad.json", R"({"name": "bad", "materials": {"both": {"E": -1, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "gird": {}})");
  std::string out;
  CHECK(run_cli(tmp.path, "run bad.json", &out) == 2);
  CHECK(out.find("materials.both.E") != std::string::npos);
  CHECK(out.find("gird: unknown key (did you mean \"grid\"?)") != std::string::npos);
  CHECK(written(tmp.path) == 0);
}

TEST_CASE("file problems exit with status 2 and write nothing") {
  TempDir tmp;
  fs::create_directory(tmp.path / "adir.json");
  write(tmp.path / "syntax.json", "{\"name\": ");
  write(tmp.path / "bytes.json", "{\"name\": \"\xff\xfe\"}");
  std::string out;
  CHECK(run_cli(tmp.path, "run missing.json", &out) == 2);
  CHECK(out.find("no such file") != std::string::npos);
  CHECK(run_cli(tmp.path, "run adir.json", &out) == 2);
  CHECK(out.find("is a directory") != std::string::npos);
  CHECK(run_cli(tmp.path, "run syntax.json", &out) == 2);
  CHECK(out.find("not valid JSON") != std::string::npos);
  CHECK(run_cli(tmp.path, "run bytes.json", &out) == 2);
  CHECK(out.find("UTF-8") != std::string::npos);
  fs::remove(tmp.path / "adir.json");
  CHECK(!fs::exists(tmp.path / "output"));
}

TEST_CASE("an unwritable output folder is reported before any work, with status 2") {
  TempDir tmp;
  write(tmp.path / "s.json", std::string(kGood).replace(std::string(kGood).find("\"grid\""), 6,
                                                        "\"output\": {\"dir\": \"/proc/fretwear\"}, \"grid\""));
  std::string out;
  CHECK(run_cli(tmp.path, "run s.json", &out) == 2);
  CHECK(out.find("output.dir") != std::string::npos);
}

TEST_CASE("validate writes nothing; defaults prints a valid scene; --version; usage errors exit 2") {
  TempDir tmp;
  write(tmp.path / "s.json", kGood);
  std::string out;
  CHECK(run_cli(tmp.path, "validate s.json", &out) == 0);
  CHECK(out.find("valid scene") != std::string::npos);
  CHECK(!fs::exists(tmp.path / "output"));
  CHECK(run_cli(tmp.path, "defaults", &out) == 0);
  write(tmp.path / "d.json", out);
  CHECK(run_cli(tmp.path, "validate d.json") == 0);
  CHECK(run_cli(tmp.path, "--version", &out) == 0);
  CHECK(out.find("fretwear ") == 0);
  CHECK(run_cli(tmp.path, "run") == 2);
  CHECK(run_cli(tmp.path, "frobnicate") == 2);
  CHECK(run_cli(tmp.path, "--help") == 0);
}

TEST_CASE("convergence writes its table into the convergence subfolder of output.dir") {
  TempDir tmp;
  write(tmp.path / "s.json", kGood);
  std::string out;
  REQUIRE(run_cli(tmp.path, "convergence s.json --from 128 --to 512 -q", &out) == 0);
  CHECK(out.find("errors against hertz") != std::string::npos);
  std::ifstream csv(tmp.path / "output" / "cli" / "convergence" / "convergence.csv");
  std::string line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 4);  // header and 128, 256, 512
}

TEST_CASE("a wear run writes wear_history.csv, profiles.csv and the wear plots") {
  TempDir tmp;
  write(tmp.path / "w.json", R"({"name": "wear", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 256}, "effects": {"wear": {"k": 1e-12, "cycles": 1e5, "record": 4}}})");
  std::string out;
  REQUIRE(run_cli(tmp.path, "run w.json -q", &out) == 0);
  const fs::path dir = tmp.path / "output" / "wear";
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
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
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

TEST_CASE("run reports each stage that ran; --verbose adds how it was solved and where the results are") {
  TempDir dir;
  write(dir.path / "s.json", R"({"name": "cli", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
    "load": {"P": 1e5, "Q": {"ratio": 0.5}, "bulk_stress": {"amplitude": 1e8}}, "grid": {"cells": 256},
    "effects": {"wear": {"law": "archard", "k": 1e-12, "cycles": 1e4, "record": 3}, "stress": {"nx": 21, "ny": 11},
                "crack": {"lengths": [1e-5, 2e-5]}}})");
  std::string out;
  REQUIRE(run_cli(dir.path, "run s.json", &out) == 0);
  for (const char* line : {"cli: contact [", "  cycle (partial_slip, analogy route)", "  wear (archard, implicit stepper)",
                           "  stress at the top of the cycle", "  crack at x = ", "results in "})
    CHECK_MESSAGE(out.find(line) != std::string::npos, line);
  CHECK(out.find("timings") == std::string::npos);
  REQUIRE(run_cli(dir.path, "run s.json -v", &out) == 0);
  for (const char* line : {"  grid: 256 cells", "  against the closed form (hertz)", "  wear asymptote (computed directly)",
                           "  wear steps: ", "  timings (s):", "  plots: pressure.svg"})
    CHECK_MESSAGE(out.find(line) != std::string::npos, line);
  REQUIRE(run_cli(dir.path, "run s.json -q", &out) == 0);
  CHECK(out.empty());
}
