// The cost of a coupled cycle (Dundurs β ≠ 0, contact/incremental_slip.hpp) without changing its answer: the
// predicted start of each increment's block Gauss–Seidel sweeps, and the coarse settling march of a wear response
// (engine/wear_contacts.hpp). Hertz, R = 10 mm, P = 100 N/mm, f = 0.5, Q/fP = 0.5, a steel pad (200 GPa, 0.3) on an
// aluminium specimen (71 GPa, 0.33), β = −0.110, 40 increments per cycle, the second cycle reported (as the wear
// stage marches it).
//
// What "the same answer" means here. The sweeps stop when one changes neither traction by more than
// coupling_tolerance · max p (1e-8), and each half of a sweep stops at its own tolerance (1e-8, relative to the
// increment's slip and to the largest gap): a sweep whose input moved by less than those leaves its output exactly
// where it was. Two runs that start their sweeps elsewhere therefore meet the same criterion at answers that differ
// by what the inner tolerances let through, not by the coupling tolerance: measured at 512 cells, 4e-7 in the energy
// of the cycle, 1e-6 p0 in the shear and 2e-6 p0 in the pressure at the top, at the cells next to the stick zone's
// edges (for steel on titanium at 1024 cells, 4e-7 in energy too). kEnergyAgreement and kTractionAgreement hold that
// with a decade to spare; they are two decades below what the wear stepper may err by in a step (τ = 1e-3 of the
// deepest wear), where the coupled cycle's energy feeds the wear rate.
#include <algorithm>
#include <cmath>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kP = 1e5, kRatio = 0.5;
constexpr Material kAluminium{71e9, 0.33};
constexpr double kEnergyAgreement = 5e-6;    // relative, the energy dissipated in the reported cycle
constexpr double kTractionAgreement = 2e-5;  // of p0, the shear and the pressure at the top of the reported cycle

struct Run {
  Model model;
  NormalResult normal;
  IncrementalResult r;
};

// The wear stage's coupled response on the unworn contact: the first loading and two cycles; with `history`, the same
// under a load history with P out of phase with Q (P from 70 to 130 N/mm while Q swings ±25 N/mm, as
// examples/hertz_history_out_of_phase.json without its bulk stress), the first loading and two runs through it.
Run run(int cells, IncrementalSlipOptions o, bool history = false) {
  Scene s = test::hertz_cycle(kP, kRatio, cells);
  s.specimen = kAluminium;
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  const NormalCoupling coupling{m.pair.beta(), m.g0};
  CyclicLoad load{s.P, s.Q_max(), *s.friction, 0.0};
  if (history)
    load.history = {{0, 1e5, 2.5e4, 0}, {1, 7e4, 0, 0}, {2, 1e5, -2.5e4, 0}, {3, 1.3e5, 0, 0}, {4, 1e5, 2.5e4, 0}};
  o.cycles = 2;
  const IncrementalSlipSolver solver(*m.kernel, o);
  IncrementalResult r = history ? solver.solve_history(n.state, load, m.g0, nullptr, &coupling)
                                : solver.solve(n.state, load, nullptr, &coupling);
  return {std::move(m), std::move(n), std::move(r)};
}

// The two runs report the same cycle: energy, shear at the top, stick zone, pressure at the top.
void check_same_cycle(const Run& a, const Run& b) {
  const CycleResult& ca = a.r.cycles.back();
  const CycleResult& cb = b.r.cycles.back();
  const double p0 = closed_form::hertz(kP, a.model.pair.A(), test::kHertzR).p0;
  const double h = a.model.grid.h();
  MESSAGE(fmt::format("energy {:.10g} against {:.10g} J/m ({:.3g}); top shear {:.3g} p0, top pressure {:.3g} p0 apart",
                      cb.dissipated_energy, ca.dissipated_energy, cb.dissipated_energy / ca.dissipated_energy - 1.0,
                      max_abs_diff(ca.q_top, cb.q_top) / p0, max_abs_diff(a.r.p_top, b.r.p_top) / p0));
  CHECK(cb.dissipated_energy == test::rel(ca.dissipated_energy, kEnergyAgreement));
  CHECK(max_abs_diff(ca.q_top, cb.q_top) < kTractionAgreement * p0);
  CHECK(max_abs_diff(a.r.p_top, b.r.p_top) < kTractionAgreement * p0);
  REQUIRE(ca.stick_zone);
  REQUIRE(cb.stick_zone);
  CHECK(std::abs(ca.stick_zone->first - cb.stick_zone->first) < 1e-3 * h);
  CHECK(std::abs(ca.stick_zone->second - cb.stick_zone->second) < 1e-3 * h);
}

}  // namespace

