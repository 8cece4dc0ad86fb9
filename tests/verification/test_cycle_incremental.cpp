// The incremental route of cyclic partial slip (contact/incremental_slip.hpp) against the analogy route on the same
// grid, against PHYSICS.md's closed forms (Cattaneo–Mindlin, Mindlin–Deresiewicz, Nowell–Hills), and on paper 001's
// reverse-slip case, which the analogy refuses.
//
// Tolerances. Under a proportional load (Q and σ in phase, constant P) no cell reverses its slip within a half cycle,
// so the state at each turning point is that of a single increment from the previous one: the increments add no
// discretisation error, and both routes solve the same discrete problem (q = f p − f p* is the KKT point of the
// increment's quadratic program). They then differ only by their solvers' tolerances. Measured on 2048 cells: with
// the incremental solver at its default 1e-8 and the analogy's normal solves at 1e-11, q agrees to 1.8e-7 f p0
// (with both at 1e-11, to 6e-8 f p0); with the analogy at its default 1e-8 the difference is 5e-5 f p0, in the one
// cell at a stick edge, and is the analogy's: the normal solver's complementarity residual weighs p·|gap|, which
// bounds the pressure poorly where the gap is nearly zero. So the comparison runs the normal and corrective
// solves at kTightNormal and allows kAgreeTraction = 1e-6 f p0 (five times the measured error). The slip range and
// travelled then agree to 3e-9 of the largest range and the energy to 4e-9 relative (kAgreeSlip = 1e-7; 400 against
// 40 increments: 1e-8), and the stick-zone edges, fitted by the same square-root fit, to 8e-6 of a cell
// (kAgreeEdge = 1e-4).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/contact_zones.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kE = 200e9, kNu = 0.3, kR = 0.01, kF = 0.5;
constexpr double kAgreeTraction = 1e-6;  // of f p0
constexpr double kAgreeSlip = 1e-7;      // of the largest slip range, and relative for the energy
constexpr double kAgreeEdge = 1e-4;      // of a cell
constexpr double kTightNormal = 1e-11;   // the analogy's normal solves in the route comparison

using test::hertz_cycle;  // tests/scenes.hpp

CyclicLoad cyclic_load(const Scene& s, const Model& m) {
  const double strain = s.bulk_stress * (m.pair.kappa_specimen() + 1.0) / (8.0 * m.pair.mu_specimen());
  return {s.P, s.Q_max(), *s.friction, strain};
}

struct Run {
  Model model;
  NormalResult normal;
  IncrementalResult incremental;
};

Run run_incremental(const Scene& s, IncrementalSlipOptions o = {}) {
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  const IncrementalSlipSolver solver(*m.kernel, o);
  IncrementalResult r = solver.solve(n.state, cyclic_load(s, m));
  return {std::move(m), std::move(n), std::move(r)};
}

double edge_tolerance(const Grid& g) { return 0.25 * g.h(); }

}  // namespace

