// Cyclic partial slip of dissimilar bodies (Dundurs β ≠ 0) by the incremental route with the normal–tangential
// coupling (contact/coupling_kernel.hpp, contact/incremental_slip.hpp): Hertz, R = 10 mm, P = 100 N/mm, f = 0.5, a
// steel pad (200 GPa, 0.3) on a titanium specimen (110 GPa, 0.34), β = −0.0497, Q/fP = 0.5.
//
// No closed form is checked here: Spence's (1975) solution for a cylinder pressed with friction on a dissimilar
// half-plane describes the normal loading with friction, which this route does not model (it starts from the
// frictionless contact with q = 0), and we found no published closed form for the tangentially loaded cycle with
// β ≠ 0. The checks are internal: β → 0 recovers the similar bodies' cycle, the pressure's shift linearly in β; the
// stick zone and the energy converge with the grid (observed order) and the increments; no increment dissipates
// negative energy; the cycle closes; the in-phase steady cycle's bottom is its top mirrored (x → −x, q → −q), which
// the coupled equations preserve; the pressure, Hertz's at Q = 0, turns asymmetric only through β and carries P.
//
// Measured (1024 cells): unlike similar bodies, the first cycle after the first loading is not yet the steady one
// (its energy is 0.1 % higher: the first loading from Hertz's pressure with q = 0 moves the pressure along another
// path than the loading from the bottom); the second cycle is, and the third repeats it to 3e-9 in energy and
// 2e-8 p0 in traction (160 increments). The engine therefore reports the second cycle when β ≠ 0, and the
// convergence studies below measure it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/coupling_kernel.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/output.hpp"
#include "engine/simulation.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kP = 1e5, kRatio = 0.5;
constexpr double kWorkBalance = 1e-3;  // ∮ Q dλ against the dissipation: the trapezoid rule, O(1/m²): 1.6e-4 at m = 160
constexpr Material kSteel{200e9, 0.3}, kTitanium{110e9, 0.34};

Scene dissimilar_cycle(Material specimen, int cells, double ratio = kRatio) {
  Scene s = test::hertz_cycle(kP, ratio, cells);
  s.specimen = specimen;
  return s;
}

struct Run {
  Model model;
  NormalResult normal;
  IncrementalResult r;
  double beta = 0.0;
};

// The cycle on the scene's model; beta: NaN for the pair's own β, else forced (0: the uncoupled solve).
Run run(const Scene& s, IncrementalSlipOptions o = {}, double beta = std::numeric_limits<double>::quiet_NaN()) {
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  const double b = std::isnan(beta) ? m.pair.beta() : beta;
  const NormalCoupling coupling{b, m.g0};
  const CyclicLoad load{s.P, s.Q_max(), *s.friction, 0.0};
  IncrementalResult r = IncrementalSlipSolver(*m.kernel, o).solve(n.state, load, nullptr, &coupling);
  return {std::move(m), std::move(n), std::move(r), b};
}

double max_of(const std::vector<double>& a) { return *std::max_element(a.begin(), a.end()); }

}  // namespace

