// The phases of the stress, fatigue, crack and life stages under dissimilar bodies and load histories
// (engine/cycle_stage.hpp, cycle_phases): they take the cycle's own pressure, shear and bulk stress at its top and
// bottom. Three checks:
//   continuity: bodies whose moduli differ by 0.1 % give the similar pair's von Mises, SWT and SIFs;
//   in-phase history: P constant, Q +Q → −Q → +Q with σ in phase, gives the force-controlled run's results to the
//     incremental solver's tolerance;
//   coupling: for steel on titanium the stress map's surface row is −p_top, −q_top of the coupled solve (and
//     −p_bottom, −q_bottom at the bottom), which differ from the uncoupled pressure and from the top reversed by
//     far more than the tolerance, so that the test fails if either were used.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/output.hpp"
#include "engine/simulation.hpp"
#include "support.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

// Hertz, P = 100 N/mm, Q/fP = 0.5, σ = 50 MPa in phase, on 512 cells with a small stress map and four cracks at the
// trailing edge: a second a run.
json scene(const json& pad, const json& specimen) {
  return {{"name", "coupled_phases"},
          {"materials", {{"pad", pad}, {"specimen", specimen}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}, {"bulk_stress", {{"amplitude", 5e7}}}}},
          {"grid", {{"cells", 512}}},
          {"effects",
           {{"tangential", json::object()},
            {"stress", {{"nx", 61}, {"ny", 21}}},
            {"crack", {{"at", "trailing_edge"}, {"lengths", {5e-6, 1e-5, 2e-5, 4e-5}}}}}},
          {"output", {{"plots", false}}}};
}

const json kSteel = {{"E", 2e11}, {"nu", 0.3}};
const json kTitanium = {{"E", 1.1e11}, {"nu", 0.34}};

json summary_of(const json& j) {
  const Scene s = parse_scene(j);
  return make_summary(s, Simulation(s).run());
}

// The largest |a_k − b_k| of two arrays of numbers, over the largest |b_k| (a closed crack's K_I is 0 at every
// length: then 0 when both are).
double relative_gap(const json& a, const json& b) {
  REQUIRE(a.size() == b.size());
  double gap = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    gap = std::max(gap, std::abs(a[k].get<double>() - b[k].get<double>()));
    scale = std::max(scale, std::abs(b[k].get<double>()));
  }
  return scale > 0.0 ? gap / scale : gap;
}

// The keys compared: the stress map's peaks, SWT's, and the SIFs at the top and the bottom.
void check_agree(const json& a, const json& b, double tolerance) {
  for (const char* phase : {"top", "bottom"}) {
    CAPTURE(phase);
    CHECK(a["stress"]["phases"][phase]["von_mises_max"].get<double>() ==
          test::rel(b["stress"]["phases"][phase]["von_mises_max"].get<double>(), tolerance));
  }
  CHECK(a["stress"]["swt_max"].get<double>() == test::rel(b["stress"]["swt_max"].get<double>(), tolerance));
  for (const std::string key : {"K_I_max", "K_I_min", "K_II_max", "K_II_min"}) {
    CAPTURE(key);
    CHECK(relative_gap(a["crack"][key], b["crack"][key]) <= tolerance);
  }
}

// Linear between the two nearest cell centres, as the stress map's surface row is (stress_stage.cpp).
double at_surface(const std::vector<double>& v, const Grid& g, double x) {
  const double u = std::clamp((x - g.x_min) / g.h() - 0.5, 0.0, double(g.n - 1));
  const int k = std::min(int(std::floor(u)), g.n - 2);
  return v[k] + (u - k) * (v[k + 1] - v[k]);
}

}  // namespace

// The pair's E* differs from the similar pair's by 5e-4, so a and p0 by about 2.5e-4, and β = 1.1e-4 moves the
// pressure by O(β); the dissimilar run is incremental, the similar one the analogy (the same discrete problem to
// 1e-8). 0.5 % leaves a decade over these.
TEST_CASE("coupled phases, continuity: moduli 0.1 % apart give the similar pair's stresses, SWT and SIFs") {
  constexpr double kContinuity = 5e-3;
  const json similar = summary_of(scene(kSteel, kSteel));
  json near_pad = kSteel;
  near_pad["E"] = 2e11 * 1.001;
  const json near = summary_of(scene(near_pad, kSteel));
  REQUIRE(near["cycle"]["route"].get<std::string>().find("dissimilar bodies") != std::string::npos);
  REQUIRE(similar["cycle"]["route"].get<std::string>() == "analogy");
  check_agree(near, similar, kContinuity);
}

