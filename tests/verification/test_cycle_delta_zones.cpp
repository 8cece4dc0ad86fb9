// The analogy route's δ_max (cycle.delta_max) where the stick zone is two: the rigid shift λ is read inside a stick
// zone, where the surfaces have never slipped. Read at the middle of the zones' hull, between the two asperities'
// contacts, it was 15 % low against the incremental route's δ_max, which marches the datum itself. Two equal
// cylinders 0.4 mm apart under P = 100 kN/m, Q/fP = 0.5, 1024 cells: the analogy and the incremental route (200
// increments) agree to 3e-9; the bound kAgree = 1e-6 is the incremental route's root-find tolerance on δ
// (test_cycle_displacement.cpp's kAgreeForce).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/simulation.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr double kAgree = 1e-6;

CycleStage two_zone_cycle(const char* route) {
  nlohmann::json j = nlohmann::json::parse(R"({"name": "two", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "envelope", "terms": [{"type": "cylinder", "R": 0.01, "offset_x": -0.2e-3},
                                              {"type": "cylinder", "R": 0.01, "offset_x": 0.2e-3}]},
    "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}}, "grid": {"cells": 1024},
    "effects": {"tangential": {"increments": 200}}})");
  j["effects"]["tangential"]["route"] = route;
  return *Simulation(parse_scene(j)).run().cycle;
}

}  // namespace

TEST_CASE("two stick zones: the analogy's delta_max is the incremental route's") {
  const CycleStage analogy = two_zone_cycle("analogy"), incremental = two_zone_cycle("incremental");
  REQUIRE(analogy.result.stick_zones.size() == 2);
  REQUIRE(incremental.result.stick_zones.size() == 2);
  CHECK(analogy.result.delta_max > 0.0);
  CHECK(analogy.result.delta_max == test::rel(incremental.result.delta_max, kAgree));
}
