// Load histories (load.history) on the incremental route (contact/incremental_slip.hpp, solve_history): a history
// that is the default in-phase cycle gives the force-control route's cycle, a normal load that drops under a
// constant Q makes the edges slip, and the steady cycle closes.
//
// Tolerances. The in-phase history [top, bottom, top] with `increments` m puts its increments exactly where the
// force-control route puts them (the first loading in m/4 steps, each half cycle in m/2), so both solve the same
// sequence of programs and agree to round-off (σ enters as ε by another product): measured 1.2e-12 f p0 in q
// and 1e-15 relative in energy; kSame = 1e-10.
// A closed cycle repeats once steady: the energy to 1e-12 relative (kRepeat = 1e-9); the traction to the CG
// tolerance (1e-8 of an increment), measured 8.4e-8 f p0 (kRepeatTraction = 1e-6 f p0, as test_cycle_incremental's).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/normal_stage.hpp"
#include "engine/simulation.hpp"
#include "engine/warnings.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kSame = 1e-10;
constexpr double kRepeat = 1e-9;
constexpr double kRepeatTraction = 1e-6;

// The shakedown history: P from 1 to 0.6 and back under a constant Q, [t, P, Q, σ] as the scene gives it, and as
// the solver's load.
std::vector<std::array<double, 4>> shakedown_points(double P, double Q) {
  return {{0.0, P, Q, 0.0}, {1.0, 0.6 * P, Q, 0.0}, {2.0, P, Q, 0.0}};
}
CyclicLoad shakedown_load(double P, double Q) {
  CyclicLoad load{P, 0.0, test::kHertzF, 0.0, 0.0, {}};
  for (const auto& pt : shakedown_points(P, Q)) load.history.push_back({pt[0], pt[1], pt[2], 0.0});  // σ = 0
  return load;
}

}  // namespace

TEST_CASE("load history: the in-phase cycle as a history is the force-controlled cycle") {
  const double P = 1e5;
  const auto hz = closed_form::hertz(P, 4 * (1 - test::kHertzNu * test::kHertzNu) / test::kHertzE, test::kHertzR);
  const double Q = 0.5 * test::kHertzF * P, sigma = 0.6 * test::kHertzF * hz.p0;  // Nowell–Hills, PHYSICS.md
  Scene force = test::hertz_cycle(P, 0.5, 1024, sigma);
  force.tangential->route = TangentialRoute::incremental;
  Scene history = test::hertz_cycle(P, 0.0, 1024);
  history.Q_ratio.reset();
  history.history = {{0.0, P, Q, sigma}, {1.0, P, -Q, -sigma}, {2.0, P, Q, sigma}};
  const Model m = make_model(force);
  const NormalResult n = solve_normal(force, m);
  const CycleStage a = solve_cycle(force, m, n);
  const CycleStage b = solve_cycle(history, m, n);
  CHECK(b.route == "incremental (auto: load history)");
  const double dq = max_abs_diff(a.result.q_top, b.result.q_top) / (test::kHertzF * hz.p0);
  const double dq_unloaded = max_abs_diff(a.result.q_unloaded, b.result.q_unloaded) / (test::kHertzF * hz.p0);
  MESSAGE(fmt::format("history vs force control: q_top {:.3g} f p0, q_unloaded {:.3g} f p0, energy {:.12g} vs {:.12g} "
                      "J/m, delta_max {:.12g} vs {:.12g} m, stick zone [{:.6f}, {:.6f}] a",
                      dq, dq_unloaded, b.result.dissipated_energy, a.result.dissipated_energy, b.result.delta_max,
                      a.result.delta_max, b.result.stick_zone->first / hz.a, b.result.stick_zone->second / hz.a));
  CHECK(dq < kSame);
  CHECK(dq_unloaded < kSame);
  CHECK(max_abs_diff(a.result.q_bottom, b.result.q_bottom) < kSame * test::kHertzF * hz.p0);
  CHECK(b.result.dissipated_energy == test::rel(a.result.dissipated_energy, kSame));
  CHECK(b.result.slip_max == test::rel(a.result.slip_max, kSame));
  CHECK(b.result.delta_max == test::rel(a.result.delta_max, kSame));
  CHECK(b.Q_max == test::rel(Q, kSame));
  REQUIRE(b.result.stick_zone);
  CHECK(std::abs(b.result.stick_zone->first + 0.557107 * hz.a) < 0.25 * m.grid.h());
  CHECK(std::abs(b.result.stick_zone->second - 0.857107 * hz.a) < 0.25 * m.grid.h());
}

