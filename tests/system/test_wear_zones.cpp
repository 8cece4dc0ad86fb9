// A wear run on a contact of several zones reports each stick zone, not their hull: wear_stick_zones.csv (zone by
// zone), summary.json's wear.stick_zones_initial and _final, the stage's line on stdout, and wear.gp's plot of the
// stick zones against cycles, one pair of curves per zone.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "system/program.hpp"

using namespace fretwear::system_test;
using nlohmann::json;

namespace {

// Two cylinders (R = 10 mm) 2 mm apart on one pad, P = 100 kN/m, Q/fP = 0.5: two contact zones, a stick zone in each.
json two_zones(const fs::path& out) {
  return {{"name", "zones"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile",
           {{"type", "envelope"},
            {"terms", {{{"type", "cylinder"}, {"R", 0.01}, {"offset_x", -1e-3}},
                       {{"type", "cylinder"}, {"R", 0.01}, {"offset_x", 1e-3}}}}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
          {"grid", {{"cells", 2048}, {"window", {-1.3e-3, 1.3e-3}}}},
          {"effects", {{"wear", {{"law", "archard"}, {"k", 1e-12}, {"cycles", 1e5}, {"record", 4}}}}},
          {"output", {{"dir", out.string()}, {"plots", true}}}};
}

std::string text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("a wear run with two stick zones reports each: its table, its summary, its line and its plot") {
  Scratch s;
  const fs::path out = s.work / "out";
  const fs::path scene = s.write("zones.json", two_zones(out).dump());
  const Outcome r = s.fretwear({"run", scene.string()});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const json summary = json::parse(text(out / "summary.json"));
  const json& w = summary["wear"];
  REQUIRE(w["stick_zones_initial"].size() == 2);
  REQUIRE(w["stick_zones_final"].size() == 2);
  // The hull is the outer ends of the two.
  CHECK(w["stick_zone_final"][0] == w["stick_zones_final"][0][0]);
  CHECK(w["stick_zone_final"][1] == w["stick_zones_final"][1][1]);
  CHECK(w["stick_zones_final"][0][1].get<double>() < w["stick_zones_final"][1][0].get<double>());
  // The table: zone by zone, a row per record (the unworn state and the 4 asked for).
  std::ifstream table(out / "wear_stick_zones.csv");
  std::string line;
  std::getline(table, line);
  CHECK(line == "cycles,zone,stick_left_m,stick_right_m");
  std::vector<int> zones;
  while (std::getline(table, line)) zones.push_back(std::stoi(line.substr(line.find(',') + 1)));
  const std::size_t records = w["records"].get<std::size_t>();
  REQUIRE(zones.size() == 2 * records);
  for (std::size_t k = 0; k < zones.size(); ++k) CHECK(zones[k] == int(k / records));
  // stdout names both zones at the first and the last record.
  CHECK(r.out.find("stick zones [") != std::string::npos);
  // The plot: each zone's ends from the table, titled once.
  const std::string gp = text(out / "wear.gp");
  CHECK(gp.find("stick zones and contact extent against cycles") != std::string::npos);
  CHECK(gp.find("using ($2 == 0 && $1 > 0 ? $1 : NaN):($3*1e3)") != std::string::npos);
  CHECK(gp.find("using ($2 == 1 && $1 > 0 ? $1 : NaN):($4*1e3)") != std::string::npos);
  CHECK(fs::exists(out / "wear_stick_zone.png"));
  CHECK_FALSE(fs::exists(out / "gnuplot.log"));
}