TEST_CASE("incremental: Hertz: the incremental route agrees with the analogy route on the same grid") {
  for (double ratio : {0.3, 0.6}) {
    CAPTURE(ratio);
    const Scene s = hertz_cycle(1e5, ratio, 2048);
    // The normal contact and the analogy's corrective solves at kTightNormal (see the tolerances above).
    const Model m = make_model(s);
    NormalSolverOptions tight;
    tight.tolerance = kTightNormal;
    ContactState contact;
    REQUIRE(NormalSolver(*m.kernel, tight).solve(m.g0, s.P, contact).converged());
    const CycleResult ana = TangentialSolver(*m.kernel, {tight})
                                .solve_cycle(m.g0, contact, locate_zones(m.grid, contact.p, m.g0), cyclic_load(s, m));
    const IncrementalResult inc = IncrementalSlipSolver(*m.kernel).solve(contact, cyclic_load(s, m));
    REQUIRE(inc.cycles.size() == 1);
    const CycleResult& r = inc.cycles[0];
    const auto hz = closed_form::hertz(1e5, m.pair.A(), kR);
    const double h = m.grid.h();
    CHECK(r.regime == Regime::partial_slip);
    REQUIRE(r.stick_zone);
    REQUIRE(ana.stick_zone);
    REQUIRE(r.stick_zone_unloaded);
    REQUIRE(ana.stick_zone_unloaded);
    const double d_edge = std::max({std::abs(r.stick_zone->first - ana.stick_zone->first),
                                    std::abs(r.stick_zone->second - ana.stick_zone->second),
                                    std::abs(r.stick_zone_unloaded->first - ana.stick_zone_unloaded->first),
                                    std::abs(r.stick_zone_unloaded->second - ana.stick_zone_unloaded->second)});
    const double d_top = max_abs_diff(r.q_top, ana.q_top) / (kF * hz.p0);
    const double d_unloaded = max_abs_diff(r.q_unloaded, ana.q_unloaded) / (kF * hz.p0);
    const double d_bottom = max_abs_diff(r.q_bottom, ana.q_bottom) / (kF * hz.p0);
    const double d_reloaded = max_abs_diff(r.q_reloaded, ana.q_reloaded) / (kF * hz.p0);
    const double d_range = max_abs_diff(r.slip_range, ana.slip_range) / ana.slip_max;
    const double d_travelled = max_abs_diff(r.slip_travelled, ana.slip_travelled) / (2.0 * ana.slip_max);
    MESSAGE(fmt::format("Q/fP = {}: edges {:.3g} h, q top/unloaded/bottom/reloaded {:.3g} {:.3g} {:.3g} {:.3g} f p0, "
                        "slip range {:.3g}, travelled {:.3g}, energy {:.10g} vs {:.10g} J/m, {} CG iterations over {} "
                        "increments, worst residual {:.3g}",
                        ratio, d_edge / h, d_top, d_unloaded, d_bottom, d_reloaded, d_range, d_travelled,
                        r.dissipated_energy, ana.dissipated_energy, inc.n_iterations,
                        inc.n_increments, inc.worst.residual));
    CHECK(d_edge < kAgreeEdge * h);
    CHECK(d_top < kAgreeTraction);
    CHECK(d_unloaded < kAgreeTraction);
    CHECK(d_bottom < kAgreeTraction);
    CHECK(d_reloaded < kAgreeTraction);
    CHECK(d_range < kAgreeSlip);
    CHECK(d_travelled < kAgreeSlip);
    CHECK(r.dissipated_energy == test::rel(ana.dissipated_energy, kAgreeSlip));
    // And both against Cattaneo–Mindlin: c/a = √(1 − Q/fP).
    const double c = hz.a * std::sqrt(1.0 - ratio);
    CHECK(std::abs(r.stick_zone->first + c) < edge_tolerance(m.grid));
    CHECK(std::abs(r.stick_zone->second - c) < edge_tolerance(m.grid));
  }
}

TEST_CASE("incremental: Hertz: Mindlin-Deresiewicz unloading stick zone c'/a = sqrt(1 - Q_max/(2fP)), incrementally") {
  const double ratio = 0.6;
  const Run r = run_incremental(hertz_cycle(1e5, ratio, 2048));
  const auto hz = closed_form::hertz(1e5, r.model.pair.A(), kR);
  const CycleResult& c = r.incremental.cycles[0];
  const double c1 = hz.a * std::sqrt(1.0 - ratio / 2.0);
  REQUIRE(c.stick_zone_unloaded);
  CHECK(std::abs(c.stick_zone_unloaded->first + c1) < edge_tolerance(r.model.grid));
  CHECK(std::abs(c.stick_zone_unloaded->second - c1) < edge_tolerance(r.model.grid));
  // No net force at Q = 0; the bottom is the top reversed to the solver's tolerance.
  double net = 0.0;
  for (double q : c.q_unloaded) net += q * r.model.grid.h();
  CHECK(std::abs(net) < 1e-9 * kF * 1e5);
  CHECK(max_abs_diff(c.q_bottom, [&] {
          std::vector<double> m(c.q_top);
          for (double& v : m) v = -v;
          return m;
        }()) < kAgreeTraction * kF * hz.p0);
}

