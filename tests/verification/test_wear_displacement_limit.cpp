// The wear limit under displacement control below the stick limit (contact/displacement_limit.hpp,
// engine/wear_stage.cpp): the stuck compliance of a complete contact, the first cycle's Q0 by the analogy, the limit
// over its stick zone under Q = δ/C(Z0), the shrinking branch's root find, and a wear run approaching the limit.
//
// The public Hertz case (PHYSICS.md): R = 10 mm, E = 200 GPa, ν = 0.3, P = 100 kN/m, f = 0.5, a = 0.10764 mm; the
// datum 10 half-widths below the centre. Closed forms: a stuck complete contact over [−c, c] carries the flat-punch
// shear Q/(π√(c² − x²)), so its compliance is hertz_stuck_compliance(A, μ, c, d), Hertz's with a → c; the analogy's
// stick zone at Q is c/a = √(1 − Q/fP); the worn area of the complete contact over [−c, c] is PHYSICS.md's
// W = [a²(x_e arccosh(x_e/c) − √(x_e² − c²)) − (x_e² − c²)^{3/2}/3]/R with a² arccosh(x_e/c) = x_e √(x_e² − c²).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>
#include <doctest/doctest.h>
#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/displacement_limit.hpp"
#include "contact/wear_limit.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr double kE = 200e9, kNu = 0.3, kR = 0.01, kF = test::kHertzF, kP = 1e5;
const double kA = 4 * (1 - kNu * kNu) / kE, kMu = kE / (2 * (1 + kNu));
const double kA0 = closed_form::hertz(kP, kA, kR).a, kD = 10 * kA0;

double root(auto f, double lo, double hi) {
  std::uintmax_t it = 200;
  const auto [a, b] = boost::math::tools::toms748_solve(f, lo, hi, boost::math::tools::eps_tolerance<double>(50), it);
  return 0.5 * (a + b);
}

// PHYSICS.md's worn area of the complete contact over [−c, c] (header).
double hertz_worn_area(double c) {
  const double a = kA0;
  const double xe = root([&](double x) { return a * a * std::acosh(x / c) - x * std::sqrt(x * x - c * c); },
                         c * (1 + 1e-9), 10 * a);
  const double r = std::sqrt(xe * xe - c * c);
  return (a * a * (xe * std::acosh(xe / c) - r) - r * r * r / 3) / kR;
}

double hertz_c(double Q) { return kA0 * std::sqrt(1 - Q / (kF * kP)); }

// The Hertz case on n cells over ±1.5 a, and the analogy on it with the datum (0, 10 a).
struct Case {
  Model model;
  ReferenceDatum datum;
  AnalogyDisplacement analogy;
  explicit Case(int n)
      : model(make_model([n] {
          Scene s = test::hertz_cycle(kP, 0.5, n);
          s.window = std::pair{-1.5 * kA0, 1.5 * kA0};
          return s;
        }())),
        datum(model.grid, model.pair, 0.0, kD),
        analogy(model.grid, *model.kernel, model.g0, kP, kF, datum) {}
  double h_over_a() const { return model.grid.h() / kA0; }
};

// The observed order of an error measured at n and 8n cells (three halvings of h).
double order(double coarse, double fine) { return std::log2(std::abs(coarse / fine)) / 3.0; }

constexpr int kCoarse = 512, kFine = 4096;

}  // namespace

// The stuck compliance is a complete-contact solve (a flat punch over Z) and the datum's sum: the punch's
// square-root ends cost O(h) in both, so the error is first order: measured 4.04e-4, 2.02e-4, 1.01e-4, 5.06e-5 at
// 512 ... 4096 cells (0.069 h/a each time). Tolerances: kCompliance = 0.1 h/a at every grid, order within
// kOrder = 0.1 of one.
TEST_CASE("a stuck complete contact over [-c, c] has Hertz's stuck compliance with a -> c, to first order in h") {
  constexpr double kCompliance = 0.1, kOrder = 0.1;
  const double c = 0.6 * kA0, want = hertz_stuck_compliance(kA, kMu, c, kD);
  std::vector<double> errors;
  for (int n = kCoarse; n <= kFine; n *= 2) {
    const Case k(n);
    Zone z;
    z.left.x = -c, z.right.x = c;
    const double C = stuck_compliance(k.model.grid, k.model.pair, 0.0, kD, {z});
    errors.push_back(C / want - 1.0);
    MESSAGE(fmt::format("{} cells: C = {:.9e} m²/N, closed form {:.9e} ({:+.3e} = {:.3f} h/a)", n, C, want,
                        errors.back(), errors.back() / k.h_over_a()));
    CHECK(std::abs(errors.back()) < kCompliance * k.h_over_a());
  }
  CHECK(order(errors.front(), errors.back()) == doctest::Approx(1.0).epsilon(kOrder));
}

