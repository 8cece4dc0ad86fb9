// `fretwear sweep` on the command line: the runs, the table, the exit status. What a sweep computes is checked in
// process by tests/unit/test_sweep.cpp.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// The sweep scene of tests/unit/test_sweep.cpp, its results under output.dir = <working folder>/out.
fs::path write_scene(const Scratch& s) {
  const json scene = {{"name", "sw"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
                      {"grid", {{"cells", 256}}},
                      {"effects", {{"tangential", json::object()}}},
                      {"output", {{"dir", (s.work / "out").string()}, {"plots", false}}}};
  return s.write("sw.json", scene.dump());
}

}  // namespace

TEST_CASE("fretwear sweep on the command line: runs, table, exit 0, and a bad --vary exits 2") {
  Scratch s;
  const std::string scene = write_scene(s).string();
  const Outcome r = s.fretwear({"sweep", scene, "--vary", "load.Q.ratio=0.2,0.4", "--jobs", "2", "-q"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  CHECK(fs::exists(s.work / "out" / "sweep" / "sweep.csv"));
  const Outcome bad = s.fretwear({"sweep", scene, "--vary", "load.Q.ratio", "-q"});
  CHECK_MESSAGE(bad.exited(kInvalid), bad.describe());
}

TEST_CASE("a sweep of a scene with a life effect tabulates the lives and draws them against the varied key") {
  Scratch s;
  const json scene = {{"name", "life"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}, {"bulk_stress", {{"amplitude", 2.5e8}}}}},
                      {"grid", {{"cells", 256}}},
                      {"effects",
                       {{"tangential", json::object()},
                        {"life", {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52}}},
                                  {"growth", {{"C", 5e-30}, {"m", 3.0}, {"a_initial", 2e-5}, {"a_final", 1e-3}}}}}}},
                      {"output", {{"dir", (s.work / "out").string()}}}};
  s.write("life.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", "life.json", "--vary", "load.Q.ratio=0.5,0.7", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  std::string header, row;
  std::ifstream csv(s.work / "out" / "sweep" / "sweep.csv");
  std::getline(csv, header);
  std::getline(csv, row);
  CHECK(header.find("life.total_cycles") != std::string::npos);
  CHECK(header.find("life.fate") != std::string::npos);
  CHECK(row.find("failure") != std::string::npos);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0)
    CHECK(fs::exists(s.work / "out" / "sweep" / "sweep_life.png"));
}