TEST_CASE("load history: a constant Q while P drops and recovers slips the edges once, then shakes down") {
  // For uncoupled bodies (β = 0) Melan's theorem holds with Coulomb friction (Klarbring, Ciavarella and Barber 2007,
  // Int. J. Solids Struct. 44): if a residual traction exists under which no cell slips, the contact shakes down.
  // Under a constant Q the first drop of P slips the edges and leaves that residual state: no slip afterwards.
  const double P = 1e5, Q = 0.4 * test::kHertzF * P;
  Scene s = test::hertz_cycle(P, 0.0, 1024);
  s.Q_ratio.reset();
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CyclicLoad load = shakedown_load(P, Q);
  IncrementalSlipOptions o;
  o.cycles = 3;
  const IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve_history(n.state, load, m.g0);
  REQUIRE(r.cycles.size() == 3);
  const CycleResult& c1 = r.cycles[0];
  const auto hz = closed_form::hertz(P, m.pair.A(), test::kHertzR);
  const auto hz_low = closed_form::hertz(0.6 * P, m.pair.A(), test::kHertzR);
  double x_slip_min = hz.a;
  for (int i = 0; i < m.grid.n; ++i)
    if (c1.slip_travelled[i] > 0.0) x_slip_min = std::min(x_slip_min, std::abs(m.grid.x(i)));
  MESSAGE(fmt::format("constant Q = 0.4 fP, P down to 0.6 P and back: energy per cycle {:.6g}, {:.3g}, {:.3g} J/m; "
                      "slip_max in cycle 1 {:.6g} m, slipping cells from |x| = {:.4f} a (contact at 0.6 P: {:.4f} a); "
                      "{} increments",
                      c1.dissipated_energy, r.cycles[1].dissipated_energy, r.cycles[2].dissipated_energy, c1.slip_max,
                      x_slip_min / hz.a, hz_low.a / hz.a, r.n_increments));
  CHECK(c1.regime == Regime::partial_slip);
  CHECK(c1.dissipated_energy > 0.0);
  CHECK(c1.slip_max > 0.0);
  CHECK(x_slip_min > 0.5 * hz_low.a);  // the edges slip, the centre sticks
  CHECK(x_slip_min < hz_low.a);        // and slip reaches inside the smallest contact
  for (double e : c1.energy_density) CHECK(e >= 0.0);
  double load_top = 0.0;  // h Σ q = Q at every increment
  for (double q : c1.q_top) load_top += q * m.grid.h();
  CHECK(load_top == test::rel(Q, 1e-12));
  // Shakedown: nothing slips in the later cycles, which repeat each other.
  for (int k : {1, 2}) {
    CAPTURE(k);
    CHECK(r.cycles[k].dissipated_energy <= kRepeat * c1.dissipated_energy);
    CHECK(r.cycles[k].slip_max <= kRepeat * c1.slip_max);
  }
  CHECK(max_abs_diff(r.cycles[2].q_top, r.cycles[1].q_top) < kRepeatTraction * test::kHertzF * hz.p0);

  // Without the drop of P nothing slips at all.
  CyclicLoad steady = load;
  steady.history = {{0.0, P, Q, 0.0}, {1.0, P, Q, 0.0}};
  const IncrementalResult still = IncrementalSlipSolver(*m.kernel).solve_history(n.state, steady, m.g0);
  CHECK(still.cycles.back().dissipated_energy == 0.0);
  CHECK(still.cycles.back().slip_max == 0.0);
}

