// The fretwear program as a user meets it: exit status, what is written and what is not.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

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

TEST_CASE("convergence writes its table") {
  TempDir tmp;
  write(tmp.path / "s.json", kGood);
  std::string out;
  REQUIRE(run_cli(tmp.path, "convergence s.json --from 128 --to 512 -q", &out) == 0);
  CHECK(out.find("errors against hertz") != std::string::npos);
  std::ifstream csv(tmp.path / "output" / "cli" / "convergence.csv");
  std::string line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 4);  // header and 128, 256, 512
}
