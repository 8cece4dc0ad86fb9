// A worn run with stresses, as a user runs it: fatigue.csv and ruiz.csv carry the cycles of every wear record in
// their first column, the unworn state first and the last record last.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "support.hpp"
#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// The first cell of every data row of a CSV file, and its header.
std::vector<std::string> first_column(const fs::path& file, std::string& header) {
  std::ifstream in(file);
  std::getline(in, header);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line.substr(0, line.find(',')));
  return out;
}

}  // namespace

TEST_CASE("run with wear and stress writes the cycles of every record in fatigue.csv and ruiz.csv") {
  Scratch s;
  json scene = wear_scene();
  scene["name"] = "records";
  scene["effects"]["wear"]["record"] = json::array({1e3, 1e4});
  scene["effects"]["stress"] = {{"nx", 21}, {"ny", 5}};
  s.write("s.json", scene.dump());
  const Outcome r = s.fretwear({"run", "-q", "s.json"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const fs::path dir = s.work / "output" / "records";
  for (const char* file : {"fatigue.csv", "ruiz.csv"}) {
    CAPTURE(file);
    std::string header;
    const std::vector<std::string> cycles = first_column(dir / file, header);
    CHECK(header.rfind("cycles,x_m,", 0) == 0);
    REQUIRE_FALSE(cycles.empty());
    CHECK(cycles.front() == "0");
    CHECK(cycles.back() == "10000");
    CHECK(std::find(cycles.begin(), cycles.end(), "1000") != cycles.end());
  }
  const json summary = json::parse(std::ifstream(dir / "summary.json"));
  CHECK(summary["stress"]["cycles"].get<double>() == 1e4);
}