TEST_CASE("load history: a history that shakes down is reported, and worn, by its steady cycle") {
  // The history of the test above, through the whole run: its first cycle slips the edges; the second slips
  // nothing, ends in the traction it began from, and is the steady cycle (shakedown). The steady cycle the stage
  // reports, the second, dissipates nothing, and 10^7 cycles of it wear
  // nothing; the first cycle's energy, worn instead, would wear as much as a constant cycle at Q/fP = 0.2 does in
  // about a fifth of the cycles. Two periods of the history as one give the same steady cycle.
  const double P = 1e5, Q = 0.4 * test::kHertzF * P;
  Scene s = test::hertz_wear(P, 0.0, 1e7, 1024);
  s.Q_ratio.reset();
  s.history = shakedown_points(P, Q);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CyclicLoad load = shakedown_load(P, Q);
  IncrementalSlipOptions first_only;
  first_only.steady_cycles_max = 0;
  const IncrementalResult first = IncrementalSlipSolver(*m.kernel, first_only).solve_history(n.state, load, m.g0);
  REQUIRE(first.cycles.size() == 1);
  const double e1 = first.cycles[0].dissipated_energy;
  REQUIRE(e1 > 0.0);

  const RunResult r = Simulation(s).run();
  REQUIRE(r.cycle);
  REQUIRE(r.wear);
  Scene twice = s;
  twice.wear.reset();
  twice.history = {{0.0, P, Q, 0.0}, {1.0, 0.6 * P, Q, 0.0}, {2.0, P, Q, 0.0}, {3.0, 0.6 * P, Q, 0.0}, {4.0, P, Q, 0.0}};
  const RunResult r2 = Simulation(twice).run();
  const double worn = r.wear->records.back().worn_area;
  MESSAGE(fmt::format("P down to 0.6 P and back under Q = 0.4 fP: first cycle {:.6g} J/m; steady cycle {:.3g} J/m "
                      "after {} cycles (two periods: {:.3g} J/m after {}); worn area after 1e7 cycles {:.3g} m^2",
                      e1, r.cycle->result.dissipated_energy, r.cycle->history_cycles,
                      r2.cycle->result.dissipated_energy, r2.cycle->history_cycles, worn));
  CHECK(r.cycle->history_steady);
  CHECK(r.cycle->history_cycles == 2);
  const nlohmann::json summary = make_summary(s, r);
  CHECK(summary.at("cycle").at("history_cycles") == 2);
  CHECK(summary.at("cycle").at("history_steady") == true);
  CHECK(r.cycle->result.dissipated_energy <= kRepeat * e1);
  CHECK(r.cycle->result.slip_max <= kRepeat * first.cycles[0].slip_max);
  CHECK(r2.cycle->history_steady);
  CHECK(r2.cycle->result.dissipated_energy <= kRepeat * e1);
  // Archard under a history wears k ∫ e/f over the cycles: the first cycle's energy would give about
  // k · 1e7 · e1 / f of worn area; the steady one gives none.
  const double first_cycle_wear = 1e-12 * 1e7 * e1 / test::kHertzF;
  CHECK(worn <= kRepeat * first_cycle_wear);
  CHECK(r.wear->unsteady_history_responses == 0);
  const std::vector<Warning> warnings = result_warnings(s, r);
  CHECK(std::none_of(warnings.begin(), warnings.end(), [](const Warning& w) { return w.code == "history_unsteady"; }));
}

TEST_CASE("load history: a march capped before its cycle repeats says so, and the run warns") {
  const double P = 1e5, Q = 0.4 * test::kHertzF * P;
  Scene s = test::hertz_cycle(P, 0.0, 256);
  s.Q_ratio.reset();
  s.history = shakedown_points(P, Q);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CyclicLoad load = shakedown_load(P, Q);
  IncrementalSlipOptions capped;
  capped.steady_cycles_max = 1;  // the first cycle slips and the second does not: one cycle cannot show it repeats
  const IncrementalResult r = IncrementalSlipSolver(*m.kernel, capped).solve_history(n.state, load, m.g0);
  CHECK(r.cycles.size() == 1);
  CHECK(!r.repeated);
  RunResult run;
  run.normal = n;
  run.cycle = solve_cycle(s, m, n);
  CHECK(run.cycle->history_steady);
  run.cycle->history_steady = false;
  const std::vector<Warning> warnings = result_warnings(s, run);
  const auto warned = std::find_if(warnings.begin(), warnings.end(),
                                   [](const Warning& w) { return w.code == "history_unsteady"; });
  REQUIRE(warned != warnings.end());
  CHECK(warned->message.find("may not be the steady one") != std::string::npos);
}