TEST_CASE("dissimilar: steel on titanium: the coupled cycle, its sweeps and its pressure") {
  const Run d = run(dissimilar_cycle(kTitanium, 1024));
  REQUIRE(d.r.cycles.size() == 1);
  const CycleResult& c = d.r.cycles[0];
  const double h = d.model.grid.h();
  double P_top = 0.0, moment = 0.0;
  for (int i = 0; i < d.model.grid.n; ++i) {
    P_top += h * d.r.p_top[i];
    moment += h * d.r.p_top[i] * d.model.grid.x(i);
  }
  const auto hz = closed_form::hertz(kP, d.model.pair.A(), test::kHertzR);
  MESSAGE(fmt::format("beta = {:.6f}; stick zone [{:.6f}, {:.6f}] a, energy {:.8g} J/m, {} sweeps over {} increments "
                      "(at most {}), {} CG iterations; top pressure: load {:.10g} N/m, centre {:.4g} a, peak change "
                      "{:.4g} p0",
                      d.beta, c.stick_zone->first / hz.a, c.stick_zone->second / hz.a, c.dissipated_energy,
                      d.r.n_coupling_sweeps, d.r.n_increments, d.r.max_coupling_sweeps, d.r.n_iterations, P_top,
                      moment / P_top / hz.a, max_abs_diff(d.r.p_top, d.normal.state.p) / hz.p0));
  CHECK(d.beta == test::rel(-0.0515561, 1e-5));  // Dundurs' formula by hand: κ1 = 1.8, κ2 = 1.64, Γ = 0.53360
  CHECK(c.regime == Regime::partial_slip);
  REQUIRE(c.stick_zone);
  CHECK(P_top == test::rel(kP, 1e-12));
  // The coupling moves the pressure by O(β f) p0, and its centre off x = 0.
  CHECK(max_abs_diff(d.r.p_top, d.normal.state.p) > 1e-3 * hz.p0);
  CHECK(std::abs(moment / P_top) > 1e-3 * hz.a);
  CHECK(d.r.max_coupling_sweeps >= 2);
  CHECK(d.r.max_coupling_sweeps <= 10);
}

TEST_CASE("dissimilar: the top of the cycle satisfies the coupled equations, written out with the dense matrices") {
  // Normal: G = g0 + K p − A β S q is the same (δ) on every loaded cell and no less on the others. Tangential: a
  // cell that has stuck since the start (deep in the stick zone) has s = K q + A β S (p − p0) − Λ = 0, Λ the sum of
  // the increments' rigid shifts and p0 the frictionless pressure the cycle starts from. S is applied densely from
  // CouplingKernel::matrix, independently of the solver's running sums.
  const Run d = run(dissimilar_cycle(kTitanium, 1024));
  const Grid& g = d.model.grid;
  const int n = g.n;
  const CycleResult& c = d.r.cycles[0];
  const CouplingKernel S(g);
  const double A = d.model.pair.A(), Ab = A * d.beta;
  std::vector<double> Kp(n), Kq(n), dp(n);
  d.model.kernel->apply(d.r.p_top, Kp);
  d.model.kernel->apply(c.q_top, Kq);
  auto S_times = [&](const std::vector<double>& t, int i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += S.matrix(i, j) * t[j];
    return sum;
  };
  for (int i = 0; i < n; ++i) dp[i] = d.r.p_top[i] - d.normal.state.p[i];
  const double p_max = max_of(d.r.p_top);
  double G_lo = std::numeric_limits<double>::infinity(), G_hi = -G_lo, G_open = G_lo;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(d.model.g0[i])) continue;
    const double G = d.model.g0[i] + Kp[i] - Ab * S_times(c.q_top, i);
    if (d.r.p_top[i] > 0.05 * p_max) G_lo = std::min(G_lo, G), G_hi = std::max(G_hi, G);
    if (d.r.p_top[i] == 0.0) G_open = std::min(G_open, G);
  }
  double Lambda = 0.0;
  for (double l : d.r.increment_shift) Lambda += l;
  const double a = closed_form::hertz(kP, A, test::kHertzR).a;
  double s_worst = 0.0;
  for (int i = 0; i < n; ++i)
    if (std::abs(g.x(i)) < 0.4 * a) s_worst = std::max(s_worst, std::abs(Kq[i] + Ab * S_times(dp, i) - Lambda));
  const double scale = A * kP;
  MESSAGE(fmt::format("normal: G spread {:.3g} A P on the loaded cells, open cells above by {:.3g} A P; tangential: "
                      "|s| {:.3g} A P on the stuck cells (the coupling term alone reaches {:.3g} A P)",
                      (G_hi - G_lo) / scale, (G_open - G_hi) / scale, s_worst / scale,
                      std::abs(Ab * S_times(dp, n / 2)) / scale));
  CHECK((G_hi - G_lo) < 1e-6 * scale);
  CHECK(G_open > G_lo - 1e-6 * scale);
  CHECK(s_worst < 1e-6 * scale);
}