// A history through the in-phase cycle's own points takes the same increments as force control (40 a cycle: 20 per
// segment of half the period), so it solves the same cycle to the incremental tolerance (1e-8 of the increment's
// slip scale; 1e-6 leaves two decades for the stresses, linear in the tractions, SWT and the closed-crack SIFs).
TEST_CASE("coupled phases, in-phase history: the force-controlled run's stresses, SWT and SIFs") {
  constexpr double kHistoryAgreement = 1e-6;
  for (const json& specimen : {kSteel, kTitanium}) {
    CAPTURE(specimen.dump());
    json force = scene(kSteel, specimen);
    force["effects"]["tangential"]["route"] = "incremental";
    const json a = summary_of(force);
    const double Q = a["cycle"]["Q_max"].get<double>();
    json history = scene(kSteel, specimen);
    history["load"] = {{"P", 1e5}, {"history", {{0, 1e5, Q, 5e7}, {1, 1e5, -Q, -5e7}, {2, 1e5, Q, 5e7}}}};
    const json b = summary_of(history);
    REQUIRE(b["cycle"]["route"].get<std::string>().find("load history") != std::string::npos);
    check_agree(b, a, kHistoryAgreement);
  }
}

// Steel on titanium (β = −0.0516): the shear moves the pressure by a few per cent of its peak. The surface row of
// the map is the tractions' exact limit at the cell centres, interpolated linearly between them: it equals −p, −q
// of the phase to round-off (kSurfaceExact of the peak pressure).
TEST_CASE("coupled phases, dissimilar: the surface row of the map is the coupled pressure and shear") {
  constexpr double kSurfaceExact = 1e-9;
  for (const bool history : {false, true}) {
    CAPTURE(history);
    json j = scene(kSteel, kTitanium);
    if (history)  // P out of phase with Q: the top at P = 1e5, the bottom at 1.2e5, σ = +50 and −20 MPa
      j["load"] = {{"P", 1e5},
                   {"history", {{0, 1e5, 2.5e4, 5e7}, {1, 8e4, 0, 0}, {2, 1.2e5, -2.5e4, -2e7}, {3, 1e5, 2.5e4, 5e7}}}};
    const Scene s = parse_scene(j);
    const RunResult r = Simulation(s).run();
    REQUIRE(r.cycle);
    const CycleStage& c = *r.cycle;
    const Grid& g = r.normal.grid;
    REQUIRE(c.p_top.size() == std::size_t(g.n));
    const double p_max = *std::max_element(c.p_top.begin(), c.p_top.end());
    const std::vector<StressMap> maps = last_record(r.stress_maps);
    REQUIRE(maps.size() == 2);
    struct Expected {
      const std::vector<double> &p, &q;
      double sigma;
    };
    const Expected top{c.p_top, c.result.q_top, c.sigma_top}, bottom{c.p_bottom, c.result.q_bottom, c.sigma_bottom};
    double moved = 0.0, unmirrored = 0.0;  // from the uncoupled pressure, and the bottom from the top reversed
    for (const StressMap& m : maps) {
      const Expected& e = m.phase == "top" ? top : bottom;
      CAPTURE(m.phase);
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const Stress& t = m.sigma[i];  // the surface row
        CHECK(std::abs(t.yy + at_surface(e.p, g, m.x[i])) <= kSurfaceExact * p_max);
        CHECK(std::abs(t.xy + at_surface(e.q, g, m.x[i])) <= kSurfaceExact * p_max);
        moved = std::max(moved, std::abs(at_surface(e.p, g, m.x[i]) - at_surface(r.normal.state.p, g, m.x[i])));
        unmirrored = std::max(unmirrored, std::abs(at_surface(c.result.q_bottom, g, m.x[i]) +
                                                   at_surface(c.result.q_top, g, m.x[i])));
      }
    }
    CHECK(moved > 1e4 * kSurfaceExact * p_max);       // the uncoupled pressure would fail the checks above
    CHECK(unmirrored > 1e4 * kSurfaceExact * p_max);  // so would the top reversed
    CHECK(c.sigma_top == test::rel(5e7, 1e-12));
    CHECK(c.sigma_bottom == test::rel(history ? -2e7 : -5e7, 1e-12));
    // The SWT and the SIFs come from the same phases: the summary has them, finite.
    const json sum = make_summary(s, r);
    CHECK(std::isfinite(sum["stress"]["swt_max"].get<double>()));
    CHECK(sum["crack"]["K_II_max"].size() == 4);
  }
}