TEST_CASE("incremental: Nowell-Hills: bulk tension shifts the stick zone by e/a = sigma/(4 f p0), incrementally") {
  const double P = 1e5;
  const auto hz = closed_form::hertz(P, 4 * (1 - kNu * kNu) / kE, kR);
  const Run r = run_incremental(hertz_cycle(P, 0.5, 2048, 0.6 * kF * hz.p0));
  const CycleResult& c = r.incremental.cycles[0];
  CHECK(c.regime == Regime::partial_slip);
  REQUIRE(c.stick_zone);
  MESSAGE(fmt::format("Nowell-Hills: stick zone [{:.6f}, {:.6f}] a", c.stick_zone->first / hz.a,
                      c.stick_zone->second / hz.a));
  CHECK(std::abs(c.stick_zone->first + 0.557107 * hz.a) < edge_tolerance(r.model.grid) + 5e-7 * hz.a);
  CHECK(std::abs(c.stick_zone->second - 0.857107 * hz.a) < edge_tolerance(r.model.grid) + 5e-7 * hz.a);
}

TEST_CASE("incremental: paper 001 in SI - the shifted case and the reverse-slip case the analogy refuses") {
  const double in = 0.0254, psi = 6894.757;
  Scene s = test::paper001_mindlin(2048);
  const double a = 0.01737 * in;
  IncrementalSlipOptions two_cycles;
  two_cycles.cycles = 2;

  s.bulk_stress = 12134 * psi;
  const Run shifted = run_incremental(s, two_cycles);
  const CycleResult& sh = shifted.incremental.cycles[1];
  REQUIRE(sh.stick_zone);
  CHECK(sh.regime == Regime::partial_slip);
  CHECK(sh.stick_zone->first == test::rel(-0.603673 * a, 1e-3));
  CHECK(sh.stick_zone->second == test::rel(0.879567 * a, 1e-3));

  s.bulk_stress = 44124 * psi;
  const Run rev = run_incremental(s, two_cycles);
  const auto hz = closed_form::hertz(s.P, rev.model.pair.A(), s.profile.R);
  CHECK(s.bulk_stress / (kF * hz.p0) > 1.033521);  // PHYSICS.md: reverse slip starts there
  const Grid& g = rev.model.grid;
  for (int k = 0; k < 2; ++k) {
    const CycleResult& c = rev.incremental.cycles[k];
    CAPTURE(k);
    CHECK(c.regime == Regime::reverse_slip);
    REQUIRE(c.stick_zone);
    REQUIRE(c.stick_zones.size() == 1);
    const double e = 0.5 * (c.stick_zone->first + c.stick_zone->second);
    const double e_shifted = 0.5 * (sh.stick_zone->first + sh.stick_zone->second);
    const double width = c.stick_zone->second - c.stick_zone->first;
    const double width_shifted = sh.stick_zone->second - sh.stick_zone->first;
    MESSAGE(fmt::format("sigma = 44124 psi, cycle {}: stick zone [{:.6f}, {:.6f}] a (centre {:.6f} a, half-width "
                        "{:.6f} a); 12134 psi: [{:.6f}, {:.6f}] a; shift ratio {:.4f}, width ratio {:.4f}; "
                        "energy {:.6g} J/m, slip_max {:.6g} m",
                        k + 1, c.stick_zone->first / a, c.stick_zone->second / a, e / a, 0.5 * width / a,
                        sh.stick_zone->first / a, sh.stick_zone->second / a, e / e_shifted, width / width_shifted,
                        c.dissipated_energy, c.slip_max));
    // Paper 001: much narrower and shifted about twice as far.
    CHECK(width < 0.8 * width_shifted);
    CHECK(e / e_shifted > 1.5);
    CHECK(e / e_shifted < 2.5);
    // At the top: q = +f p on the trailing slip zone, −f p on the leading one, |q| < f p between.
    const auto& p = rev.normal.state.p;
    int n_trailing = 0, n_leading = 0;
    for (int i = 0; i < g.n; ++i) {
      if (!(p[i] > 0.0)) continue;
      const double x = g.x(i);
      if (x < c.stick_zone->first - g.h()) {
        CHECK(c.q_top[i] == kF * p[i]);
        ++n_trailing;
      } else if (x > c.stick_zone->second + g.h()) {
        CHECK(c.q_top[i] == -kF * p[i]);
        ++n_leading;
      } else if (x > c.stick_zone->first + g.h() && x < c.stick_zone->second - g.h()) {
        CHECK(std::abs(c.q_top[i]) < kF * p[i]);
        CHECK(c.slip_travelled[i] == 0.0);
      }
    }
    CHECK(n_trailing > 0);
    CHECK(n_leading > 0);
  }
  // The steady cycle is reached after the first loading: the second cycle repeats the first.
  const CycleResult& c1 = rev.incremental.cycles[0];
  const CycleResult& c2 = rev.incremental.cycles[1];
  CHECK(max_abs_diff(c1.q_top, c2.q_top) < kAgreeTraction * kF * hz.p0);
  CHECK(c2.dissipated_energy == test::rel(c1.dissipated_energy, kAgreeSlip));
}