TEST_CASE("dissimilar: the bottom of the in-phase steady cycle is its top mirrored") {
  IncrementalSlipOptions o;
  o.cycles = 2;
  const Run d = run(dissimilar_cycle(kTitanium, 1024), o);
  const Grid& g = d.model.grid;
  REQUIRE(std::abs(g.x_min + g.x_max) < 1e-12 * g.width());  // a symmetric window: cell i mirrors cell n − 1 − i
  const CycleResult& c = d.r.cycles.back();
  const int n = g.n;
  std::vector<double> p_mirror(n), q_mirror(n);
  for (int i = 0; i < n; ++i) p_mirror[i] = d.r.p_top[n - 1 - i], q_mirror[i] = -c.q_top[n - 1 - i];
  const double p0 = max_of(d.normal.state.p);
  const double dp = max_abs_diff(d.r.p_bottom, p_mirror) / p0, dq = max_abs_diff(c.q_bottom, q_mirror) / p0;
  MESSAGE(fmt::format("bottom against the mirrored top: p {:.3g} p0, q {:.3g} p0", dp, dq));
  // Not to round-off: the discrete equations are mirror-symmetric, but the steady cycle keeps a memory of the first
  // loading (from q = 0 to +Q, which has no mirror in the cycle): measured 1.8e-5 p0 in p and 4.7e-4 p0 in q, against
  // the O(β f) = 0.026 p0 by which the coupling moves the traction.
  CHECK(dp < 1e-4);
  CHECK(dq < 2e-3);
}

TEST_CASE("dissimilar: beta -> 0 recovers the similar bodies' cycle, linearly in beta") {
  // The forced β = 0 solve goes through the same coupled machinery and must give the uncoupled route exactly.
  {
    const Scene s = dissimilar_cycle(kTitanium, 512);
    const Run zero = run(s, {}, 0.0);
    const Run tiny = run(s, {}, 1e-12);
    const double p0 = max_of(zero.normal.state.p);
    const double dq = max_abs_diff(tiny.r.cycles[0].q_top, zero.r.cycles[0].q_top) / p0;
    MESSAGE(fmt::format("beta = 1e-12 against the uncoupled solve: q {:.3g} p0", dq));
    CHECK(dq < 1e-7);
    CHECK(tiny.r.cycles[0].dissipated_energy == test::rel(zero.r.cycles[0].dissipated_energy, 1e-7));
  }
  // Specimens approaching the pad: E2 = E1 (1 − η), same ν; against the same pair solved with β forced to 0. The
  // pressure's centre moves linearly in β; the largest change of p or q does not (it sits at an edge that moves,
  // where p grows like the square root of the distance), nor does the energy (even in β).
  std::vector<double> betas, centres;
  for (double eta : {0.4, 0.2, 0.1, 0.05}) {
    const Scene s = dissimilar_cycle({kSteel.E * (1.0 - eta), kSteel.nu}, 1024);
    const Run coupled = run(s), uncoupled = run(s, {}, 0.0);
    const double p0 = max_of(uncoupled.normal.state.p);
    const double dq = max_abs_diff(coupled.r.cycles[0].q_top, uncoupled.r.cycles[0].q_top) / p0;
    const double dE = std::abs(coupled.r.cycles[0].dissipated_energy / uncoupled.r.cycles[0].dissipated_energy - 1.0);
    double P = 0.0, moment = 0.0;
    for (int i = 0; i < coupled.model.grid.n; ++i) {
      P += coupled.model.grid.h() * coupled.r.p_top[i];
      moment += coupled.model.grid.h() * coupled.r.p_top[i] * coupled.model.grid.x(i);
    }
    const double a = closed_form::hertz(kP, coupled.model.pair.A(), test::kHertzR).a;
    MESSAGE(fmt::format("eta = {}: beta = {:.5f}: pressure centre {:.5g} a ({:.5g} a per unit beta), q_top {:.4g} p0, "
                        "energy {:.4g}",
                        eta, coupled.beta, moment / P / a, moment / P / a / coupled.beta, dq, dE));
    betas.push_back(coupled.beta);
    centres.push_back(moment / P / a);
  }
  for (std::size_t k = 1; k < betas.size(); ++k) {
    const double ratio = (centres[k] / betas[k]) / (centres[k - 1] / betas[k - 1]);
    CAPTURE(k);
    CHECK(std::abs(ratio - 1.0) < 1e-3);
  }
  CHECK(std::abs(centres.back()) < 0.002);
}

