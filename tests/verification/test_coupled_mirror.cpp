// The coupled cycle's reloading half as the mirror image of its unloading half (IncrementalSlipOptions::
// mirror_half_cycle, contact/incremental_slip.hpp), against the full march it replaces. Hertz, R = 10 mm,
// P = 100 N/mm, f = 0.5, a steel pad (200 GPa, 0.3) on an aluminium specimen (71 GPa, 0.33, β = −0.110) and on a
// titanium one (110 GPa, 0.34, β = −0.052), 512 cells, 40 increments per cycle, the settling march of the wear
// stage's responses (the first loading in one increment, the first cycle in four), the second cycle reported.
//
// What may differ. x → −x with q → −q and Q → −Q leaves the equations unchanged on an even gap, so a steady cycle
// whose bottom is its top mirrored dissipates e(x) + e(−x) over a cycle, e the unloading half's. The marched cycle's
// bottom is that but for the slip the first loading left locked in at the stick zone's edges: the marched bottom
// and the mirrored top differ there by about 2e-3 p0 (examples/dissimilar_cycle.json with aluminium: 2.3e-3 p0 at
// x = −0.704 a, the same at 40 and 160 increments), and the marched energy density is even only to 1.5e-5 of its
// peak. kEnergyAgreement and kDensityAgreement hold the mirrored cycle to that; the top it reports is the steady top
// the half cycle starts from, as the full march reaches it (test_coupled_increments.cpp: 2e-5 p0).
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kP = 1e5;
constexpr Material kAluminium{71e9, 0.33}, kTitanium{110e9, 0.34};
// Measured: the energy 4.3e-7, 5.1e-7 and 4.5e-8 apart (aluminium at Q/fP = 0.5 and 0.85, titanium at 0.5); the
// density 7.9e-6, 1.4e-5 and 7.3e-7 of its peak; the top 1e-6 to 2.4e-6 p0; the shear after reloading to Q = 0,
// where the marched cycle keeps the locked-in slip and the mirrored one has it mirrored, 1.6e-3, 6.4e-3 and 3.2e-4
// p0.
constexpr double kEnergyAgreement = 5e-6;     // relative, the energy dissipated in the cycle
constexpr double kDensityAgreement = 5e-5;    // of its peak, the energy density cell by cell
constexpr double kTopAgreement = 2e-5;        // of p0, the shear and the pressure at the top
constexpr double kLockedIn = 1e-2;            // of p0, the shear after reloading to Q = 0 (locked in, above)

struct Run {
  Model model;
  NormalResult normal;
  IncrementalResult r;
};

Run run(Material specimen, double ratio, bool mirror, double bulk_stress = 0.0, double window_shift = 0.0) {
  Scene s = test::hertz_cycle(kP, ratio, 512);
  s.specimen = specimen;
  if (window_shift != 0.0) {
    const Model m = make_model(s);
    s.window = std::pair{m.grid.x_min + window_shift, m.grid.x_max + window_shift};
  }
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  const NormalCoupling coupling{m.pair.beta(), m.g0};
  const CyclicLoad load{s.P, s.Q_max(), *s.friction, bulk_stress};
  IncrementalSlipOptions o;
  o.cycles = 2;
  o.settling_increments = 4;
  o.mirror_half_cycle = mirror;
  IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve(n.state, load, nullptr, &coupling);
  return {std::move(m), std::move(n), std::move(r)};
}

}  // namespace