// The first cycle's Q0 by the analogy's δ_top(Q) against the incremental route, which marches the cycle under the
// prescribed δ with the same datum: the same cycle (the README's force-controlled cycle at that Q), measured 1.4e-7
// apart at 1024 cells (the incremental route solves δ per increment to about 1e-7: test_cycle_dissimilar.cpp); the
// stick limit δ_s against δ − the sliding amplitude of a gross-slip cycle, the same limit reached from above.
TEST_CASE("the first cycle under displacement control: the analogy's Q0 and stick limit are the incremental cycle's") {
  constexpr double kSameCycle = 1e-6;
  for (const double delta : {0.5e-6, 1e-6, 2e-6}) {
    CAPTURE(delta);
    Scene s = test::hertz_cycle(kP, 0.0, 1024);
    s.Q_ratio.reset();
    s.control = LoadControl::displacement;
    s.delta = delta;
    s.tangential->increments = 80;
    const Model m = make_model(s);
    const NormalResult n = solve_normal(s, m);
    const CycleStage cycle = solve_cycle(s, m, n);
    const ReferenceDatum datum(m.grid, m.pair, cycle.reference_x, cycle.reference_depth);
    const AnalogyDisplacement analogy(m.grid, *m.kernel, m.g0, kP, kF, datum);
    if (delta < analogy.stick_limit()) {
      REQUIRE(cycle.result.regime == Regime::partial_slip);
      const AnalogyTop top = analogy.at_displacement(delta);
      MESSAGE(fmt::format("delta {:g}: Q0 = {:.9g} N/m (analogy), {:.9g} (incremental); stick zone {:.6e} vs {:.6e} m",
                          delta, top.Q, cycle.Q_max, top.stick_zones.front().right.x, cycle.result.stick_zone->second));
      CHECK(top.Q == test::rel(cycle.Q_max, kSameCycle));
      CHECK(top.delta == test::rel(delta, kSameCycle));
      CHECK(std::abs(top.stick_zones.front().right.x - cycle.result.stick_zone->second) < 0.1 * m.grid.h());
    } else {
      REQUIRE(cycle.result.regime == Regime::gross_slip);
      const double from_above = delta - cycle.result.sliding_amplitude;
      MESSAGE(fmt::format("stick limit {:.9e} m (analogy), {:.9e} (incremental, δ − sliding amplitude)",
                          analogy.stick_limit(), from_above));
      CHECK(analogy.stick_limit() == test::rel(from_above, kSameCycle));
    }
  }
}

// The limit over the first cycle's stick zone: c0 = a√(1 − Q0/fP) located to a quarter cell (as the force-controlled
// asymptote's, test_wear.cpp), and Q = δ/C(Z0) and the worn area against Hertz's at c0, with the errors of the
// compliance and of the located edges, first order in h: measured for Q 2.0e-4 ... 1.2e-5 (0.034 ... 0.016 h/a) and
// for W 6.0e-3 ... 3.5e-4 (1.0 ... 0.48 h/a) from 512 to 4096 cells. Tolerances: kQ = 0.1 h/a, kW = 1.5 h/a, and
// each error falls at least kMinOrder = 2/3 per halving over the three halvings (the located edges scatter within
// their cells from grid to grid).
TEST_CASE("Hertz under displacement control: the limit is the complete contact over the first cycle's stick zone, "
          "under Q = delta/C") {
  constexpr double kQ = 0.1, kW = 1.5, kMinOrder = 2.0 / 3.0;
  for (const double delta : {0.5e-6, 1e-6}) {
    CAPTURE(delta);
    std::vector<double> eQ, eW;
    for (int n = kCoarse; n <= kFine; n *= 2) {
      const Case k(n);
      const AnalogyTop top = k.analogy.at_displacement(delta);
      const DisplacementLimit L = displacement_limit(k.analogy, k.model.grid, k.model.pair, 0.0, kD, delta, top.Q);
      REQUIRE(L.stick_zones.size() == 1);
      CHECK_FALSE(L.shrinks);
      const double c0 = hertz_c(top.Q);
      const double Q_want = delta / hertz_stuck_compliance(kA, kMu, c0, kD);
      const double W = wear_limit(k.model.profile, kA, k.model.grid, kP, L.stick_zones).worn_area;
      eQ.push_back(L.Q / Q_want - 1.0);
      eW.push_back(W / hertz_worn_area(c0) - 1.0);
      MESSAGE(fmt::format("{} cells: Q0/fP = {:.7f}, c0 = {:.6e} m (closed form {:.6e}), Q/fP = {:.7f} ({:+.2e}), "
                          "worn area {:.6e} m² ({:+.2e})",
                          n, top.Q / (kF * kP), L.stick_zones.front().right.x, c0, L.Q / (kF * kP), eQ.back(), W,
                          eW.back()));
      CHECK(L.Q < top.Q);  // Q falls
      CHECK(std::abs(L.stick_zones.front().right.x - c0) < 0.25 * k.model.grid.h());
      CHECK(std::abs(L.stick_zones.front().left.x + c0) < 0.25 * k.model.grid.h());
      CHECK(std::abs(eQ.back()) < kQ * k.h_over_a());
      CHECK(std::abs(eW.back()) < kW * k.h_over_a());
    }
    CHECK(order(eQ.front(), eQ.back()) > kMinOrder);
    CHECK(order(eW.front(), eW.back()) > kMinOrder);
  }
}