TEST_CASE("dissimilar: the cycle converges with the grid and with the increments") {
  // Grid: 512, 1024, 2048, 4096 cells on the same window; the observed order from three successive differences.
  std::vector<double> c_left, c_right, energy;
  std::vector<std::vector<double>> q_coarse;
  IncrementalSlipOptions steady;
  steady.cycles = 2;
  for (int n : {512, 1024, 2048, 4096}) {
    const Run d = run(dissimilar_cycle(kTitanium, n), steady);
    const CycleResult& c = d.r.cycles.back();
    REQUIRE(c.stick_zone);
    c_left.push_back(c.stick_zone->first);
    c_right.push_back(c.stick_zone->second);
    energy.push_back(c.dissipated_energy);
    MESSAGE(fmt::format("n = {}: stick [{:.8g}, {:.8g}] m, energy {:.10g} J/m, {} sweeps, at most {}", n,
                        c.stick_zone->first, c.stick_zone->second, c.dissipated_energy, d.r.n_coupling_sweeps,
                        d.r.max_coupling_sweeps));
  }
  auto order = [](const std::vector<double>& v, std::size_t k) {
    return std::log2(std::abs(v[k] - v[k - 1]) / std::abs(v[k + 1] - v[k]));
  };
  for (std::size_t k = 1; k + 1 < energy.size(); ++k) {
    MESSAGE(fmt::format("observed order: energy {:.3f}, left edge {:.3f}, right edge {:.3f}", order(energy, k),
                        order(c_left, k), order(c_right, k)));
    CHECK(order(energy, k) > 1.0);
    CHECK(order(c_left, k) > 0.9);
    CHECK(order(c_right, k) > 0.9);
  }
  CHECK(std::abs(energy[3] / energy[2] - 1.0) < 1e-5);

  // Increments: 20, 40, 80, 160 per cycle on 1024 cells.
  std::vector<double> e_inc;
  for (int m : {20, 40, 80, 160}) {
    IncrementalSlipOptions o = steady;
    o.increments_per_cycle = m;
    const Run d = run(dissimilar_cycle(kTitanium, 1024), o);
    e_inc.push_back(d.r.cycles.back().dissipated_energy);
    MESSAGE(fmt::format("m = {}: energy {:.12g} J/m, stick [{:.8g}, {:.8g}] m", m, e_inc.back(),
                        d.r.cycles.back().stick_zone->first, d.r.cycles.back().stick_zone->second));
  }
  for (std::size_t k = 1; k + 1 < e_inc.size(); ++k) {
    const double o = std::log2(std::abs(e_inc[k] - e_inc[k - 1]) / std::abs(e_inc[k + 1] - e_inc[k]));
    MESSAGE(fmt::format("increments: energy differences {:.4g} then {:.4g}: order {:.3f}", e_inc[k] - e_inc[k - 1],
                        e_inc[k + 1] - e_inc[k], o));
    CHECK(o > 1.0);
  }
  CHECK(std::abs(e_inc[3] / e_inc[2] - 1.0) < 1e-5);
}

