// The life stage (engine/life_stage.hpp) on a Hertz contact with bulk tension (R = 10 mm, P = 100 N/mm, f = 0.5,
// Q/fP = 0.7, σ = 250 MPa in phase, 1024 cells): its initiation against SWT computed point by point here, its growth
// against Paris integrated here from the crack solver's own SIFs at fine length steps (the stepping, not the SIFs,
// is under test), and Miner's sum over wear records reducing to the one cycle's life when nothing wears.
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "support.hpp"

#include "contact/fatigue_life.hpp"
#include "contact/fatigue_measures.hpp"
#include "contact/subsurface_stress.hpp"
#include "engine/crack_stage.hpp"
#include "engine/simulation.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

json life_scene(double ell) {
  return {{"name", "life"},
          {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.7}}}, {"bulk_stress", {{"amplitude", 250e6}}}}},
          {"grid", {{"cells", 1024}}},
          {"effects",
           {{"tangential", json::object()},
            {"life",
             {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52},
                              {"critical_distance", ell}}},
              {"growth", {{"C", 5e-30}, {"m", 3.0}, {"dK_th", 2e6}, {"a_initial", 2e-5}, {"a_final", 1e-3}}}}}}}};
}

}  // namespace

TEST_CASE("life: without wear, initiation is the one cycle's N_i at the surface point of largest SWT") {
  const Scene s = parse_scene(life_scene(0.0));
  const RunResult r = Simulation(s).run();
  REQUIRE(r.life);
  REQUIRE(r.life->initiation);
  const LifeInitiationResult& i = *r.life->initiation;
  // At the site, from the tractions of the cycle: SWT on its critical plane, and the life from the curve.
  const Model m = make_model(s);
  const std::vector<Phase> phases = cycle_phases(s, r.normal.state.p, &r.cycle->result.q_top);
  const SurfaceTractions top{m.grid, phases[0].p, phases[0].q, phases[0].sigma_bulk};
  const SurfaceTractions bottom{m.grid, phases[1].p, phases[1].q, phases[1].sigma_bulk};
  const Stress pair[2] = {stress_along_depth(top, i.x, std::vector<double>{0.0})[0],
                          stress_along_depth(bottom, i.x, std::vector<double>{0.0})[0]};
  const SwtResult swt = swt_critical_plane(pair, s.specimen, s.plane);
  const InitiationConstants k{1.817e9, -0.08, 0.35, -0.52, 200e9};
  CHECK(i.swt == test::rel(swt.swt, 1e-12));
  CHECK(i.cycles == test::rel(initiation_life(k, swt.swt), 1e-12));
  // No surface point of the layer has a larger SWT (a shorter life): the site is the maximum.
  for (double x : i.map_x) {
    const Stress p2[2] = {stress_along_depth(top, x, std::vector<double>{0.0})[0],
                          stress_along_depth(bottom, x, std::vector<double>{0.0})[0]};
    CHECK(swt_critical_plane(p2, s.specimen, s.plane).swt <= swt.swt * (1.0 + 1e-12));
  }
  MESSAGE(fmt::format("site x = {:.6g} m, SWT {:.6g} Pa, N_i = {:.6g}, total {:.6g}, fate {}", i.x, i.swt, i.cycles,
                      r.life->total_cycles, r.life->fate));
}

TEST_CASE("life: the growth matches Paris integrated here from the crack solver at fine length steps") {
  // The life stage interpolates a table of kTableLengths lengths; here 2000 log-spaced lengths and the trapezoid
  // rule on N = ∫ da / (C ΔK^m), whose own error at this spacing is below 1e-5: kIndependent bounds the table's
  // interpolation and the integrator together.
  constexpr double kIndependent = 5e-3;
  const Scene s = parse_scene(life_scene(0.0));
  const RunResult r = Simulation(s).run();
  REQUIRE(r.life);
  REQUIRE(r.life->propagation);
  REQUIRE(r.life->fate == "failure");
  const Model m = make_model(s);
  CrackEffect crack;
  crack.at = CrackPosition::x;
  crack.x = r.life->crack_x;
  const int n = 2000;
  for (int j = 0; j < n; ++j) crack.lengths.push_back(2e-5 * std::pow(1e-3 / 2e-5, double(j) / (n - 1)));
  const std::vector<SifSet> sets =
      crack_sifs(m.grid, cycle_phases(s, r.normal.state.p, &r.cycle->result.q_top), crack.x, crack, 0.0);
  double N = 0.0;
  auto inverse_rate = [&](int j) {
    const double dK = sets[0].result.sifs[std::size_t(j)].K_I - sets[1].result.sifs[std::size_t(j)].K_I;
    return dK > 2e6 ? 1.0 / (5e-30 * std::pow(dK, 3.0)) : std::numeric_limits<double>::infinity();
  };
  for (int j = 1; j < n; ++j)
    N += 0.5 * (inverse_rate(j - 1) + inverse_rate(j)) * (crack.lengths[std::size_t(j)] - crack.lengths[std::size_t(j - 1)]);
  MESSAGE(fmt::format("growth: life stage {:.8g} cycles, integrated here {:.8g}", r.life->propagation->cycles, N));
  CHECK(r.life->propagation->cycles == test::rel(N, kIndependent));
  CHECK(r.life->total_cycles == test::rel(r.life->initiation->cycles + r.life->propagation->cycles, 1e-14));
}

