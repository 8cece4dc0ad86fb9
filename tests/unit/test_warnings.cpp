// The advice of the warnings of too few cells (engine/warnings.hpp): a narrower grid.window where the window is much
// wider than the contact needs, more grid.cells alone where it is not (a window fretwear chose, or contact zones far
// apart that any window must span), with the number of cells that resolve the zone.
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/simulation.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

json base() {
  return {{"name", "warnings"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"load", {{"P", 1e5}}},
          {"grid", {{"cells", 256}}}};
}

// The messages of the run's warnings with `code`.
std::vector<std::string> messages(const json& scene, const std::string& code) {
  const Scene s = parse_scene(scene);
  std::vector<std::string> found;
  for (const Warning& w : Simulation(s).run().warnings)
    if (w.code == code) found.push_back(w.message);
  return found;
}

bool has(const std::string& message, const std::string& words) { return message.find(words) != std::string::npos; }

}  // namespace

TEST_CASE("a contact over a cell of a wide given window: a narrower window around it, where the same cells resolve it") {
  // The Hertz contact, a = 0.1077 mm, in a window of 0.2 m on 256 cells (0.78 mm each): two cells. Over 3a around it,
  // as fretwear would choose, the same 256 cells give it 171; in this window 16 × 0.2 m / 2a = 14 860 would.
  json j = base();
  j["grid"]["window"] = {-0.1, 0.1};
  const auto found = messages(j, "contact_under_resolved");
  REQUIRE(found.size() == 1);
  CAPTURE(found[0]);
  CHECK(has(found[0], "give a narrower grid.window around the contact, such as [-0.0001615, 0.0001615] m (over it "
                      "the same grid.cells give it about 171), or more grid.cells (about 15000 in this window)"));
}

TEST_CASE("the advised window far from the origin has the digits that tell its ends apart, and resolves the contact") {
  // The same contact at x = 50 m: to four digits the advice read [50, 50] m, a window of no width.
  json j = base();
  j["profile"]["offset_x"] = 50.0;
  j["grid"]["window"] = {49.9, 50.1};
  const auto found = messages(j, "contact_under_resolved");
  REQUIRE(found.size() == 1);
  CAPTURE(found[0]);
  CHECK(has(found[0], "such as [49.9998385, 50.0001615] m (over it the same grid.cells give it about 171)"));
  j["grid"]["window"] = {49.9998385, 50.0001615};  // as advised: accepted, and the contact resolved
  CHECK(messages(j, "contact_under_resolved").empty());
}

TEST_CASE("a wide given window with too few cells even around the contact: both a narrower window and more cells") {
  // 16 cells: over 3a around the contact the zone would span 10.7, under 16; 24 there, 16 × 0.02 m / 2a = 1486 here.
  json j = base();
  j["grid"] = {{"cells", 16}, {"window", {-0.01, 0.01}}};
  const auto found = messages(j, "contact_under_resolved");
  REQUIRE(found.size() == 1);
  CAPTURE(found[0]);
  CHECK(has(found[0], "give a narrower grid.window around the contact, such as [-0.0001615, 0.0001615] m, and more "
                      "grid.cells (about 24 there; about 1500 in this window)"));
}

TEST_CASE("a contact under-resolved in the window fretwear chose: more cells only") {
  // 16 cells over the chosen window of 3a: the contact touches 12 of them; 16 × 3a / 2a = 24 resolve it.
  json j = base();
  j["grid"]["cells"] = 16;
  const auto found = messages(j, "contact_under_resolved");
  REQUIRE(found.size() == 1);
  CAPTURE(found[0]);
  CHECK(has(found[0], "the window is already about as narrow as the contact allows: give more grid.cells (about 24)"));
  CHECK_FALSE(has(found[0], "narrower grid.window around"));
}

TEST_CASE("two contact zones 1 m apart: the window must span both, so more cells only") {
  // Two cylinders 1 m apart share the load: each zone is some 0.15 mm wide, under a cell of 4096 over the ~1 m
  // window (0.25 mm). No window that holds both zones makes the cells much finer. The count of cells is estimated
  // from the zone as this grid locates it, a cell wide (16 × 1 m / 0.25 mm): the warning says again at that count.
  json j = base();
  j["profile"] = {{"type", "envelope"},
                  {"terms", {{{"type", "cylinder"}, {"R", 0.01}, {"offset_x", -0.5}},
                             {{"type", "cylinder"}, {"R", 0.01}, {"offset_x", 0.5}}}}};
  j["grid"]["cells"] = 4096;
  for (const json& window : {json(nullptr), json({-0.6, 0.6})}) {
    CAPTURE(window.dump());
    if (!window.is_null()) j["grid"]["window"] = window;
    const auto found = messages(j, "contact_under_resolved");
    REQUIRE(found.size() == 1);  // one warning for every zone under 16 cells, its advice the narrowest's
    for (const std::string& m : found) {
      CAPTURE(m);
      CHECK(has(m, "contact zones 1–2 of 2 span fewer than 16 cells each (the narrowest, zone "));
      CHECK(has(m, ": the window must span the contact's 2 zones, from x = -0.5"));
      CHECK(has(m, " to 0.5"));
      CHECK(has(m, "m, so a narrower grid.window cannot make the cells much finer: give more grid.cells (about "
                   "66000)"));
      CHECK_FALSE(has(m, "narrower grid.window around"));
    }
  }
}

TEST_CASE("a stick zone under-resolved: a narrower window where the given one is wide, more cells in a chosen one") {
  // Q/fP = 0.995: the stick zone is √0.005 a ≈ 0.07 a each side, 15 µm in all.
  json j = base();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.995}};
  j["effects"] = {{"tangential", json::object()}};
  {
    const auto found = messages(j, "stick_zone_under_resolved");  // 13 cells of 256 over the chosen window
    REQUIRE(found.size() == 1);
    CAPTURE(found[0]);
    CHECK(has(found[0], "the window is already about as narrow as the contact allows: give more grid.cells (about "));
  }
  j["grid"] = {{"cells", 1024}, {"window", {-2e-3, 2e-3}}};  // 4 cells of 3.9 µm; around the contact some 48
  const auto found = messages(j, "stick_zone_under_resolved");
  REQUIRE(found.size() == 1);
  CAPTURE(found[0]);
  CHECK(has(found[0], "give a narrower grid.window around the contact, such as [-0.0001615, 0.0001615] m (over it "
                      "the same grid.cells give it about 50), or more grid.cells (about 4100 in this window)"));
}
