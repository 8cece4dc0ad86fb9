// The crack solver (contact/crack_solver.hpp) against PHYSICS.md ("Cracks"): the edge crack in uniform tension
// (1.121522) with the O(N⁻²) convergence rate, the linearly varying loads (0.682863, 0.438659), mode II by the
// kernel's symmetry with PHYSICS.md's sign, a large quadrature, the depth table against direct evaluation, a crack
// shorter than a cell, and closure under compression.
#include <cmath>
#include <numbers>
#include <vector>

#include <doctest/doctest.h>

#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/crack_solver.hpp"
#include "common/error.hpp"

using namespace fretwear;
using fretwear::test::rel;

namespace {

constexpr double kPi = std::numbers::pi;
// PHYSICS.md's reference factors K/(σ√(πl)), printed to 6 decimals.
constexpr double kUniform = 1.121522, kRising = 0.682863, kFalling = 0.438659;
constexpr double kPrintedDigit = 0.5e-6;
// The quadrature error of the uniform load is 0.38/N² (observed from N = 20 to 640); the bound leaves a margin.
double quadrature_error(int n) { return 0.5 / (double(n) * n); }

constexpr double kSigma = 1e8;  // Pa
constexpr double kL = 1e-3;     // m

double factor(double K, double l = kL) { return K / (kSigma * std::sqrt(kPi * l)); }

double uniform_factor(int n) {
  const CrackSolver s({n});
  return factor(s.sif(kL, [](double) { return kSigma; }, {}).K_I);
}

// Hertz pressure (cell averages) and full sliding q = f p on n cells over ±1.5 a, PHYSICS.md's steel pair.
struct HertzLoad {
  closed_form::Hertz hz = closed_form::hertz(1e5, 1.82e-11, 0.01);
  Grid grid;
  std::vector<double> p, q;
  HertzLoad(int n, double f) : grid{-1.5 * hz.a, 1.5 * hz.a, n}, p(std::size_t(n)), q(std::size_t(n)) {
    for (int i = 0; i < n; ++i) {
      p[i] = hz.cell_average(grid.left(i), grid.left(i + 1));
      q[i] = f * p[i];
    }
  }
};

}  // namespace

TEST_CASE("Edge crack, uniform tension: K_I/(sigma sqrt(pi l)) = 1.121522, converging as N^-2") {
  const double at60 = uniform_factor(60);
  CHECK(at60 == rel(kUniform, 1e-3));
  CHECK(std::abs(at60 - kUniform) < quadrature_error(60));
  // PHYSICS.md's two quoted values, to the digits it prints.
  CHECK(std::abs(uniform_factor(80) - 1.12146) < 0.5e-5);
  CHECK(std::abs(uniform_factor(320) - 1.12152) < 0.5e-5);
  // The rate without the reference: successive differences of N = 20, 40, 80, 160, 320 shrink by 2^order.
  std::vector<double> K;
  for (int n : {20, 40, 80, 160, 320}) K.push_back(uniform_factor(n));
  for (std::size_t i = 0; i + 2 < K.size(); ++i) {
    const double order = std::log2((K[i + 1] - K[i]) / (K[i + 2] - K[i + 1]));
    MESSAGE("N = " << (20 << i) << ": K = " << K[i] << ", observed order " << order);
    CHECK(order == rel(2.0, 0.05));
  }
  // Richardson at order 2 from 160 and 320 reaches the reference to its printed digits.
  CHECK(std::abs((4.0 * K[4] - K[3]) / 3.0 - kUniform) < 2 * kPrintedDigit);
}