TEST_CASE("dissimilar: no increment dissipates negative energy, and the steady cycle repeats") {
  IncrementalSlipOptions o;
  o.cycles = 3;
  o.increments_per_cycle = 160;
  const Run d = run(dissimilar_cycle(kTitanium, 1024), o);
  REQUIRE(d.r.cycles.size() == 3);
  double least = std::numeric_limits<double>::infinity(), total = 0.0;
  for (double w : d.r.increment_energy) least = std::min(least, w), total += w;
  MESSAGE(fmt::format("{} increments: least energy {:.4g} J/m, total {:.8g} J/m", d.r.increment_energy.size(), least,
                      total));
  CHECK(d.r.increment_energy.size() == std::size_t(d.r.n_increments));
  CHECK(least >= 0.0);
  CHECK(total > 0.0);
  const CycleResult &c1 = d.r.cycles[0], &c2 = d.r.cycles[1], &c3 = d.r.cycles[2];
  const double p0 = max_of(d.normal.state.p);
  MESSAGE(fmt::format("cycle 2 vs 1: q_top {:.3g} p0, energy {:.3g}; cycle 3 vs 2: q_top {:.3g} p0, energy {:.3g}",
                      max_abs_diff(c2.q_top, c1.q_top) / p0, c2.dissipated_energy / c1.dissipated_energy - 1.0,
                      max_abs_diff(c3.q_top, c2.q_top) / p0, c3.dissipated_energy / c2.dissipated_energy - 1.0));
  // The work of Q over the steady (third) cycle, ∮ Q dλ by the trapezoid rule over its increments, is the energy
  // it dissipates: the coupling terms do no net work over a closed cycle (∮ p·S dq = 0 by the normal contact's
  // complementarity under constant P, and ∮ q·S dp = ∮ d(q·S p) − ∮ dq·S p = 0 as S is antisymmetric). This checks
  // the bookkeeping of λ and Δw with the coupling in it, not the coupling's signs (the test above does).
  {
    const int m = o.increments_per_cycle, first = m / 4;  // the first loading, then three cycles of m
    REQUIRE(d.r.n_increments == first + 3 * m);
    double W = 0.0;
    for (int k = first + 2 * m; k < first + 3 * m; ++k)
      W += 0.5 * (d.r.increment_Q[k] + d.r.increment_Q[k - 1]) * d.r.increment_shift[k];
    MESSAGE(fmt::format("steady cycle: work of Q {:.10g} J/m, dissipated {:.10g} J/m ({:.3g})", W,
                        d.r.cycles[2].dissipated_energy, W / d.r.cycles[2].dissipated_energy - 1.0));
    CHECK(W == test::rel(d.r.cycles[2].dissipated_energy, kWorkBalance));
  }
  // The first cycle after the first loading is off by 0.1 % (see the top); the third repeats the second.
  CHECK(max_abs_diff(c2.q_top, c1.q_top) < 1e-5 * p0);
  CHECK(c2.dissipated_energy == test::rel(c1.dissipated_energy, 3e-3));
  CHECK(max_abs_diff(c3.q_top, c2.q_top) < 1e-6 * p0);
  CHECK(c3.dissipated_energy == test::rel(c2.dissipated_energy, 1e-7));
  REQUIRE(c3.stick_zone);
  CHECK(std::abs(c3.stick_zone->first - c2.stick_zone->first) < 1e-4 * d.model.grid.h());
  CHECK(std::abs(c3.stick_zone->second - c2.stick_zone->second) < 1e-4 * d.model.grid.h());
}

TEST_CASE("dissimilar: a coupled increment that cannot settle names itself") {
  IncrementalSlipOptions o;
  o.max_coupling_sweeps = 1;
  try {
    run(dissimilar_cycle(kTitanium, 256), o);
    FAIL("no ConvergenceError");
  } catch (const ConvergenceError& e) {
    const std::string what = e.what();
    CHECK(what.find("the first loading, increment 1") != std::string::npos);
    CHECK(what.find("beta") != std::string::npos);
  }
}