TEST_CASE("incremental: the cycle closes - the second cycle repeats the first and 100 cycles do not drift") {
  const double ratio = 0.6;
  IncrementalSlipOptions o;
  o.cycles = 100;
  const auto hz = closed_form::hertz(1e5, 4 * (1 - kNu * kNu) / kE, kR);
  const Run r = run_incremental(hertz_cycle(1e5, ratio, 128, 0.3 * kF * hz.p0), o);
  const auto& cycles = r.incremental.cycles;
  REQUIRE(cycles.size() == 100);
  const double d2 = max_abs_diff(cycles[0].q_top, cycles[1].q_top) / (kF * hz.p0);
  const double d100 = max_abs_diff(cycles[0].q_top, cycles[99].q_top) / (kF * hz.p0);
  const double e100 = std::abs(cycles[99].dissipated_energy / cycles[0].dissipated_energy - 1.0);
  const double s100 = max_abs_diff(cycles[0].slip_range, cycles[99].slip_range) / cycles[0].slip_max;
  MESSAGE(fmt::format("cycle 2 vs 1: {:.3g} f p0; cycle 100 vs 1: q {:.3g} f p0, slip range {:.3g}, energy {:.3g}",
                      d2, d100, s100, e100));
  CHECK(d2 < kAgreeTraction);
  CHECK(d100 < kAgreeTraction);
  CHECK(s100 < kAgreeSlip);
  CHECK(e100 < kAgreeSlip);
  // Dissipation is never negative, per cell and per cycle, and the stick zone never dissipates.
  for (const CycleResult& c : cycles) {
    CHECK(c.dissipated_energy > 0.0);
    for (double e : c.energy_density) CHECK(e >= 0.0);
  }
}

TEST_CASE("incremental: 400 increments per cycle give the 40-increment cycle (a proportional load has no increment error)") {
  const Scene s = hertz_cycle(1e5, 0.6, 512);
  IncrementalSlipOptions fine;
  fine.increments_per_cycle = 400;
  const Run coarse = run_incremental(s);
  const Run dense = run_incremental(s, fine);
  const auto hz = closed_form::hertz(1e5, coarse.model.pair.A(), kR);
  const CycleResult& a = coarse.incremental.cycles[0];
  const CycleResult& b = dense.incremental.cycles[0];
  const double dq = max_abs_diff(a.q_unloaded, b.q_unloaded) / (kF * hz.p0);
  const double ds = max_abs_diff(a.slip_travelled, b.slip_travelled) / a.slip_max;
  MESSAGE(fmt::format("400 vs 40 increments: q unloaded {:.3g} f p0, slip travelled {:.3g}, energy {:.10g} vs "
                      "{:.10g} J/m; {} vs {} CG iterations",
                      dq, ds, b.dissipated_energy, a.dissipated_energy, dense.incremental.n_iterations,
                      coarse.incremental.n_iterations));
  CHECK(dq < kAgreeTraction);
  CHECK(ds < kAgreeSlip);
  CHECK(b.dissipated_energy == test::rel(a.dissipated_energy, kAgreeSlip));
}