TEST_CASE("Linearly varying loads: sigma eta/l gives 0.682863, sigma (1 - eta/l) gives 0.438659") {
  for (int n : {60, 320}) {
    CAPTURE(n);
    const CrackSolver s({n});
    const double rising = factor(s.sif(kL, [](double eta) { return kSigma * eta / kL; }, {}).K_I);
    const double falling = factor(s.sif(kL, [](double eta) { return kSigma * (1.0 - eta / kL); }, {}).K_I);
    // A load vanishing at the mouth suits the quadrature's weight: the rising load converges much faster.
    CHECK(std::abs(rising - kRising) < kPrintedDigit);
    CHECK(std::abs(falling - kFalling) < quadrature_error(n));
    CHECK(rising + falling == rel(uniform_factor(n), 1e-12));
  }
}

TEST_CASE("Mode II: a uniform shear gives the same 1.1215, with the sign of sigma_xy ahead of the tip") {
  const CrackSolver s;
  for (double tau : {kSigma, -kSigma}) {
    const CrackSif r = s.sif(kL, {}, [&](double) { return tau; });
    CHECK(r.K_II == rel(tau / kSigma * uniform_factor(60) * kSigma * std::sqrt(kPi * kL), 1e-12));
    CHECK(r.K_I == 0.0);
  }
}

TEST_CASE("400 quadrature points stay stable") {
  const CrackSolver s({400});
  const double K = factor(s.sif(kL, [](double) { return kSigma; }, {}).K_I);
  CHECK(std::abs(K - kUniform) < quadrature_error(400));
  CHECK(std::abs(K - kUniform) < std::abs(uniform_factor(320) - kUniform));
  // The density is finite and positive: tension opens the crack everywhere.
  for (double phi : s.density(kL, [](double) { return kSigma; })) {
    CHECK(std::isfinite(phi));
    CHECK(phi > 0.0);
  }
}

TEST_CASE("Options are validated") {
  CrackSolverOptions few_nodes;
  few_nodes.n_quadrature = 1;
  CHECK(!few_nodes.validate().empty());
  CHECK_THROWS_AS(CrackSolver{few_nodes}, InputError);
  CHECK_THROWS_AS(CrackSolver().sif(0.0, {}, {}), InputError);
}

TEST_CASE("Below a Hertz contact in full sliding: solve() gives the SIFs of the stress evaluated along the crack") {
  const HertzLoad L(1024, 0.5);
  const SurfaceTractions t{L.grid, L.p, L.q, 0.1 * L.hz.p0};
  const double a = L.hz.a, x_c = -a;
  std::vector<double> lengths;
  for (int k = 0; k < 12; ++k) lengths.push_back(a * 0.002 * std::pow(1000.0, k / 11.0));
  const CrackSolver s;
  const CrackResult r = s.solve(t, x_c, lengths);
  REQUIRE(r.sifs.size() == lengths.size());
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    CAPTURE(lengths[k] / a);
    const CrackSif d = s.sif(
        lengths[k], [&](double eta) { return stress_at(t, x_c, eta).xx; },
        [&](double eta) { return stress_at(t, x_c, eta).xy; });
    // The same stresses at the same points, gathered once for every length instead of point by point: round-off.
    const double scale = L.hz.p0 * std::sqrt(kPi * lengths[k]);
    CHECK(r.sifs[k].l == lengths[k]);
    CHECK(std::abs(r.sifs[k].K_I_open - d.K_I_open) < 1e-12 * scale);
    CHECK(std::abs(r.sifs[k].K_II - d.K_II) < 1e-12 * scale);
    // The trailing edge is in tension: the crack is open.
    CHECK(r.sifs[k].K_I > 0.0);
  }
}

