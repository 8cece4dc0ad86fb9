// run_sweep: the product of variations, run on threads, one folder per run, the table and the map. The command
// `fretwear sweep` is tried in tests/system/test_sweep_cli.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "engine/scene.hpp"
#include "engine/sweep.hpp"

namespace fs = std::filesystem;
using namespace fretwear;
using nlohmann::json;

namespace {
struct Scratch {
  fs::path path = fs::temp_directory_path() / ("fretwear-sweep-" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(path); }
  ~Scratch() { fs::remove_all(path); }
};

fs::path write_scene(const fs::path& dir) {
  const json scene = {{"name", "sw"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
                      {"grid", {{"cells", 256}}},
                      {"effects", {{"tangential", json::object()}}},
                      {"output", {{"dir", (dir / "out").string()}, {"plots", false}}}};
  std::ofstream(dir / "sw.json") << scene.dump();
  return dir / "sw.json";
}
}  // namespace

TEST_CASE("a 2 x 2 sweep on two threads into output.dir/sweep: runs, folders, table, stick share sqrt(1 - Q/fP)") {
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  const SweepResult r = run_sweep(scene, {parse_variation("load.Q.ratio=0.36,0.64"), parse_variation("load.P=1e5,4e5")},
                                  2, nullptr);
  REQUIRE(r.runs.size() == 4);
  for (const SweepRun& run : r.runs) {
    CAPTURE(run.name);
    REQUIRE(run.status == 0);
    CHECK(fs::exists(scratch.path / "out" / "sweep" / "runs" / run.name / "summary.json"));
    // Hertz: c/a = sqrt(1 − Q/fP) at any P; the edges are located to a fraction of a cell (1/170 of the contact).
    const double ratio = run.values[0].get<double>();
    const auto stick = run.summary["cycle"]["stick_zone"], extent = run.summary["contact"]["extent"];
    const double share = (stick[1].get<double>() - stick[0].get<double>()) /
                         (extent[1].get<double>() - extent[0].get<double>());
    CHECK(std::abs(share - std::sqrt(1.0 - ratio)) < 0.01);
  }
  std::ifstream csv(scratch.path / "out" / "sweep" / "sweep.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  CHECK(lines == 5);
  CHECK(fs::exists(scratch.path / "out" / "sweep" / "sweep.json"));
}

TEST_CASE("a sweep with an invalid variant names it and runs nothing") {
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  try {
    run_sweep(scene, {parse_variation("load.P=1e5,-1")}, 1, nullptr);
    FAIL("the sweep should be refused");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find("sw__load.P_-1: load.P") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(scratch.path / "out"));
  CHECK_THROWS_AS(parse_variation("load.P"), InputError);
}