TEST_CASE("incremental: near sliding at Q/fP = 0.999 and gross slip at Q = fP") {
  const Run r = run_incremental(hertz_cycle(1e5, 0.999, 4096));
  const auto hz = closed_form::hertz(1e5, r.model.pair.A(), kR);
  const CycleResult& c = r.incremental.cycles[0];
  REQUIRE(c.stick_zone);
  CHECK(c.regime == Regime::partial_slip);
  const double cc = hz.a * std::sqrt(0.001);
  MESSAGE(fmt::format("Q/fP = 0.999: stick zone [{:.4g}, {:.4g}] c, {} CG iterations", c.stick_zone->first / cc,
                      c.stick_zone->second / cc, r.incremental.n_iterations));
  CHECK(std::abs(c.stick_zone->first + cc) < 0.5 * r.model.grid.h());
  CHECK(std::abs(c.stick_zone->second - cc) < 0.5 * r.model.grid.h());
  CHECK(std::isfinite(c.dissipated_energy));
  CHECK(c.dissipated_energy > 0.0);

  const Run gross = run_incremental(hertz_cycle(1e5, 1.0, 256));
  REQUIRE(gross.incremental.cycles.size() == 1);
  CHECK(gross.incremental.cycles[0].regime == Regime::gross_slip);
  CHECK_FALSE(gross.incremental.cycles[0].stick_zone);
}

TEST_CASE("incremental: a solve that stops short says so with its residual and bad options are named") {
  const Scene s = hertz_cycle(1e5, 0.6, 256);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  IncrementalSlipOptions o;
  o.max_iterations = 1;
  o.tolerance = 1e-12;
  const IncrementalSlipSolver solver(*m.kernel, o);
  try {
    (void)solver.solve(n.state, cyclic_load(s, m));
    FAIL("expected a ConvergenceError");
  } catch (const ConvergenceError& e) {
    const std::string what = e.what();
    CHECK(what.find("residual") != std::string::npos);
    CHECK(what.find("first loading") != std::string::npos);
  }
  IncrementalSlipOptions bad;
  bad.increments_per_cycle = 42;
  CHECK(bad.validate().find("increments_per_cycle = 42") != std::string::npos);
  CHECK_THROWS_AS(IncrementalSlipSolver(*m.kernel, bad), InputError);
}