// The shrinking branch (a first cycle stiffer than the complete contact over its stick zone; given here a Q0 of
// 0.2 fP, below the Q* of δ): toms748 finds Q* with C(Z(Q*)) Q* = δ, Z(Q*) = [−c, c], c/a = √(1 − Q*/fP). Against
// the closed-form root of hertz_stuck_compliance(A, μ, a√(1 − Q/fP), d) Q = δ: measured 1.6e-4 ... 2.6e-5 in Q* from
// 512 to 4096 cells (0.027 ... 0.036 h/a); c to a quarter cell. Tolerances as above.
TEST_CASE("the shrinking stick zone: the root find lands on Hertz's c(Q*) with delta = C(c) Q*") {
  constexpr double kQ = 0.1, kMinOrder = 2.0 / 3.0;
  for (const double delta : {0.5e-6, 1e-6}) {
    CAPTURE(delta);
    const double Q_want = root(
        [&](double Q) { return hertz_stuck_compliance(kA, kMu, hertz_c(Q), kD) * Q - delta; }, 1e-9 * kF * kP,
        (1 - 1e-12) * kF * kP);
    std::vector<double> eQ;
    for (int n = kCoarse; n <= kFine; n *= 2) {
      const Case k(n);
      const DisplacementLimit L =
          displacement_limit(k.analogy, k.model.grid, k.model.pair, 0.0, kD, delta, 0.2 * kF * kP);
      REQUIRE(L.shrinks);
      REQUIRE(L.stick_zones.size() == 1);
      eQ.push_back(L.Q / Q_want - 1.0);
      MESSAGE(fmt::format("{} cells: Q*/fP = {:.7f} (closed form {:.7f}, {:+.2e}), c = {:.6e} m (closed form {:.6e})",
                          n, L.Q / (kF * kP), Q_want / (kF * kP), eQ.back(), L.stick_zones.front().right.x,
                          hertz_c(Q_want)));
      CHECK(std::abs(eQ.back()) < kQ * k.h_over_a());
      CHECK(std::abs(L.stick_zones.front().right.x - hertz_c(Q_want)) < 0.25 * k.model.grid.h());
      CHECK(L.compliance * L.Q == test::rel(delta, 1e-9));
    }
    CHECK(order(eQ.front(), eQ.back()) > kMinOrder);
  }
}

namespace {

// The limit of a worn state whose stick zones stand still: the complete contact over them on the worn profile
// g0 + w (their cells no longer wear), under P; the worn depth is w inside them and the overlap outside. Returns
// the worn area (m²). The zones' ends are cell boundaries (the run's records), so the model's grid serves.
double frozen_zone_worn_area(const Model& m, double P, const std::vector<double>& w,
                             const std::vector<Interval>& zones) {
  const int n = m.grid.n;
  const double h = m.grid.h();
  auto inside = [&zones](double x) {
    return std::any_of(zones.begin(), zones.end(), [x](const Interval& z) { return x > z.first && x < z.second; });
  };
  std::vector<double> g(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i)
    if (inside(m.grid.x(i))) g[i] = m.g0[i] + w[i];
  ContactState s;
  REQUIRE(NormalSolver(*m.kernel).solve(g, P, s).converged());
  std::vector<double> u(n);
  m.kernel->apply(s.p, u);
  double W = 0.0;
  for (int i = 0; i < n; ++i)
    W += (inside(m.grid.x(i)) ? w[i] : std::max(0.0, -(m.g0[i] + u[i] - s.approach))) * h;
  return W;
}

std::vector<Zone> as_zones(const std::vector<Interval>& intervals) {
  std::vector<Zone> z(intervals.size());
  for (std::size_t k = 0; k < z.size(); ++k) z[k].left.x = intervals[k].first, z[k].right.x = intervals[k].second;
  return z;
}

}  // namespace

