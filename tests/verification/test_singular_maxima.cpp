// Maxima at singular edges (engine/stress_stage.hpp, SingularEdges; PHYSICS.md, "Singular edges"): a sharp flat
// punch's pressure is square-root singular at its corners, so the von Mises maximum there grows with the grid while
// the corner's intensity K_N converges; the summary marks the maximum "singular" and warns, and a Hertz contact, whose
// edges are bounded, is marked nowhere. The punch's peak pressure, its corner cell's, is marked and warned alike.
// Bounded edges have a cusp instead: a surface maximum there is sampled short of its top, and warned (edge_cusp).
#include <cmath>
#include <fstream>
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
  CHECK_FALSE(has_warning(summary, "edge_cusp"));  // frictionless: σxx = −p, no tension peak at the edge
}

std::string warning(const json& s, const std::string& code) {
  for (const auto& w : s["warnings"])
    if (w["code"] == code) return w["message"].get<std::string>();
  return "";
}

// Under Q the surface tension peaks at the trailing edge, σxx(−a) = 2 f p0 √(Q/fP) (PHYSICS.md), in a square-root
// cusp: the map's largest sample there falls short of it by about K √Δ for points Δ apart. Bounded, so not singular;
// warned, and the shortfall halves when the map has four times the points.
TEST_CASE("a Hertz contact's tension peaks in a cusp at its trailing edge: sampled short by the root of the spacing") {
  const double P = 1e5, R = 0.01, f = 0.5, ratio = 0.6, E = 200e9, nu = 0.3;
  const double a = std::sqrt(4.0 * P * R * 2.0 * (1.0 - nu * nu) / (M_PI * E)), p0 = 2.0 * P / (M_PI * a);
  const double closed = 2.0 * f * p0 * std::sqrt(ratio);
  std::vector<double> short_by;
  for (int nx : {161, 641}) {
    CAPTURE(nx);
    json j = punch(2048, nx);
    j["profile"] = {{"type", "cylinder"}, {"R", R}};
    j["load"] = {{"P", P}, {"Q", {{"ratio", ratio}}}};
    j["friction"] = f;
    j["effects"] = {{"tangential", json::object()}, {"stress", {{"nx", nx}, {"ny", 4}}}};
    const Scene s = parse_scene(j);
    const json summary = make_summary(s, Simulation(s).run());
    const json& top = summary["stress"]["phases"]["top"];
    CHECK_FALSE(top["surface_sxx_trailing_peak_singular"].get<bool>());
    CHECK(top["surface_sxx_trailing_peak_x"].get<double>() == doctest::Approx(-a).epsilon(0.01));
    CHECK(warning(summary, "edge_cusp").find("stress.phases.top.surface_sxx_trailing_peak") != std::string::npos);
    CHECK_FALSE(has_warning(summary, "singular_maximum"));
    short_by.push_back(1.0 - top["surface_sxx_trailing_peak"].get<double>() / closed);
  }
  MESSAGE(fmt::format("trailing edge's tension short of 2 f p0 sqrt(Q/fP) by {:.3g} and {:.3g} at 161 and 641 points",
                      short_by[0], short_by[1]));
  CHECK(short_by[0] > 0.1);
  CHECK(short_by[0] / short_by[1] == doctest::Approx(2.0).epsilon(0.15));  // √4
}

// The life's point method evaluates SWT at the cells' centres: at the trailing edge's cusp it moves with the grid
// and is warned; the line method averages over the critical distance and is not.
TEST_CASE("a point-method initiation at a contact's edge is warned, a line-method one is not") {
  for (const double distance : {0.0, 2e-5}) {
    CAPTURE(distance);
    json j = json::parse(std::ifstream(FRETWEAR_SOURCE_DIR "/examples/life_slip_amplitude_unworn.json"));
    j["effects"]["life"]["initiation"]["critical_distance"] = distance;
    j["effects"]["life"]["growth"]["a_initial"] = 2e-5;
    const Scene s = parse_scene(j);
    const json summary = make_summary(s, Simulation(s).run());
    CHECK_FALSE(summary["life"]["initiation"]["singular"].get<bool>());
    CHECK((warning(summary, "edge_cusp").find("life.initiation (point method") != std::string::npos) ==
          (distance == 0.0));
  }
}