namespace {

// The incremental route against the analogy route on scene s, on the same grid, the analogy's normal solves at
// kTightNormal; tractions compared on the scale f p_max of the normal solution. Returns the number of stick zones.
std::size_t compare_routes(const Scene& s) {
  const Model m = make_model(s);
  NormalSolverOptions tight;
  tight.tolerance = kTightNormal;
  ContactState contact;
  REQUIRE(NormalSolver(*m.kernel, tight).solve(m.g0, s.P, contact).converged());
  const auto zones = locate_zones(m.grid, contact.p, m.g0);
  const CycleResult ana = TangentialSolver(*m.kernel, {tight}).solve_cycle(m.g0, contact, zones, cyclic_load(s, m));
  const IncrementalResult inc = IncrementalSlipSolver(*m.kernel).solve(contact, cyclic_load(s, m));
  REQUIRE(inc.cycles.size() == 1);
  const CycleResult& r = inc.cycles[0];
  REQUIRE(ana.regime == Regime::partial_slip);
  CHECK(r.regime == Regime::partial_slip);
  const double scale = kF * *std::max_element(contact.p.begin(), contact.p.end());
  const double h = m.grid.h();
  const double d_top = max_abs_diff(r.q_top, ana.q_top) / scale;
  const double d_unloaded = max_abs_diff(r.q_unloaded, ana.q_unloaded) / scale;
  const double d_range = max_abs_diff(r.slip_range, ana.slip_range) / ana.slip_max;
  MESSAGE(fmt::format("{}: {} contact zones, {} stick zones; q top/unloaded {:.3g} {:.3g} f p_max, slip range {:.3g}, "
                      "energy {:.10g} vs {:.10g} J/m",
                      s.name, zones.size(), ana.stick_zones.size(), d_top, d_unloaded, d_range, r.dissipated_energy,
                      ana.dissipated_energy));
  CHECK(d_top < kAgreeTraction);
  CHECK(d_unloaded < kAgreeTraction);
  CHECK(d_range < kAgreeSlip);
  CHECK(r.dissipated_energy == test::rel(ana.dissipated_energy, kAgreeSlip));
  REQUIRE(r.stick_zones.size() == ana.stick_zones.size());
  for (std::size_t k = 0; k < r.stick_zones.size(); ++k) {
    CHECK(std::abs(r.stick_zones[k].first - ana.stick_zones[k].first) < kAgreeEdge * h);
    CHECK(std::abs(r.stick_zones[k].second - ana.stick_zones[k].second) < kAgreeEdge * h);
  }
  return ana.stick_zones.size();
}

// A table of g0 sampled at the grid's cell centres of `m` (0.1 of a cell apart, linear between).
ProfileSpec table_of(const Model& m, const std::vector<double>& g) {
  ProfileSpec spec;
  spec.type = ProfileType::table;
  const int n = m.grid.n;
  for (int i = 0; i + 1 < n; ++i)
    for (int k = 0; k < 10; ++k) {
      const double t = k / 10.0;
      spec.x.push_back((1.0 - t) * m.grid.x(i) + t * m.grid.x(i + 1));
      spec.h.push_back((1.0 - t) * g[i] + t * g[i + 1]);
    }
  spec.x.push_back(m.grid.x(n - 1));
  spec.h.push_back(g[n - 1]);
  return spec;
}

}  // namespace

TEST_CASE("incremental: agrees with the analogy on a tabulated, a worn-looking and a two-zone profile") {
  // Tabulated: a cylinder with a waviness, sampled.
  {
    Scene s = hertz_cycle(1e5, 0.5, 1024);
    s.name = "table";
    ProfileSpec wavy;
    wavy.type = ProfileType::sum;
    ProfileSpec w;
    w.type = ProfileType::wavy;
    w.amplitude = 0.02e-6;
    w.wavelength = 0.05e-3;
    wavy.terms = {test::cylinder(), w};
    s.profile = wavy;
    const Model coarse = make_model(s, 4096);
    s.profile = table_of(coarse, coarse.g0);
    s.window = std::pair{coarse.grid.x_min + 2 * coarse.grid.h(), coarse.grid.x_max - 2 * coarse.grid.h()};
    CHECK(compare_routes(s) >= 1);
  }
  // Worn-looking: the cylinder with the wear asymptote's scar, as paper 002's limit leaves it.
  {
    Scene s = test::hertz_wear(1e5, 0.5, 1, 1024);
    const Model m = make_model(s);
    const WearAsymptote a = wear_asymptote(s, m, solve_normal(s, m));
    std::vector<double> g(m.grid.n);
    for (int i = 0; i < m.grid.n; ++i) g[i] = m.g0[i] + 0.8 * a.w[i];  // 80 % of the way: slip zones still loaded
    Scene worn = hertz_cycle(1e5, 0.5, 1024);
    worn.name = "worn";
    worn.profile = table_of(m, g);
    worn.window = std::pair{m.grid.x_min + 2 * m.grid.h(), m.grid.x_max - 2 * m.grid.h()};
    CHECK(compare_routes(worn) == 1);
  }
  // Two zones: two cylinders 0.4 mm apart, each with its stick zone.
  {
    Scene s = hertz_cycle(1e5, 0.5, 2048);
    s.name = "two_zone";
    s.profile = ProfileSpec{};
    s.profile.type = ProfileType::envelope;
    s.profile.terms = {test::cylinder(-0.2e-3), test::cylinder(0.2e-3)};
    CHECK(compare_routes(s) == 2);
  }
}