TEST_CASE("coupled mirror: half a cycle, mirrored, dissipates what the full march does, in half the increments") {
  for (const auto& [name, specimen, ratio] : {std::tuple{"aluminium", kAluminium, 0.5},
                                              std::tuple{"aluminium", kAluminium, 0.85},
                                              std::tuple{"titanium", kTitanium, 0.5}}) {
    CAPTURE(name);
    CAPTURE(ratio);
    const Run full = run(specimen, ratio, false);
    const Run half = run(specimen, ratio, true);
    CHECK_FALSE(full.r.mirrored);
    REQUIRE(half.r.mirrored);
    // The first loading in one increment, the first cycle in four, then 40 marched or 20 and their mirror image.
    CHECK(full.r.n_increments == 1 + 4 + 40);
    CHECK(half.r.n_increments == 1 + 4 + 20);
    const CycleResult& a = full.r.cycles.back();
    const CycleResult& b = half.r.cycles.back();
    const int n = full.model.grid.n;
    const double p0 = closed_form::hertz(kP, full.model.pair.A(), test::kHertzR).p0;
    const double peak = *std::max_element(a.energy_density.begin(), a.energy_density.end());
    MESSAGE(fmt::format("{} at Q/fP = {}: energy {:.10g} (mirrored) against {:.10g} J/m ({:.3g}); density {:.3g} of "
                        "its peak apart; top shear {:.3g} p0; reloaded shear {:.3g} p0; slip travelled {:.3g} of its "
                        "largest",
                        name, ratio, b.dissipated_energy, a.dissipated_energy,
                        b.dissipated_energy / a.dissipated_energy - 1.0,
                        max_abs_diff(a.energy_density, b.energy_density) / peak,
                        max_abs_diff(a.q_top, b.q_top) / p0, max_abs_diff(a.q_reloaded, b.q_reloaded) / p0,
                        max_abs_diff(a.slip_travelled, b.slip_travelled) /
                            *std::max_element(a.slip_travelled.begin(), a.slip_travelled.end())));
    CHECK(b.dissipated_energy == test::rel(a.dissipated_energy, kEnergyAgreement));
    CHECK(max_abs_diff(a.energy_density, b.energy_density) < kDensityAgreement * peak);
    CHECK(max_abs_diff(a.q_top, b.q_top) < kTopAgreement * p0);
    CHECK(max_abs_diff(full.r.p_top, half.r.p_top) < kTopAgreement * p0);
    CHECK(max_abs_diff(a.q_reloaded, b.q_reloaded) < kLockedIn * p0);
    REQUIRE(a.stick_zone);
    REQUIRE(b.stick_zone);
    const double h = full.model.grid.h();
    CHECK(std::abs(a.stick_zone->first - b.stick_zone->first) < 1e-3 * h);
    CHECK(std::abs(a.stick_zone->second - b.stick_zone->second) < 1e-3 * h);
    // Mirrored, the cycle's energy and slip are even to the last bit: e(x) + e(−x) either way round.
    for (int i = 0; i < n; ++i) {
      CHECK(b.energy_density[i] == b.energy_density[n - 1 - i]);
      CHECK(b.slip_travelled[i] == b.slip_travelled[n - 1 - i]);
    }
    // The slip range from the unloading's extremes and their mirror image (mirror_reloading).
    REQUIRE(b.slip_range.size() == std::size_t(n));
    CHECK(max_abs_diff(a.slip_range, b.slip_range) < 1e-3 * a.slip_max);
  }
}

TEST_CASE("coupled mirror: a contact that is not mirror-symmetric, or a bulk stress, marches the whole cycle") {
  const Run shifted = run(kAluminium, 0.5, true, 0.0, 0.37e-5);  // the cells no longer pair about x = 0
  CHECK_FALSE(shifted.r.mirrored);
  CHECK(shifted.r.n_increments == 1 + 4 + 40);
  const Run bulk = run(kAluminium, 0.5, true, 1e-4);  // the bulk strain ε x is not odd under the mirror
  CHECK_FALSE(bulk.r.mirrored);
  CHECK(bulk.r.n_increments == 1 + 4 + 40);
  const Run similar = run({200e9, 0.3}, 0.5, true);  // β = 0: nothing to gain, the pressure is fixed
  CHECK_FALSE(similar.r.mirrored);
}

TEST_CASE("coupled mirror: a dissimilar wear run says how its cycles were solved, mirrored or lagged") {
  Scene s = test::hertz_wear(kP, 0.5, 1e4, 128);
  s.specimen = kAluminium;
  const RunResult r = Simulation(s).run();
  REQUIRE(r.wear);
  const nlohmann::json summary = summarise_wear(s, *r.wear);
  REQUIRE(summary.contains("coupling"));
  const nlohmann::json& c = summary["coupling"];
  MESSAGE(c.dump());
  const long responses = c["responses"].get<long>(), coupled = c["coupled"].get<long>(),
             mirrored = c["mirrored"].get<long>(), lagged = c["lagged"].get<long>();
  CHECK(responses == coupled + lagged);
  CHECK(coupled > 0);
  CHECK(lagged > 0);
  // The Hertz gap worn by mirrored cycles stays even: every coupled cycle is a half cycle mirrored.
  CHECK(mirrored == coupled);
  // Similar bodies take the analogy: nothing coupled to count.
  Scene similar = test::hertz_wear(kP, 0.5, 1e4, 128);
  CHECK_FALSE(summarise_wear(similar, *Simulation(similar).run().wear).contains("coupling"));
  // Under displacement control too: the lag's uncoupled cycle is the analogy's at the Q that reaches δ.
  Scene displaced = test::hertz_wear(kP, 0.5, 1e4, 128);
  displaced.specimen = kAluminium;
  displaced.Q_ratio.reset();
  displaced.control = LoadControl::displacement;
  displaced.delta = 1e-6;
  const nlohmann::json d = summarise_wear(displaced, *Simulation(displaced).run().wear).at("coupling");
  MESSAGE(d.dump());
  CHECK(d["responses"].get<long>() == d["coupled"].get<long>() + d["lagged"].get<long>());
  CHECK(d["lagged"].get<long>() > 0);
  CHECK(d["coupled"].get<long>() > 0);
  CHECK(d["mirrored"].get<long>() == d["coupled"].get<long>());
}