TEST_CASE("A length's SIFs are the same whatever other lengths are listed with it") {
  // Each length's stress is evaluated at its own points: listed alone or beside one a thousand times longer, the
  // same numbers. (A table to the longest length, read by every length, put 0.35 % into K_I of 0.7 a beside 700 a.)
  const HertzLoad L(1024, 0.5);
  const SurfaceTractions t{L.grid, L.p, L.q, 0.1 * L.hz.p0};
  const double a = L.hz.a, x_c = -a;
  const CrackSolver s;
  for (const double l : {0.002 * a, 0.05 * a, 0.7 * a}) {
    CAPTURE(l / a);
    const CrackSif alone = s.solve(t, x_c, std::vector<double>{l}).sifs.front();
    const CrackResult listed = s.solve(t, x_c, std::vector<double>{1000.0 * l, l, 3.0 * l});
    const CrackSif& beside = listed.sifs[1];
    CHECK(beside.l == l);
    CHECK(beside.K_I_open == alone.K_I_open);
    CHECK(beside.K_II == alone.K_II);
    CHECK(beside.K_I == alone.K_I);
  }
}

TEST_CASE("A uniform bulk tension alone gives 1.1215 sigma sqrt(pi l) for every length") {
  const Grid g{-1e-3, 1e-3, 64};
  const std::vector<double> zero(64, 0.0);
  const SurfaceTractions t{g, zero, zero, kSigma};
  const std::vector<double> lengths = {1e-6, 1e-4, 3e-3};
  const CrackSolver s;
  const CrackResult r = s.solve(t, 0.0, lengths);
  for (const CrackSif& c : r.sifs) {
    CHECK(factor(c.K_I, c.l) == rel(uniform_factor(60), 1e-12));
    CHECK(std::abs(c.K_II) < 1e-12 * kSigma * std::sqrt(kPi * c.l));
  }
}

TEST_CASE("A crack shorter than one cell sees the surface stress and its gradient") {
  // For l ≪ h the crack-line stress is σ(0) + σ′(0) η + O(η²), so K/√(πl) = F_u σ(0) + F_r σ′(0) l + O(σ″ l²),
  // with F_u, F_r the uniform and rising factors of the same quadrature. σ varies on the scale of the half cell to
  // the nearest jump, so the remainder is O((2l/h)²) relative.
  const HertzLoad L(256, 0.5);
  const SurfaceTractions t{L.grid, L.p, L.q, 0.0};
  const double h = L.grid.h(), x_c = L.grid.x(50), l = 0.02 * h;
  const CrackSolver s;
  const double d = 1e-4 * l;
  const Stress s0 = stress_at(t, x_c, 0.0), s1 = stress_at(t, x_c, d), s2 = stress_at(t, x_c, 2 * d);
  const double dxx = (-3 * s0.xx + 4 * s1.xx - s2.xx) / (2 * d), dxy = (-3 * s0.xy + 4 * s1.xy - s2.xy) / (2 * d);
  const CrackSif want = s.sif(
      l, [&](double eta) { return s0.xx + dxx * eta; }, [&](double eta) { return s0.xy + dxy * eta; });
  const CrackSif got = s.solve(t, x_c, std::vector<double>{l}).sifs.front();
  const double remainder = (2 * l / h) * (2 * l / h);
  CHECK(got.K_I_open == rel(want.K_I_open, remainder));
  CHECK(got.K_II == rel(want.K_II, remainder));
  // And the leading term alone is the surface stress times the edge-crack factor.
  CHECK(got.K_I_open == rel(uniform_factor(60) * s0.xx * std::sqrt(kPi * l), 4 * l / h));
}

TEST_CASE("Under pure compression the crack closes: K_I = 0, the open value negative beside it") {
  const HertzLoad L(512, 0.0);
  const SurfaceTractions t{L.grid, L.p, {}, 0.0};
  const CrackSolver s;
  const std::vector<double> lengths = {0.01 * L.hz.a, 0.3 * L.hz.a, 2.0 * L.hz.a};
  for (const CrackSif& c : s.solve(t, 0.0, lengths).sifs) {
    CAPTURE(c.l);
    CHECK(c.closed);
    CHECK(c.K_I == 0.0);
    CHECK(c.K_I_open < 0.0);
    // On the axis of a symmetric pressure σxy = 0: no mode II.
    CHECK(std::abs(c.K_II) < 1e-9 * L.hz.p0 * std::sqrt(kPi * c.l));
  }
}
