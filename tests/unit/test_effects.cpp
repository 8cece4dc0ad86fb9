// Only the effects a scene names are computed (SCENES.md): what is left out has no stage, no timing and no summary
// section; what an effect needs is added and said.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/simulation.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {
json summary_of(const json& scene_json) {
  const Scene scene = parse_scene(scene_json);
  return make_summary(scene, Simulation(scene).run());
}

json base() {
  return {{"name", "effects"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"load", {{"P", 1e5}}},
          {"grid", {{"cells", 256}}}};
}
}  // namespace

TEST_CASE("a normal-contact scene runs the normal stage only") {
  const json s = summary_of(base());
  CHECK(s["effects_run"] == json::array({"normal"}));
  CHECK_FALSE(s.contains("cycle"));
  CHECK_FALSE(s.contains("wear"));
  CHECK_FALSE(s["timings"].contains("tangential"));
  CHECK_FALSE(s["timings"].contains("wear"));
}

TEST_CASE("a cycle scene adds the cycle and nothing else") {
  json j = base();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"tangential", json::object()}};
  const json s = summary_of(j);
  CHECK(s["effects_run"] == json::array({"normal", "tangential"}));
  CHECK(s.contains("cycle"));
  CHECK_FALSE(s.contains("wear"));
  CHECK_FALSE(s.contains("effects_implied"));
  CHECK(s["timings"].contains("tangential"));
}

TEST_CASE("wear brings the cycle it needs, and the summary says so") {
  json j = base();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"wear", {{"k", 1e-12}, {"cycles", 10}, {"record", 1}}}};
  const json s = summary_of(j);
  CHECK(s["effects_run"] == json::array({"normal", "tangential", "wear"}));
  CHECK(s["effects_implied"]["tangential"] == "needed by wear");
  CHECK(s["timings"].contains("wear"));
}
