// The fretting loop on the incremental route: Q against the relative tangential displacement δ of the reference
// points (contact/reference_datum.hpp), for the public Hertz case under force control.
//
// Tolerances. The discrete fully stuck compliance (all contact cells stuck) differs from the closed form by the
// grid's treatment of the square-root edges of q = Q/(π√(a² − x²)): measured 3.9e-4 relative on 1024 cells and
// 6.3e-5 on 2048. The loop's first unloading slope is not quite the discrete stuck one: the outermost cells, where
// p → 0, reverse their slip at once for any ΔQ, so the slope is that of a contact a cell or so narrower; it is
// 3.9e-4 from the closed form on 1024 cells and 2.0e-4 on 2048 (and does not change from 400 to 1600 increments
// per cycle, so it is no increment error). kStuckGrid = 1e-3 covers both.
// The loop's area ∮ Q dδ against the dissipated energy: the rigid shift λ is work-conjugate to Q in the half-plane
// model (∮ Q dλ is the dissipation exactly), δ = λ + D(q) is not quite, because the datum's weights vary over the
// contact by O((a/d)²). Measured with 400 increments: area/dissipation − 1 = 1.38e-3 at d = 10a, 1.2e-5 at d = 100a
// (the trapezoidal rule adds 3e-5 of that at 400 increments: 1600 give the same to 3e-5). So the tolerance is
// 0.3 (a/d)².
#include <algorithm>
#include <cmath>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/incremental_slip.hpp"
#include "contact/reference_datum.hpp"
#include "engine/simulation.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kSolver = 1e-6;       // a hundred times the CG tolerance (relative to an increment)
constexpr double kStuckGrid = 1e-3;
double loop_area_tolerance(double a, double d) { return 0.3 * (a / d) * (a / d); }

CyclicLoad cyclic_load(const Scene& s, const Model& m) {
  const double strain = s.bulk_stress * (m.pair.kappa_specimen() + 1.0) / (8.0 * m.pair.mu_specimen());
  return {s.P, s.Q_max(), *s.friction, strain};
}

// ∮ Q dδ by the trapezoidal rule over the loop's points.
double loop_area(const std::vector<LoopPoint>& loop) {
  double w = 0.0;
  for (std::size_t k = 1; k < loop.size(); ++k)
    w += 0.5 * (loop[k].Q + loop[k - 1].Q) * (loop[k].delta - loop[k - 1].delta);
  return w;
}

// The discrete fully stuck compliance: one increment from rest with a friction too large to slip anywhere.
double stuck_compliance(const Model& m, const NormalResult& n, const ReferenceDatum& datum, double Q) {
  const IncrementalSlipSolver solver(*m.kernel);
  IncrementState state;
  const SolveSummary s = solver.solve_increment(n.state.p, 1e6, {Q, 0.0, 0.0, 0.0}, state);
  REQUIRE(s.converged());
  for (double dw : state.dw) REQUIRE(dw == 0.0);
  const std::vector<double> zero(m.grid.n, 0.0);
  const double D = datum.relative_displacement(state.q, n.state.p) - datum.relative_displacement(zero, n.state.p);
  return (state.shift + D) / Q;
}

}  // namespace

TEST_CASE("fretting loop: Hertz, force control - the unloading slope is the stuck compliance, the area the energy") {
  double last_slope_error = 1.0;
  for (int cells : {1024, 2048}) {
    CAPTURE(cells);
    const Scene s = test::hertz_cycle(1e5, 0.6, cells);
    const Model m = make_model(s);
    const NormalResult n = solve_normal(s, m);
    const double a = 0.5 * (n.zones.back().right.x - n.zones.front().left.x);
    const double x_c = 0.5 * (n.zones.back().right.x + n.zones.front().left.x);
    const auto hz = closed_form::hertz(s.P, m.pair.A(), s.profile.R);
    for (double depth : {10.0, 100.0}) {
      CAPTURE(depth);
      const double d = depth * a;
      const ReferenceDatum datum(m.grid, m.pair, x_c, d);
      IncrementalSlipOptions o;
      o.increments_per_cycle = 400;
      const IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve(n.state, cyclic_load(s, m), &datum);
      const CycleResult& c = r.cycles.back();
      REQUIRE(c.loop.size() == 401);
      REQUIRE(c.first_loading.size() == 101);

      // The cycle starts where the first loading ended, and closes; the bottom is the top reversed.
      CHECK(c.loop.front().delta == test::rel(c.first_loading.back().delta, kSolver));
      CHECK(c.loop.back().delta == test::rel(c.loop.front().delta, kSolver));
      CHECK(c.loop[200].delta == test::rel(-c.loop.front().delta, kSolver));
      CHECK(c.delta_max == test::rel(c.loop.front().delta, kSolver));

      // The slope at the start of unloading.
      const double slope = (c.loop[1].delta - c.loop[0].delta) / (c.loop[1].Q - c.loop[0].Q);
      const double stuck = stuck_compliance(m, n, datum, 0.01 * s.Q_max());
      const double closed = hertz_stuck_compliance(m.pair.A(), m.pair.mu_specimen(), hz.a, d);
      const double area = loop_area(c.loop);
      MESSAGE(fmt::format("{} cells, d = {} a: unloading slope {:.10g} m²/N ({:.3g} rel from the closed form), "
                          "discrete stuck {:.10g} ({:.3g} rel), closed form {:.10g}; loop area {:.10g} J/m, "
                          "dissipated {:.10g} J/m ({:.3g} rel); delta_max {:.6g} m",
                          cells, depth, slope, slope / closed - 1.0, stuck, stuck / closed - 1.0, closed, area,
                          c.dissipated_energy, area / c.dissipated_energy - 1.0, c.delta_max));
      CHECK(slope == test::rel(closed, kStuckGrid));
      CHECK(stuck == test::rel(closed, kStuckGrid));
      CHECK(area == test::rel(c.dissipated_energy, loop_area_tolerance(a, d)));
      if (depth == 10.0) {
        CHECK(std::abs(slope / closed - 1.0) < last_slope_error);  // converges with the grid
        last_slope_error = std::abs(slope / closed - 1.0);
      }
    }
  }
}