// A wear run under displacement control approaches the limit. Q falls from Q0 (the first record) toward δ/C(Z0) at
// every record; at the end the contact is the complete contact over the stick zones of the last record, fully stuck:
// Q_max = δ/C(Z_final), and the worn area is that complete contact's over them on the worn profile. On 256 cells
// (h = 0.013 a) the stick cells of the end are the first cycle's, and after 3e4 cycles the run is there to 8e-9 in Q
// (kSameCycle) and 2.9e-6 in worn area (below the stepper's tolerance), at the limit over those cells,
// `cells_worn_area`, 99.69 % of the asymptote. On 1024 cells (h = 0.0034 a) the stick zone grows by a cell on each
// side as Q falls (the worn neighbours join it; 3.6e-7 m, two cells, on 2048), and the run settles below the
// asymptote, 96.6 % (96.5 % on 2048; kStickGrowth = 5 %), at the grown zone's limit: 1.1e-8 in Q and 5.6e-7 in worn
// area. The run's cycles are the analogy's at the Q that reaches δ (engine/wear_contacts.hpp); marched instead, the
// grown zone's end cells crept toward that limit, 4.1e-5 in Q and 8.7e-4 in worn area short of it after 3e4 cycles
// (the marched cycle gives a worn cell without pressure no slip on touching, docs/METHODS.md).
TEST_CASE("a wear run under displacement control ends fully stuck over its stick zone under Q = delta/C") {
  constexpr double kSameCycle = 1e-6, kStickGrowth = 0.05;
  for (const int cells : {256, 1024}) {
    CAPTURE(cells);
    Scene s = test::hertz_wear(kP, 0.0, 3e4, cells);
    s.Q_ratio.reset();
    s.control = LoadControl::displacement;
    s.delta = 0.5e-6;
    s.tangential->increments = 40;
    const Model m = make_model(s);
    const NormalResult n = solve_normal(s, m);
    const CycleStage cycle = solve_cycle(s, m, n);
    const WearStage w = run_wear(s, m, n, cycle);
    const WearAsymptote& a = w.asymptote;
    REQUIRE(a.unavailable.empty());
    REQUIRE(a.Q_max);
    const WearRecord& first = w.records.front();
    const WearRecord& last = w.records.back();
    REQUIRE(last.stick_zone);
    for (std::size_t k = 1; k < w.records.size(); ++k) {
      CHECK(w.records[k].Q_max < w.records[k - 1].Q_max);  // Q falls ...
      CHECK(w.records[k].Q_max > *a.Q_max);                // ... toward δ/C(Z0)
      CHECK(w.records[k].fraction >= w.records[k - 1].fraction);
    }
    const double C_final =
        stuck_compliance(m.grid, m.pair, cycle.reference_x, cycle.reference_depth, as_zones(last.stick_zones));
    const double W_frozen = frozen_zone_worn_area(m, kP, last.w, last.stick_zones);
    // What the stage reports as the settled limit: the same state.
    REQUIRE(w.settled);
    CHECK(w.settled->worn_area == test::rel(W_frozen, 1e-12));
    CHECK(w.settled->Q_max * C_final == test::rel(*s.delta, 1e-12));
    const double growth = last.stick_zone->second - first.stick_zone->second;
    MESSAGE(fmt::format("{} cells: {:.6f} of the asymptote (its grid's limit {:.6f}); Q0 {:.2f}, at the end {:.2f}, "
                        "delta/C(Z0) {:.2f}, delta/C(final stick zone) {:.2f} ({:+.2e}); the final zone's limit "
                        "{:.6e} m², the run {:.6e} ({:+.2e}); the stick zone grew by {:.3e} m ({:.2f} cells)",
                        cells, last.fraction, a.cells_worn_area / a.worn_area, first.Q_max, last.Q_max, *a.Q_max,
                        s.delta.value() / C_final, last.Q_max * C_final / *s.delta - 1.0, W_frozen, last.worn_area,
                        last.worn_area / W_frozen - 1.0, growth, growth / m.grid.h()));
    CHECK(last.fraction <= 1.0);
    CHECK(last.fraction > 1.0 - kStickGrowth);
    CHECK(last.Q_max * C_final == test::rel(*s.delta, kSameCycle));
    CHECK(last.worn_area == test::rel(W_frozen, s.wear->tolerance));
    if (cells == 256)
      CHECK(last.worn_area == test::rel(a.cells_worn_area, s.wear->tolerance));
    else
      CHECK(growth > 0.5 * m.grid.h());
  }
}
