// NormalSolver: the preconditioned solver with the carried displacement gives the pressure of plain constrained CG
// (Polonsky and Keer 1999, as first written here) to the tolerance, on Hertz and on a two-zone profile; a warm start
// takes fewer iterations than a cold one.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include <doctest/doctest.h>

#include "contact/closed_form.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"

using namespace fretwear;

namespace {
constexpr double kA = 1.82e-11;  // 1/Pa, PHYSICS.md's steel pair in plane strain
constexpr double kR = 0.01;      // m
constexpr double kP = 1e6;       // N/m
constexpr double kTolerance = 1e-8;
// The residual is a product of pressure and gap, and the gap error is K times the pressure error: an error e in p
// shows in the residual as e², so two solutions that both meet the tolerance agree in pressure to about its square
// root (in units of p_max). Measured: 2e-6 (none) to 1.4e-5 (symbol), at the edge cells. A solution with one cell of
// contact more or less differs by 1e-2.
const double kSamePressure = std::sqrt(kTolerance);

// The solver as first written (two products per iteration, K p recomputed, no preconditioner, cold start on every
// admissible cell), kept as the reference the optimised one must reproduce.
std::vector<double> reference_pressure(const HalfPlaneKernel& kernel, std::span<const double> g0, double P) {
  const int n = kernel.grid().n;
  const double h = kernel.grid().h();
  std::vector<char> admissible(n);
  int n_admissible = 0;
  for (int i = 0; i < n; ++i) n_admissible += admissible[i] = std::isfinite(g0[i]);
  std::vector<double> p(n), g(n), t(n, 0.0), r(n);
  for (int i = 0; i < n; ++i) p[i] = admissible[i] ? P / (h * n_admissible) : 0.0;
  double G_old = 1.0;
  bool conjugate = false;
  for (int it = 0; it < 20000; ++it) {
    kernel.apply(p, g);
    double g_sum = 0.0;
    int n_active = 0;
    for (int i = 0; i < n; ++i) {
      g[i] = admissible[i] ? g[i] + g0[i] : std::numeric_limits<double>::infinity();
      if (p[i] > 0.0) g_sum += g[i], ++n_active;
    }
    const double g_mean = g_sum / n_active;
    double g_max = 0.0, comp = 0.0, overlap = 0.0, G = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!admissible[i]) continue;
      g[i] -= g_mean;
      g_max = std::max(g_max, g[i]);
      if (p[i] > 0.0) comp += p[i] * std::abs(g[i]), G += g[i] * g[i];
      else overlap = std::max(overlap, -g[i]);
    }
    if (std::max(h * comp / (P * g_max), overlap / g_max) <= kTolerance) return p;
    const double beta = conjugate ? G / G_old : 0.0;
    for (int i = 0; i < n; ++i) t[i] = p[i] > 0.0 ? g[i] + beta * t[i] : 0.0;
    G_old = G;
    kernel.apply(t, r);
    double r_sum = 0.0;
    for (int i = 0; i < n; ++i)
      if (p[i] > 0.0) r_sum += r[i];
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; ++i)
      if (p[i] > 0.0) num += g[i] * t[i], den += (r[i] - r_sum / n_active) * t[i];
    const double tau = num / den;
    bool reentered = false;
    double load = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!admissible[i]) continue;
      if (p[i] > 0.0) p[i] = std::max(p[i] - tau * t[i], 0.0);
      else if (g[i] < 0.0) p[i] = -tau * g[i], reentered = true;
      load += h * p[i];
    }
    conjugate = !reentered;
    for (double& pi : p) pi *= P / load;
  }
  FAIL("the reference solver did not converge");
  return p;
}