// Displacement control (load.control "displacement"): δ of the datum cycles 0 → +δ → −δ → +δ and each increment
// finds the Q that gives it. Tolerances: the root find stops when δ is within 10 × 1e-8 of the increment's Δδ, so Q
// and the traction agree with force control at the same Q_max to about 1e-7 relative; measured (1024 cells, 80
// increments): q_top 1.2e-7 f p0, energy 6e-9 relative. kAgreeForce = 1e-6 (of f p0, and relative).
namespace {

constexpr double kAgreeForce = 1e-6;

struct DisplacementRun {
  Model model;
  NormalResult normal;
  IncrementalResult result;
  double a = 0.0;
};

DisplacementRun run_displacement(double delta, int cycles = 1, int cells = 1024) {
  Scene s = test::hertz_cycle(1e5, 0.0, cells);
  s.Q_ratio.reset();
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  const double a = 0.5 * (n.zones.back().right.x - n.zones.front().left.x);
  const ReferenceDatum datum(m.grid, m.pair, 0.0, 10.0 * a);
  IncrementalSlipOptions o;
  o.increments_per_cycle = 80;
  o.cycles = cycles;
  CyclicLoad load{s.P, 0.0, *s.friction, 0.0, delta};
  IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve(n.state, load, &datum);
  return {std::move(m), std::move(n), std::move(r), a};
}

}  // namespace

TEST_CASE("displacement control: below the stick limit it is the force-controlled cycle with the same Q_max") {
  const double delta = 0.5e-6;
  const DisplacementRun d = run_displacement(delta);
  const CycleResult& c = d.result.cycles.back();
  CHECK(c.regime == Regime::partial_slip);
  CHECK(c.sliding_amplitude == 0.0);
  CHECK(c.delta_max == test::rel(delta, kAgreeForce));
  const double Q_max = c.Q_peak;
  REQUIRE(Q_max > 0.0);
  REQUIRE(Q_max < 0.5 * 1e5);

  // Force control at that Q_max on the same model.
  const ReferenceDatum datum(d.model.grid, d.model.pair, 0.0, 10.0 * d.a);
  IncrementalSlipOptions o;
  o.increments_per_cycle = 80;
  const IncrementalResult fr =
      IncrementalSlipSolver(*d.model.kernel, o).solve(d.normal.state, {1e5, Q_max, test::kHertzF, 0.0}, &datum);
  const CycleResult& f = fr.cycles.back();
  const auto hz = closed_form::hertz(1e5, d.model.pair.A(), test::kHertzR);
  const double dq = max_abs_diff(c.q_top, f.q_top) / (test::kHertzF * hz.p0);
  const double dq_bottom = max_abs_diff(c.q_bottom, f.q_bottom) / (test::kHertzF * hz.p0);
  MESSAGE(fmt::format("delta = {} m: Q_max/fP = {:.8f}; against force control: q_top {:.3g} f p0, q_bottom {:.3g} "
                      "f p0, energy {:.10g} vs {:.10g} J/m, delta at the top {:.10g} m; {} CG iterations over {} "
                      "increments (force control {})",
                      delta, Q_max / (test::kHertzF * 1e5), dq, dq_bottom, c.dissipated_energy, f.dissipated_energy,
                      f.delta_max, d.result.n_iterations, d.result.n_increments, fr.n_iterations));
  CHECK(dq < kAgreeForce);
  CHECK(dq_bottom < kAgreeForce);
  CHECK(c.dissipated_energy == test::rel(f.dissipated_energy, kAgreeForce));
  CHECK(c.slip_max == test::rel(f.slip_max, kAgreeForce));
  CHECK(f.delta_max == test::rel(delta, kAgreeForce));
  REQUIRE(c.stick_zone);
  REQUIRE(f.stick_zone);
  CHECK(std::abs(c.stick_zone->second - f.stick_zone->second) < 1e-3 * d.model.grid.h());
  // Hertz: the stick zone of that Q_max, c/a = √(1 − Q_max/fP).
  CHECK(std::abs(c.stick_zone->second - hz.a * std::sqrt(1.0 - Q_max / (test::kHertzF * 1e5))) <
        0.25 * d.model.grid.h());
}