TEST_CASE("load history: a cycle that ends in the traction it began from is the steady one, and the march stops there") {
  // The next cycle starts from the same state under the same loads, so it repeats this one (Run::closed): marched
  // anyway it does, to the CG tolerance. Out of phase from the top of Q, the first loading (Q from 0 up to the first
  // point under P) already leaves the steady cycle's traction, so its first cycle closes; the shakedown's first cycle
  // slips and its second, which slips nothing, closes.
  const double P = 1e5;
  Scene s = test::hertz_cycle(P, 0.0, 512);
  s.Q_ratio.reset();
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const auto hz = closed_form::hertz(P, m.pair.A(), test::kHertzR);
  const double Q = 0.5 * test::kHertzF * P;
  const CyclicLoad out_of_phase{P, 0.0, test::kHertzF, 0.0, 0.0,
                                {{0.0, P, Q, 0.0}, {1.0, 0.7 * P, 0.0, 0.0}, {2.0, P, -Q, 0.0},
                                 {3.0, 1.3 * P, 0.0, 0.0}, {4.0, P, Q, 0.0}}};
  const std::pair<const char*, CyclicLoad> cases[] = {{"out of phase", out_of_phase},
                                                      {"shakedown", shakedown_load(P, 0.4 * test::kHertzF * P)}};
  const int closes_after[] = {1, 2};
  for (int k = 0; k < 2; ++k) {
    const std::string name = cases[k].first;
    CAPTURE(name);
    const IncrementalResult r = IncrementalSlipSolver(*m.kernel).solve_history(n.state, cases[k].second, m.g0);
    IncrementalSlipOptions more;
    more.cycles = r.cycles_marched + 1;
    more.steady_cycles_max = 0;
    const IncrementalResult next = IncrementalSlipSolver(*m.kernel, more).solve_history(n.state, cases[k].second, m.g0);
    const CycleResult &c = r.cycles.back(), &c_next = next.cycles.back();
    const double dq = std::max(max_abs_diff(c_next.q_top, c.q_top), max_abs_diff(c_next.q_bottom, c.q_bottom)) /
                      (test::kHertzF * hz.p0);
    MESSAGE(fmt::format("{}: steady after {} cycles (energy {:.10g} J/m); the cycle after it: energy {:.10g} J/m, "
                        "top and bottom shear {:.3g} f p0 apart",
                        cases[k].first, r.cycles_marched, c.dissipated_energy, c_next.dissipated_energy, dq));
    CHECK(r.repeated);
    CHECK(r.cycles_marched == closes_after[k]);
    CHECK(dq < kRepeatTraction);
    CHECK(std::abs(c_next.dissipated_energy - c.dissipated_energy) <=
          kRepeat * std::max(c.dissipated_energy, r.cycles.front().dissipated_energy));
  }
}

TEST_CASE("load history: Q cycling with P out of phase - the steady cycle closes and dissipates") {
  const double P = 1e5, Q = 0.5 * test::kHertzF * P;
  Scene s = test::hertz_cycle(P, 0.0, 1024);
  s.Q_ratio.reset();
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const auto hz = closed_form::hertz(P, m.pair.A(), test::kHertzR);
  const CyclicLoad load{P, 0.0, test::kHertzF, 0.0, 0.0,
                        {{0.0, P, Q, 0.0}, {1.0, 0.7 * P, 0.0, 0.0}, {2.0, P, -Q, 0.0}, {3.0, 1.3 * P, 0.0, 0.0},
                         {4.0, P, Q, 0.0}}};
  IncrementalSlipOptions o;
  o.cycles = 3;
  const IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve_history(n.state, load, m.g0);
  REQUIRE(r.cycles.size() == 3);
  const CycleResult& c2 = r.cycles[1];
  const CycleResult& c3 = r.cycles[2];
  const double dq = max_abs_diff(c3.q_top, c2.q_top) / (test::kHertzF * hz.p0);
  MESSAGE(fmt::format("Q = ±0.5 fP with P between 0.7 and 1.3 P out of phase: energy per cycle {:.10g}, {:.10g}, "
                      "{:.10g} J/m; cycle 3 vs 2: q_top {:.3g} f p0; slip_max {:.6g} m",
                      r.cycles[0].dissipated_energy, c2.dissipated_energy, c3.dissipated_energy, dq, c3.slip_max));
  CHECK(c3.dissipated_energy > 0.0);
  CHECK(dq < kRepeatTraction);
  CHECK(c3.dissipated_energy == test::rel(c2.dissipated_energy, kRepeat));
  CHECK(max_abs_diff(c3.slip_range, c2.slip_range) < kRepeat * c2.slip_max);
  CHECK(c3.loop.empty());  // no datum given
}

