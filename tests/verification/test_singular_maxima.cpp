// Maxima at singular edges (engine/stress_stage.hpp, SingularEdges; PHYSICS.md, "Singular edges"): a sharp flat
// punch's pressure is square-root singular at its corners, so the von Mises maximum there grows with the grid while
// the corner's intensity K_N converges; the summary marks the maximum "singular" and warns, and a Hertz contact, whose
// edges are bounded, is marked nowhere. The punch's peak pressure, its corner cell's, is marked and warned alike.
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "support.hpp"

#include "engine/simulation.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

json punch(int cells, int nx = 201) {
  return {{"name", "punch"},
          {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
          {"profile", {{"type", "flat"}, {"b", 0.5e-3}}},
          {"load", {{"P", 2e5}}},
          {"grid", {{"cells", cells}}},
          {"effects", {{"stress", {{"nx", nx}, {"ny", 21}}}}}};
}

bool has_warning(const json& s, const std::string& code) {
  for (const auto& w : s["warnings"])
    if (w["code"] == code) return true;
  return false;
}

}  // namespace

TEST_CASE("a flat punch's stress maximum sits at a corner: marked singular and warned, growing while K_N converges") {
  // Grid and map refined together: the map's points come closer to the corner, where the stresses are unbounded.
  std::vector<double> vm, K;
  for (int cells : {256, 1024}) {
    const Scene s = parse_scene(punch(cells, cells / 256 * 200 + 1));
    const json summary = make_summary(s, Simulation(s).run());
    const json& loaded = summary["stress"]["phases"]["loaded"];
    CHECK(loaded["von_mises_max_singular"].get<bool>());
    CHECK(has_warning(summary, "singular_maximum"));
    vm.push_back(loaded["von_mises_max"].get<double>());
    K.push_back(summary["contact"]["edge_intensity"][0].get<double>());
  }
  MESSAGE(fmt::format("von Mises max {:.6g} -> {:.6g} Pa; K_N {:.6g} -> {:.6g} Pa m^0.5", vm[0], vm[1], K[0], K[1]));
  CHECK(vm[1] > 1.2 * vm[0]);                // grows with the grid (like √(1/h) at the corner)
  CHECK(K[1] == test::rel(K[0], 2e-2));      // converges (first order, test_edge_intensity.cpp)
}

TEST_CASE("a flat punch's peak pressure is its corner cell's: marked singular and warned, growing like √(1/h)") {
  // The pressure P/(π√(b² − x²)) averaged over the corner cell of width h is (P/π)(π/2 − asin(1 − h/b))/h, about
  // (P/π)√(2/(b h)): four times the cells, twice the peak. Normal contact alone (no stress map) is enough to warn.
  std::vector<double> p_max;
  for (int cells : {256, 1024, 4096}) {
    json j = punch(cells);
    j.erase("effects");
    const Scene s = parse_scene(j);
    const json summary = make_summary(s, Simulation(s).run());
    CHECK(summary["contact"]["p_max_singular"].get<bool>());
    bool named = false;
    for (const auto& w : summary["warnings"])
      named = named || (w["code"] == "singular_maximum" &&
                        w["message"].get<std::string>().rfind("contact.p_max sits at an edge", 0) == 0);
    CHECK(named);
    p_max.push_back(summary["contact"]["p_max"].get<double>());
  }
  MESSAGE(fmt::format("p_max {:.6g}, {:.6g}, {:.6g} Pa", p_max[0], p_max[1], p_max[2]));
  CHECK(p_max[1] / p_max[0] == doctest::Approx(2.0).epsilon(0.05));  // ratios: dimensionless
  CHECK(p_max[2] / p_max[1] == doctest::Approx(2.0).epsilon(0.05));
}

TEST_CASE("a Hertz contact's maxima are bounded: nothing marked singular, no warning") {
  json j = punch(512);
  j["profile"] = {{"type", "cylinder"}, {"R", 0.01}};
  j["load"]["P"] = 1e5;
  const Scene s = parse_scene(j);
  const json summary = make_summary(s, Simulation(s).run());
  CHECK_FALSE(summary["stress"]["phases"]["loaded"]["von_mises_max_singular"].get<bool>());
  CHECK_FALSE(summary["stress"]["phases"]["loaded"]["surface_sxx_trailing_peak_singular"].get<bool>());
  CHECK_FALSE(summary["contact"]["p_max_singular"].get<bool>());
  CHECK_FALSE(has_warning(summary, "singular_maximum"));
}