TEST_CASE("displacement control: through the onset of gross slip Q saturates at fP and the sliding grows linearly") {
  const double fP = test::kHertzF * 1e5;
  // The stick limit δ_s: the amplitude beyond which the steady cycle slides (δ − sliding amplitude, any δ above it).
  const DisplacementRun ref = run_displacement(2e-6);
  const CycleResult& r2 = ref.result.cycles.back();
  REQUIRE(r2.regime == Regime::gross_slip);
  const double delta_s = 2e-6 - r2.sliding_amplitude;
  MESSAGE(fmt::format("stick limit delta_s = {:.8g} m", delta_s));
  double last_Q = 0.0;
  for (double delta : {0.6e-6, 0.9 * delta_s, 0.99 * delta_s, 1.01 * delta_s, 1.2 * delta_s, 3e-6}) {
    CAPTURE(delta);
    const DisplacementRun d = run_displacement(delta, 2);
    const CycleResult& c1 = d.result.cycles[0];
    const CycleResult& c = d.result.cycles[1];
    MESSAGE(fmt::format("delta = {:.6g} m ({:.4f} delta_s): {}, Q_max/fP = {:.10f}, sliding amplitude {:.6g} m, "
                        "slip_max {:.6g} m, energy {:.6g} J/m",
                        delta, delta / delta_s, to_string(c.regime), c.Q_peak / fP, c.sliding_amplitude, c.slip_max,
                        c.dissipated_energy));
    CHECK(std::isfinite(c.dissipated_energy));
    CHECK(std::isfinite(c.slip_max));
    CHECK(c.Q_peak >= last_Q);
    last_Q = c.Q_peak;
    // The cycle closes: the second repeats the first, and the loop ends where it began.
    CHECK(std::abs(c.dissipated_energy - c1.dissipated_energy) < kAgreeForce * c1.dissipated_energy);
    CHECK(max_abs_diff(c.q_top, c1.q_top) < kAgreeForce * fP / (2 * d.a));
    CHECK(std::abs(c.loop.back().delta - c.loop.front().delta) < kAgreeForce * delta);
    CHECK(std::abs(c.loop.back().Q - c.loop.front().Q) < kAgreeForce * fP);
    if (delta < delta_s) {
      CHECK(c.regime == Regime::partial_slip);
      CHECK(c.Q_peak < fP);
      CHECK(c.sliding_amplitude == 0.0);
      CHECK(c.stick_zone);
    } else {
      CHECK(c.regime == Regime::gross_slip);
      CHECK(c.Q_peak == test::rel(fP, 1e-12));
      CHECK_FALSE(c.stick_zone);
      CHECK(c.stick_zones.empty());  // none listed either (summary: cycle.stick_zones)
      // Linear beyond the stick limit: the sliding amplitude is δ − δ_s; each point's slip range grows by 2(δ − δ')
      // and the energy by 4 f P (δ − δ').
      CHECK(c.sliding_amplitude == test::rel(delta - delta_s, kAgreeForce));
      CHECK(c.slip_max - r2.slip_max == test::rel(2.0 * (delta - 2e-6), kAgreeForce));
      CHECK(c.dissipated_energy - r2.dissipated_energy == test::rel(4.0 * fP * (delta - 2e-6), kAgreeForce));
    }
  }
}

TEST_CASE("fretting loop: the analogy route's delta_max is the incremental route's") {
  // The analogy gives δ at the top from the steady stick zone (never slipped, w = 0): λ = (K q_top)_i there.
  Scene s = test::hertz_cycle(1e5, 0.6, 1024);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  s.tangential->route = TangentialRoute::analogy;
  const CycleStage analogy = solve_cycle(s, m, n);
  s.tangential->route = TangentialRoute::incremental;
  const CycleStage incremental = solve_cycle(s, m, n);
  MESSAGE(fmt::format("delta_max: analogy {:.10g} m, incremental {:.10g} m", analogy.result.delta_max,
                      incremental.result.delta_max));
  CHECK(analogy.route == "analogy");
  CHECK(analogy.result.delta_max > 0.0);
  CHECK(analogy.result.delta_max == test::rel(incremental.result.delta_max, kAgreeForce));
  const double a = 0.5 * (n.zones.back().right.x - n.zones.front().left.x);
  CHECK(incremental.reference_depth == test::rel(10.0 * a, 1e-15));
}