TEST_CASE("life: Miner over wear records that do not change the contact gives the one cycle's N_i") {
  // k = 1e-30: the records' contact is the unworn one to round-off, so the damage rate is the same in each and
  // Miner's sum gives N_i of the unworn cycle. The window is given, so that both runs share one grid (a wear run
  // otherwise widens it to the asymptote's worn extent).
  json j = life_scene(0.0);
  j["grid"]["window"] = {-0.4e-3, 0.4e-3};
  const RunResult unworn = Simulation(parse_scene(j)).run();
  j["effects"]["wear"] = {{"law", "archard"}, {"k", 1e-30}, {"cycles", 1e6}, {"record", 6}};
  const RunResult worn = Simulation(parse_scene(j)).run();
  REQUIRE(unworn.life->initiation);
  REQUIRE(worn.life->initiation);
  CHECK(worn.life->initiation->x == unworn.life->initiation->x);
  CHECK(worn.life->initiation->cycles == test::rel(unworn.life->initiation->cycles, 1e-6));
}

TEST_CASE("life: at a punch's corner the point method's SWT doubles with the grid, the line method's barely moves") {
  // A sharp flat punch (b = 0.5 mm, P = 200 kN/m, Q/fP = 0.3, 100 MPa bulk tension): p ∝ r^(−1/2) at its corners, so
  // SWT ∝ 1/r and the point value at the cell centre next to a corner doubles as h halves; averaged over 20 µm of
  // depth it grows only like ln(ℓ/h) (measured: 4 % and 5 % per halving). Both are marked singular.
  auto site = [](double ell, int cells) {
    const json j = {{"name", "punch_life"},
                    {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
                    {"profile", {{"type", "flat"}, {"b", 0.5e-3}}},
                    {"friction", 0.5},
                    {"load", {{"P", 2e5}, {"Q", {{"ratio", 0.3}}}, {"bulk_stress", {{"amplitude", 1e8}}}}},
                    {"grid", {{"cells", cells}}},
                    {"effects", {{"tangential", json::object()},
                                 {"life", {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35},
                                                           {"c", -0.52}, {"critical_distance", ell}}}}}}}};
    const RunResult r = Simulation(parse_scene(j)).run();
    CHECK(r.life->initiation->singular);
    return r.life->initiation->swt;
  };
  const double p1 = site(0.0, 512), p2 = site(0.0, 1024), l1 = site(2e-5, 512), l2 = site(2e-5, 1024),
               l3 = site(2e-5, 2048);
  MESSAGE(fmt::format("point: {:.6g} -> {:.6g}; line: {:.6g} -> {:.6g} -> {:.6g} Pa", p1, p2, l1, l2, l3));
  CHECK(p2 / p1 > 1.8);
  CHECK(l2 / l1 < 1.1);
  CHECK(l3 / l2 < 1.1);
}

TEST_CASE("life: in gross slip wear removes the damaged layer, and the crack starts hundreds of times later") {
  // examples/life_slip_amplitude.json at a 3 µm stroke on 256 cells: without wear the surface at the contact's edge
  // starts a crack after about 1.4e5 cycles; with wear the specimen loses its surface faster than damage builds up
  // there, and initiation waits some 6.5e7 cycles (Madge, Leen and Shipway 2007 report this rise in gross slip).
  json j = json::parse(std::ifstream(FRETWEAR_SOURCE_DIR "/examples/life_slip_amplitude.json"));
  j["load"]["delta"] = 3e-6;
  j["grid"]["cells"] = 256;
  const RunResult worn = Simulation(parse_scene(j)).run();
  j["effects"].erase("wear");
  j["effects"]["tangential"] = json::object();
  const RunResult unworn = Simulation(parse_scene(j)).run();
  REQUIRE(worn.cycle->result.regime == Regime::gross_slip);
  MESSAGE(fmt::format("initiation: {:.6g} cycles worn, {:.6g} unworn", worn.life->initiation->cycles,
                      unworn.life->initiation->cycles));
  CHECK(worn.life->initiation->cycles > 100.0 * unworn.life->initiation->cycles);
}