TEST_CASE("coupled increments: the predicted start reaches the same cycle in fewer sweeps") {
  IncrementalSlipOptions plain;
  plain.predict_increments = false;
  const Run a = run(512, plain);
  const Run b = run(512, {});
  MESSAGE(fmt::format("sweeps over {} increments: {} from the increment's start, {} from the predicted one; CG "
                      "iterations {} and {}",
                      a.r.n_increments, a.r.n_coupling_sweeps, b.r.n_coupling_sweeps, a.r.n_iterations,
                      b.r.n_iterations));
  REQUIRE(a.r.n_increments == b.r.n_increments);
  check_same_cycle(a, b);
  // Measured 5.7 sweeps an increment from the start and 5.1 from the prediction at 1024 cells.
  CHECK(b.r.n_coupling_sweeps < 0.95 * a.r.n_coupling_sweeps);
  CHECK(b.r.n_iterations < a.r.n_iterations);
}

TEST_CASE("coupled increments: a settling march of four increments leaves the same steady cycle, under a constant "
          "amplitude and under a load history") {
  IncrementalSlipOptions settle;
  settle.settling_increments = 4;
  for (const bool history : {false, true}) {
    CAPTURE(history);
    const Run a = run(512, {}, history);
    const Run b = run(512, settle, history);
    MESSAGE(fmt::format("{}: increments {} marching every cycle at 40, {} settling at 4",
                        history ? "history" : "amplitude", a.r.n_increments, b.r.n_increments));
    // The first loading in one increment, the first cycle in four (the history's four segments one each), the
    // reported cycle in the scene's 40. A history marches on until its last cycle ends in the traction it began from
    // or repeats the one before it at the scene's increments (IncrementalSlipOptions::steady_cycles_max): marched at
    // 40 throughout its second cycle ends where it began; after the settling march, whose first cycle leaves another
    // traction to 1e-6, one cycle more.
    CHECK(a.r.n_increments == 10 + 40 + 40);
    CHECK(b.r.n_increments == 1 + 4 + 40 + (history ? 40 : 0));
    if (history) CHECK(a.r.repeated);
    if (history) CHECK(b.r.repeated);
    check_same_cycle(a, b);
  }
}

TEST_CASE("coupled increments: settling_increments must be a multiple of 4") {
  IncrementalSlipOptions o;
  o.settling_increments = 6;
  CHECK(o.validate().find("settling_increments = 6") != std::string::npos);
  o.settling_increments = 8;
  CHECK(o.validate().empty());
}

TEST_CASE("coupled increments: a wear response settles in five increments and answers as the cycle stage") {
  Scene s = test::hertz_wear(kP, kRatio, 1e5, 512);
  s.specimen = kAluminium;
  const Model model = make_model(s);
  const NormalResult normal = solve_normal(s, model);
  const CycleStage cycle = solve_cycle(s, model, normal);  // 10 + 40 + 40 increments
  REQUIRE(cycle.plan.beta != 0.0);
  IncrementalContactResponse contact(s, model, cycle, IncrementalContactResponse::Coupling::every_response);
  wear::CycleResponse out;
  contact.respond(std::vector<double>(std::size_t(model.grid.n), 0.0), out);
  // One normal solve on the (unworn) profile, then 1 + 4 settling increments and half the scene's 40, mirrored
  // (test_coupled_mirror.cpp).
  CHECK(contact.cycle_solves == 1 + 1 + 4 + 20);
  const CycleResult& c = contact.last_cycle();
  MESSAGE(fmt::format("energy {:.10g} J/m against the cycle stage's {:.10g} ({:.3g})", c.dissipated_energy,
                      cycle.result.dissipated_energy, c.dissipated_energy / cycle.result.dissipated_energy - 1.0));
  CHECK(c.dissipated_energy == test::rel(cycle.result.dissipated_energy, kEnergyAgreement));
  const double p0 = closed_form::hertz(kP, model.pair.A(), test::kHertzR).p0;
  CHECK(max_abs_diff(c.q_top, cycle.result.q_top) < kTractionAgreement * p0);
}