double max_difference(std::span<const double> a, std::span<const double> b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

int zones(std::span<const double> p) {
  int z = 0;
  for (std::size_t i = 0; i < p.size(); ++i) z += p[i] > 0.0 && (i == 0 || !(p[i - 1] > 0.0));
  return z;
}

struct Case {
  Grid grid;
  std::vector<double> g0;
};

// PHYSICS.md's public Hertz case on ±1.5 a.
Case hertz(int n) {
  const double a = closed_form::hertz(kP, kA, kR).a;
  Case c{Grid{-1.5 * a, 1.5 * a, n}, std::vector<double>(std::size_t(n))};
  for (int i = 0; i < n; ++i) c.g0[i] = c.grid.x(i) * c.grid.x(i) / (2.0 * kR);
  return c;
}

// Two cylinders 1 mm apart, the right one 0.2 µm higher: two zones of unequal width.
Case two_zone(int n) {
  const double s = 0.5e-3;
  Case c{Grid{-1.0e-3, 1.0e-3, n}, std::vector<double>(std::size_t(n))};
  for (int i = 0; i < n; ++i) {
    const double x = c.grid.x(i);
    c.g0[i] = std::min((x + s) * (x + s) / (2.0 * kR), (x - s) * (x - s) / (2.0 * kR) + 0.2e-6);
  }
  return c;
}

void check_same_as_reference(const Case& c) {
  const HalfPlaneKernel kernel(c.grid, kA);
  const std::vector<double> want = reference_pressure(kernel, c.g0, kP);
  const double p_max = *std::max_element(want.begin(), want.end());
  for (auto pre : {NormalSolverOptions::Preconditioner::none, NormalSolverOptions::Preconditioner::symbol}) {
    for (bool incremental : {false, true}) {
      CAPTURE(to_string(pre));
      CAPTURE(incremental);
      NormalSolverOptions o;
      o.preconditioner = pre;
      o.incremental_gap = incremental;
      ContactState s;
      const SolveSummary summary = NormalSolver(kernel, o).solve(c.g0, kP, s);
      REQUIRE(summary.converged());
      CHECK(summary.residual <= kTolerance);
      CHECK(max_difference(s.p, want) <= kSamePressure * p_max);
      CHECK(zones(s.p) == zones(want));
    }
  }
}
}  // namespace

TEST_CASE("every solver variant gives the reference pressure on Hertz") { check_same_as_reference(hertz(1024)); }

TEST_CASE("every solver variant gives the reference pressure on a two-zone profile") {
  const Case c = two_zone(1024);
  const HalfPlaneKernel kernel(c.grid, kA);
  ContactState s;
  REQUIRE(NormalSolver(kernel).solve(c.g0, kP, s).converged());
  REQUIRE(zones(s.p) == 2);
  check_same_as_reference(c);
}

TEST_CASE("the carried displacement is the recomputed one at convergence") {
  const Case c = hertz(4096);
  const HalfPlaneKernel kernel(c.grid, kA);
  ContactState s;
  REQUIRE(NormalSolver(kernel).solve(c.g0, kP, s).converged());
  std::vector<double> u(c.g0.size());
  kernel.apply(s.p, u);
  double g_max = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    g_max = std::max(g_max, s.gap[i]);
    worst = std::max(worst, std::abs(c.g0[i] + u[i] - s.approach - s.gap[i]));
  }
  CHECK(worst <= 1e-12 * g_max);
}

TEST_CASE("a warm start from a nearby load or a worn profile takes fewer iterations than a cold start") {
  for (int n : {1024, 8192}) {
    CAPTURE(n);
    const Case c = hertz(n);
    const HalfPlaneKernel kernel(c.grid, kA);
    const NormalSolver solver(kernel);
    ContactState cold;
    const SolveSummary cold_summary = solver.solve(c.g0, kP, cold);
    REQUIRE(cold_summary.converged());

    ContactState warm;
    REQUIRE(solver.solve(c.g0, 0.99 * kP, warm).converged());
    const SolveSummary warm_summary = solver.solve(c.g0, kP, warm);
    REQUIRE(warm_summary.converged());
    CHECK(warm_summary.iterations < cold_summary.iterations);
    CHECK(max_difference(warm.p, cold.p) <= kSamePressure * closed_form::hertz(kP, kA, kR).p0);

    std::vector<double> worn = c.g0;
    const double a = closed_form::hertz(kP, kA, kR).a;
    for (int i = 0; i < n; ++i) {
      const double s = c.grid.x(i) / a;
      if (std::abs(s) < 1.0) worn[i] += 1e-7 * (1.0 - s * s);
    }
    ContactState worn_cold, worn_warm = cold;
    const SolveSummary worn_cold_summary = solver.solve(worn, kP, worn_cold);
    const SolveSummary worn_warm_summary = solver.solve(worn, kP, worn_warm);
    REQUIRE(worn_cold_summary.converged());
    REQUIRE(worn_warm_summary.converged());
    CHECK(worn_warm_summary.iterations < worn_cold_summary.iterations);
  }
}

TEST_CASE("invalid options name the field, its value and the constraint") {
  NormalSolverOptions o;
  CHECK(o.validate().empty());
  o.proportioning = kWearProportioning;
  CHECK(o.validate().empty());
  o.proportioning = -0.5;
  CHECK(o.validate().find("proportioning = -0.5") != std::string::npos);
  o = {};
  o.tolerance = 0.1;
  CHECK(o.validate().find("tolerance = 0.1") != std::string::npos);
  o = {};
  o.max_iterations = 0;
  CHECK(o.validate().find("max_iterations = 0") != std::string::npos);
}