namespace {

// The wear stage's coupled response under displacement control (engine/wear_contacts.cpp): the datum's δ cycles
// ±delta, the first loading in one increment and the first cycle in four (settle) or in full, the second cycle
// reported, whole or its reloading half mirrored. reference_shift moves the datum's reference points off x = 0.
Run run_displacement(Material specimen, double delta, bool mirror, bool settle, double reference_shift = 0.0) {
  Scene s = test::hertz_cycle(kP, 0.5, 512);
  s.specimen = specimen;
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  const auto [x_c, d] = reference_point(s, n);
  const ReferenceDatum datum(m.grid, m.pair, x_c + reference_shift, d);
  const NormalCoupling coupling{m.pair.beta(), m.g0};
  CyclicLoad load{s.P, 0.0, *s.friction, 0.0};
  load.delta = delta;
  IncrementalSlipOptions o;
  o.cycles = 2;
  o.settling_increments = settle ? 4 : 0;
  o.mirror_half_cycle = mirror;
  IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve(n.state, load, &datum, &coupling);
  return {std::move(m), std::move(n), std::move(r)};
}

}  // namespace

// Under displacement control the mirror takes δ → −δ as well (the datum's reference points on x = 0), and the
// settling march is that of force control: each increment is a δ search of coupled increments from the increment's
// start (contact/incremental_slip.hpp). Measured against the whole march of 90 increments (the first loading in ten,
// two cycles of 40): the settled march's energy 7e-9, 1e-9 and 2e-8 apart (aluminium in partial and in gross slip,
// titanium), the mirrored one's 2.2e-7, 1e-9 and 1.7e-8 from the settled one; the density 4e-6 of its peak at most,
// the top shear 3.2e-6 p0, the Q at the top 1.3e-9; in gross slip the sliding amplitude the same to 1e-12.
TEST_CASE("coupled mirror: under displacement control, settled and mirrored, the cycle is the full march's") {
  for (const auto& [name, specimen, delta] : {std::tuple{"aluminium", kAluminium, 1.0e-6},
                                              std::tuple{"aluminium", kAluminium, 4.0e-6},
                                              std::tuple{"titanium", kTitanium, 1.0e-6}}) {
    CAPTURE(name);
    CAPTURE(delta);
    const Run marched = run_displacement(specimen, delta, false, false);
    const Run settled = run_displacement(specimen, delta, false, true);
    const Run half = run_displacement(specimen, delta, true, true);
    CHECK_FALSE(settled.r.mirrored);
    REQUIRE(half.r.mirrored);
    CHECK(marched.r.n_increments == 10 + 40 + 40);
    CHECK(settled.r.n_increments == 1 + 4 + 40);
    CHECK(half.r.n_increments == 1 + 4 + 20);
    const CycleResult& m = marched.r.cycles.back();
    const double p0 = closed_form::hertz(kP, marched.model.pair.A(), test::kHertzR).p0;
    const double peak = *std::max_element(m.energy_density.begin(), m.energy_density.end());
    for (const auto& [how, run] : {std::pair{"settled", &settled}, std::pair{"mirrored", &half}}) {
      CAPTURE(how);
      const CycleResult& b = run->r.cycles.back();
      MESSAGE(fmt::format("{} at delta = {:.3g} m ({}), {}: energy {:.10g} against {:.10g} J/m ({:.3g}); Q at the "
                          "top {:.3g}; density {:.3g} of its peak; top shear {:.3g} p0; sliding amplitude {:.10g} "
                          "against {:.10g} m",
                          name, delta, to_string(m.regime), how, b.dissipated_energy, m.dissipated_energy,
                          b.dissipated_energy / m.dissipated_energy - 1.0, b.Q_peak / m.Q_peak - 1.0,
                          max_abs_diff(m.energy_density, b.energy_density) / peak,
                          max_abs_diff(m.q_top, b.q_top) / p0, b.sliding_amplitude, m.sliding_amplitude));
      CHECK(b.regime == m.regime);
      CHECK(b.dissipated_energy == test::rel(m.dissipated_energy, kEnergyAgreement));
      CHECK(b.Q_peak == test::rel(m.Q_peak, kEnergyAgreement));
      CHECK(max_abs_diff(m.energy_density, b.energy_density) < kDensityAgreement * peak);
      CHECK(max_abs_diff(m.q_top, b.q_top) < kTopAgreement * p0);
      if (m.regime == Regime::gross_slip) {
        REQUIRE(m.sliding_amplitude > 0.0);
        CHECK(b.sliding_amplitude == test::rel(m.sliding_amplitude, kEnergyAgreement));
      } else {
        REQUIRE(m.stick_zone);
        REQUIRE(b.stick_zone);
        const double h = marched.model.grid.h();
        CHECK(std::abs(m.stick_zone->first - b.stick_zone->first) < 1e-3 * h);
        CHECK(std::abs(m.stick_zone->second - b.stick_zone->second) < 1e-3 * h);
      }
    }
  }
  // Reference points off x = 0: δ is not odd under the mirror, and the whole cycle is marched.
  const Run shifted = run_displacement(kAluminium, 1.0e-6, true, true, 1e-6);
  CHECK_FALSE(shifted.r.mirrored);
  CHECK(shifted.r.n_increments == 1 + 4 + 40);
}