TEST_CASE("dissimilar: a scene picks the incremental route and reports the sweeps, the analogy is refused") {
  Scene s = dissimilar_cycle(kTitanium, 512);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CycleStage st = solve_cycle(s, m, n);
  MESSAGE(st.route);
  CHECK(st.route.find("incremental (auto: dissimilar bodies) [beta = -0.05156") == 0);
  CHECK(st.route.find("coupling sweeps") != std::string::npos);
  CHECK(st.result.stick_zone);
  s.tangential->route = TangentialRoute::analogy;
  CHECK_THROWS_AS(solve_cycle(s, m, n), UnsupportedError);
}

TEST_CASE("dissimilar: the coupled pressure at the top and the bottom reaches the outputs, similar bodies have none") {
  Scene s = dissimilar_cycle(kTitanium, 512);
  s.name = "dissimilar_outputs";
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CycleStage st = solve_cycle(s, m, n);
  REQUIRE(st.p_top.size() == std::size_t(m.grid.n));
  REQUIRE(st.p_bottom.size() == std::size_t(m.grid.n));
  // Each carries P, and the shear has moved it off the frictionless pressure (β = −0.05: by a little).
  double top = 0.0, bottom = 0.0;
  for (int i = 0; i < m.grid.n; ++i) top += m.grid.h() * st.p_top[i], bottom += m.grid.h() * st.p_bottom[i];
  CHECK(top == test::rel(s.P, 1e-10));
  CHECK(bottom == test::rel(s.P, 1e-10));
  CHECK(max_abs_diff(st.p_top, n.state.p) > 1e-6 * max_of(n.state.p));

  RunResult r;
  r.normal = n;
  r.cycle = st;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("fretwear-dissimilar-{}", ::getpid());
  {
    Scene quiet = s;
    quiet.plots = false;
    OutputFolder out(dir);
    const nlohmann::json summary = write_results(quiet, r, out);
    out.commit();
    CHECK(summary["cycle"]["p_max_top"].get<double>() == test::rel(max_of(st.p_top), 1e-15));
    CHECK(summary["cycle"]["p_max_bottom"].get<double>() == test::rel(max_of(st.p_bottom), 1e-15));
  }
  std::ifstream csv(dir / "cycle.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header.ends_with(",p_top_Pa,p_bottom_Pa"));
  std::filesystem::remove_all(dir);

  // Similar bodies: the pressure is the contact's at every instant, and no such columns or keys are written.
  const Scene similar = test::hertz_cycle(kP, kRatio, 512);
  const Model ms = make_model(similar);
  const CycleStage sst = solve_cycle(similar, ms, solve_normal(similar, ms));
  CHECK(sst.p_top.empty());
  CHECK(sst.p_bottom.empty());
}

// Displacement control of dissimilar bodies: each increment is the force-controlled coupled increment at the Q whose
// δ(Q) hits the target (incremental_slip.hpp). Prescribing the δ_max that force control reaches must give back its
// Q, stick zone and energy, to the displacement search's tolerance 10 · tolerance · |Δδ| (a relative error in Q of
// about 1e-7 of a cycle's compliance), far inside kDisplacementAgreement.
namespace {

constexpr double kDisplacementAgreement = 1e-5;

Scene under_displacement(Scene s, double delta) {
  s.control = LoadControl::displacement;
  s.delta = delta;
  s.Q_amplitude.reset();
  s.Q_ratio.reset();
  return s;
}

}  // namespace

TEST_CASE("dissimilar: displacement control at force control's delta_max gives back its Q, stick zone and energy") {
  const Scene force = dissimilar_cycle(kTitanium, 512);
  const Model m = make_model(force);
  const NormalResult n = solve_normal(force, m);
  const CycleStage f = solve_cycle(force, m, n);
  REQUIRE(f.result.delta_max > 0.0);
  const Scene disp = under_displacement(force, f.result.delta_max);
  const CycleStage d = solve_cycle(disp, m, n);
  CHECK(d.route.find("incremental (auto: displacement control) [beta = -0.05156") == 0);
  CHECK(d.result.regime == Regime::partial_slip);
  CHECK(d.Q_max == test::rel(f.Q_max, kDisplacementAgreement));
  CHECK(d.result.dissipated_energy == test::rel(f.result.dissipated_energy, kDisplacementAgreement));
  REQUIRE(d.result.stick_zone);
  CHECK(std::abs(d.result.stick_zone->first - f.result.stick_zone->first) < 0.5 * m.grid.h());
  CHECK(std::abs(d.result.stick_zone->second - f.result.stick_zone->second) < 0.5 * m.grid.h());
  CHECK(max_abs_diff(d.p_top, f.p_top) < kDisplacementAgreement * max_of(f.p_top));
}

TEST_CASE("dissimilar: displacement control is continuous as beta tends to 0, and slides past the stick limit") {
  // Moduli 0.1 % apart (β ≈ 1e-4) against similar bodies at the same δ: within 0.5 % (the continuity check;
  // the composite modulus itself differs by 0.05 %).
  constexpr double kContinuity = 5e-3;
  const Scene similar = under_displacement(test::hertz_cycle(kP, kRatio, 512), 0.7e-6);
  Scene near = similar;
  near.specimen = {200.2e9, 0.3};
  const Model ms = make_model(similar), mn = make_model(near);
  const CycleStage s = solve_cycle(similar, ms, solve_normal(similar, ms));
  const CycleStage c = solve_cycle(near, mn, solve_normal(near, mn));
  CHECK(c.route.find("beta") != std::string::npos);
  CHECK(c.Q_max == test::rel(s.Q_max, kContinuity));
  CHECK(c.result.dissipated_energy == test::rel(s.result.dissipated_energy, kContinuity));
  REQUIRE(c.result.stick_zone);
  REQUIRE(s.result.stick_zone);
  const double width_s = s.result.stick_zone->second - s.result.stick_zone->first;
  const double width_c = c.result.stick_zone->second - c.result.stick_zone->first;
  CHECK(width_c == test::rel(width_s, kContinuity));

  // Steel on titanium well past the stick limit: Q stops at f P and the bodies slide.
  const Scene gross = under_displacement(dissimilar_cycle(kTitanium, 512), 5e-6);
  const Model mg = make_model(gross);
  const CycleStage g = solve_cycle(gross, mg, solve_normal(gross, mg));
  CHECK(g.result.regime == Regime::gross_slip);
  CHECK(g.Q_max == test::rel(gross.friction.value() * gross.P, 1e-9));
  CHECK(g.result.sliding_amplitude > 0.0);
  CHECK_FALSE(g.result.stick_zone);

  // Steel on aluminium at 128 cells: there the bounds f p of the coupled pressure at Q = f P, the search's end, sum
  // to f P less a few ulps, and the increment must still be carried (it stopped with no_admissible_cell, exit 3).
  const Scene aluminium = under_displacement(dissimilar_cycle({71e9, 0.33}, 128), 3e-6);
  const Model ma = make_model(aluminium);
  const CycleStage al = solve_cycle(aluminium, ma, solve_normal(aluminium, ma));
  CHECK(al.result.regime == Regime::gross_slip);
  CHECK(al.Q_max == test::rel(aluminium.friction.value() * aluminium.P, 1e-9));
  CHECK(al.result.sliding_amplitude > 0.0);
}

// A load history of dissimilar bodies: each increment is a coupled increment under its own P. The in-phase cycle
// written as a history takes the same increments as force control, so it must give the same cycle to the coupled
// solves' tolerance (coupling_tolerance 1e-8 of the peak pressure: kHistoryAgreement leaves two decades).
TEST_CASE("dissimilar: the in-phase cycle as a load history is force control's cycle, and P may vary") {
  constexpr double kHistoryAgreement = 1e-6;
  const Scene force = dissimilar_cycle(kTitanium, 512);
  const double Q = force.Q_max();
  Scene history = force;
  history.Q_ratio.reset();
  history.history = {{0.0, kP, Q, 0.0}, {1.0, kP, -Q, 0.0}, {2.0, kP, Q, 0.0}};
  const Model m = make_model(force);
  const NormalResult n = solve_normal(force, m);
  const CycleStage a = solve_cycle(force, m, n);
  const CycleStage b = solve_cycle(history, m, n);
  CHECK(b.route.find("incremental (auto: load history) [beta = -0.05156") == 0);
  CHECK(b.result.dissipated_energy == test::rel(a.result.dissipated_energy, kHistoryAgreement));
  CHECK(max_abs_diff(b.result.q_top, a.result.q_top) < kHistoryAgreement * max_of(a.p_top));
  CHECK(max_abs_diff(b.p_top, a.p_top) < kHistoryAgreement * max_of(a.p_top));
  CHECK(max_abs_diff(b.p_bottom, a.p_bottom) < kHistoryAgreement * max_of(a.p_top));

  // P varying out of phase with Q: the coupled pressure carries each increment's P; at the top (Q largest, P = kP)
  // it carries kP, and the cycle closes (the second cycle repeats the first steady one).
  history.history = {{0.0, kP, Q, 0.0}, {1.0, 0.7 * kP, 0.0, 0.0}, {2.0, kP, -Q, 0.0}, {3.0, 1.3 * kP, 0.0, 0.0},
                     {4.0, kP, Q, 0.0}};
  const CycleStage c = solve_cycle(history, m, n);
  REQUIRE(c.p_top.size() == std::size_t(m.grid.n));
  double top = 0.0;
  for (double p : c.p_top) top += m.grid.h() * p;
  CHECK(top == test::rel(kP, 1e-10));
  CHECK(c.result.regime == Regime::partial_slip);
  CHECK(c.result.dissipated_energy > 0.0);
}

// A sweep contracts the coupled increment's change by about f |β| (contact/incremental_slip.hpp): steel on
// aluminium (β = −0.110) settles at f = 8 (f |β| = 0.88) with more sweeps than at f = 0.5, and at f = 9 (0.99) it
// does not, and the error names f |β| as the reason.
TEST_CASE("dissimilar: the coupled sweeps slow as f |beta| nears one, and the error then names it") {
  constexpr Material kAluminium{71e9, 0.33};
  auto at_friction = [&](double f) {
    Scene s = dissimilar_cycle(kAluminium, 256);
    s.friction = f;
    return s;
  };
  const Run low = run(at_friction(0.5)), high = run(at_friction(8.0));
  MESSAGE(fmt::format("f |beta| = {:.3f}: at most {} sweeps an increment; {:.3f}: {}", 0.5 * std::abs(low.beta),
                      low.r.max_coupling_sweeps, 8.0 * std::abs(high.beta), high.r.max_coupling_sweeps));
  CHECK(high.beta == test::rel(-0.1102, 1e-3));
  CHECK(high.r.max_coupling_sweeps > 2 * low.r.max_coupling_sweeps);
  CHECK_THROWS_WITH_AS(run(at_friction(9.0)),
                       doctest::Contains("a sweep contracts the change by about f |beta| = 0.99"), ConvergenceError);
  // Below kSweepsSlowBeyond the message does not blame f |beta|: the cap on the sweeps alone stops f = 0.5 at one.
  IncrementalSlipOptions one;
  one.max_coupling_sweeps = 1;
  try {
    run(at_friction(0.5), one);
    FAIL("one sweep settled a coupled increment");
  } catch (const ConvergenceError& e) {
    CHECK(std::string(e.what()).find("after 1 sweeps") != std::string::npos);
    CHECK(std::string(e.what()).find("f |beta|") == std::string::npos);
  }
}