TEST_CASE("load history: with P out of phase the energy converges at first order in the increments, and says so") {
  // Where P moves within an increment a sliding cell's bound moves with it, and q Δw with the end's q is first order
  // (docs/METHODS.md, "Load histories"): the differences from 40 to 320 increments halve (measured at 512 cells:
  // observed orders 0.90 and 0.95), so the change from half the increments is about the error left, which the cycle
  // stage measures (CycleStage::history_energy) and the run warns of past 1 %: at 40 increments (3.2 %), not
  // at 320 (0.49 %).
  const double P = 1e5, Q = 0.5 * test::kHertzF * P;
  Scene s = test::hertz_cycle(P, 0.0, 512);
  s.Q_ratio.reset();
  s.history = {{0.0, P, Q, 0.0}, {1.0, 0.7 * P, 0.0, 0.0}, {2.0, P, -Q, 0.0}, {3.0, 1.3 * P, 0.0, 0.0}, {4.0, P, Q, 0.0}};
  std::vector<double> e;
  for (const int increments : {40, 80, 160, 320}) {
    s.tangential->increments = increments;
    const RunResult r = Simulation(s).run();
    REQUIRE(r.cycle);
    REQUIRE(r.cycle->history_energy.size() == 1);
    CHECK(r.cycle->history_energy[0].block == -1);
    CHECK(r.cycle->history_energy[0].energy == r.cycle->result.dissipated_energy);
    const double e_half = r.cycle->history_energy[0].energy_half;
    e.push_back(r.cycle->result.dissipated_energy);
    const std::vector<Warning> warnings = result_warnings(s, r);
    const bool warned = std::any_of(warnings.begin(), warnings.end(),
                                    [](const Warning& w) { return w.code == "history_increments"; });
    CAPTURE(increments);
    CHECK(warned == (std::abs(e.back() / e_half - 1.0) > kHistoryEnergyShare));
    if (increments == 40) CHECK(warned);
    if (increments == 320) CHECK(!warned);
  }
  const double order_1 = std::log2((e[1] - e[0]) / (e[2] - e[1])), order_2 = std::log2((e[2] - e[1]) / (e[3] - e[2]));
  MESSAGE(fmt::format("energy {:.8e}, {:.8e}, {:.8e}, {:.8e} J/m at 40 to 320 increments; observed orders {:.2f}, "
                      "{:.2f}",
                      e[0], e[1], e[2], e[3], order_1, order_2));
  CHECK(order_1 == doctest::Approx(1.0).epsilon(0.2));
  CHECK(order_2 == doctest::Approx(1.0).epsilon(0.2));
  // Measured: it rises toward its limit.
  CHECK(e[0] < e[1]);
  CHECK(e[1] < e[2]);
  CHECK(e[2] < e[3]);
}

TEST_CASE("load history: a history block of load.blocks is checked as the scene's own history is, and named") {
  // A constant block, then the out-of-phase history of the test above as a block of its own: the cycle stage solves
  // the first block, so it marches the history block at the scene's increments and at half of them (on the unworn
  // contact), and that energy is the one the history gives as the scene's own load.history on the same grid, to
  // round-off (the same march). The warning names the block; at 160 increments (0.5 % from 80 here) there is none.
  const double P = 1e5, Q = 0.5 * test::kHertzF * P;
  const std::vector<std::array<double, 4>> history = {
      {0.0, P, Q, 0.0}, {1.0, 0.7 * P, 0.0, 0.0}, {2.0, P, -Q, 0.0}, {3.0, 1.3 * P, 0.0, 0.0}, {4.0, P, Q, 0.0}};
  Scene own = test::hertz_cycle(P, 0.0, 256);
  own.Q_ratio.reset();
  own.history = history;
  Scene blocks = test::hertz_cycle(P, 0.3, 256);
  blocks.blocks = {LoadBlock{std::nullopt, 0.3, std::nullopt, {}, 100.0},
                   LoadBlock{std::nullopt, std::nullopt, std::nullopt, history, 100.0}};
  own.window = blocks.window = std::pair{-2e-4, 2e-4};  // one grid (a window chosen for P alone would differ)
  for (const int increments : {40, 160}) {
    own.tangential->increments = blocks.tangential->increments = increments;
    CAPTURE(increments);
    const Setup setup = make_setup(blocks);
    const NormalResult normal = solve_normal(blocks, setup.model);
    RunResult r;
    r.normal = normal;
    r.cycle = solve_cycle(blocks, setup.model, *setup.cycle, normal);
    REQUIRE(r.cycle->history_energy.size() == 1);
    const CycleStage::HistoryEnergy& h = r.cycle->history_energy[0];
    CHECK(h.block == 1);
    CHECK(h.half_increments == increments / 2);
    const RunResult alone = Simulation(own).run();
    REQUIRE(alone.cycle->history_energy.size() == 1);
    CHECK(h.energy == test::rel(alone.cycle->history_energy[0].energy, kSame));
    CHECK(h.energy_half == test::rel(alone.cycle->history_energy[0].energy_half, kSame));
    const std::vector<Warning> warnings = result_warnings(blocks, r);
    const auto warned = std::find_if(warnings.begin(), warnings.end(),
                                     [](const Warning& w) { return w.code == "history_increments"; });
    CHECK((warned != warnings.end()) == (increments == 40));
    if (warned != warnings.end()) CHECK(warned->message.find("load.blocks[1]") != std::string::npos);
  }
}

TEST_CASE("load history: a history that reaches |Q| >= fP is gross slip, reported without fields") {
  const double P = 1e5;
  Scene s = test::hertz_cycle(P, 0.0, 256);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CyclicLoad load{P, 0.0, test::kHertzF, 0.0, 0.0,
                        {{0.0, P, 0.4 * test::kHertzF * P, 0.0}, {1.0, 0.3 * P, 0.4 * test::kHertzF * P, 0.0},
                         {2.0, P, 0.4 * test::kHertzF * P, 0.0}}};
  const IncrementalResult r = IncrementalSlipSolver(*m.kernel).solve_history(n.state, load, m.g0);
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0].regime == Regime::gross_slip);
  CHECK(r.cycles[0].slip_range.empty());
  CHECK(r.cycles[0].message.find("t = 1") != std::string::npos);
}

// The progress of a history's march is told against the most it may march (engine/cycle_stage.cpp): that bound is
// what the march takes when it marches every cycle it may (steady_cycles_max reached, or 0 with `cycles` cycles,
// settling ones included), and more than it takes when a cycle repeats earlier.
TEST_CASE("load history: the most a march may take is what it takes when it marches every cycle it may") {
  const double P = 1e5, Q = 0.5 * test::kHertzF * P;
  Scene s = test::hertz_cycle(P, 0.0, 256);
  s.Q_ratio.reset();
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  // Segments of unequal length (0.7, 1.3 and 1 of the period's quarters), so that their increments round up.
  const CyclicLoad uneven{P, 0.0, test::kHertzF, 0.0, 0.0,
                          {{0.0, P, Q, 0.0}, {0.7, 0.7 * P, 0.0, 0.0}, {2.0, P, -Q, 0.0},
                           {3.0, 1.3 * P, 0.0, 0.0}, {4.1, P, Q, 0.0}}};
  struct Case {
    const char* name;
    CyclicLoad load;
    int cycles, steady_cycles_max, settling;
    bool every_cycle;  // the march takes every cycle it may
  };
  const Case cases[] = {{"uneven, exactly three cycles", uneven, 3, 0, 0, true},
                        {"uneven, two cycles, the first at 12 increments", uneven, 2, 0, 12, true},
                        {"shakedown capped at one cycle", shakedown_load(P, 0.4 * test::kHertzF * P), 1, 1, 0, true},
                        {"uneven, until it repeats", uneven, 1, 10, 0, false}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    IncrementalSlipOptions o;
    o.increments_per_cycle = 36;
    o.cycles = c.cycles;
    o.steady_cycles_max = c.steady_cycles_max;
    o.settling_increments = c.settling;
    int last_told = 0;
    o.after_increment = [&last_told](int marched) { last_told = marched; };
    const int at_most = IncrementalSlipSolver::history_increments_at_most(o, c.load.history);
    const IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve_history(n.state, c.load, m.g0);
    MESSAGE(fmt::format("{}: {} increments marched in {} cycles, at most {}", c.name, r.n_increments,
                        r.cycles_marched, at_most));
    CHECK(last_told == r.n_increments);
    if (c.every_cycle)
      CHECK(r.n_increments == at_most);
    else
      CHECK(r.n_increments < at_most);
  }
}
