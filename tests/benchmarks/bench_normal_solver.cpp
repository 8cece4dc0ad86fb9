// The normal solver against ARCHITECTURE.md's performance budget, on PHYSICS.md's public Hertz case: E = 200 GPa,
// ν = 0.3 for both bodies, plane strain, R = 10 mm, P = 1e6 N/m, window ±1.5 a. docs/PERFORMANCE.md has the
// commands and the numbers. Build with -DCMAKE_BUILD_TYPE=Release (the default).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "contact/closed_form.hpp"
#include "contact/elastic_pair.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"

namespace {
using namespace fretwear;

constexpr double kR = 0.01;  // m
constexpr double kP = 1e6;   // N/m

double composite_A() {
  const Material steel{200e9, 0.3};
  return ElasticPair(steel, steel, PlaneState::strain).A();
}

struct HertzCase {
  double A = composite_A();
  double a = closed_form::hertz(kP, A, kR).a;
  Grid grid;
  HalfPlaneKernel kernel;
  std::vector<double> g0;

  explicit HertzCase(int n) : grid{-1.5 * a, 1.5 * a, n}, kernel(grid, A), g0(std::size_t(n)) {
    for (int i = 0; i < n; ++i) g0[i] = grid.x(i) * grid.x(i) / (2.0 * kR);
  }
};

// Second argument: the preconditioner (-1: the default, 0: none, 1: symbol); third, when present: 0 recomputes
// K p at every iteration instead of carrying it.
NormalSolverOptions options_from(const benchmark::State& st) {
  NormalSolverOptions o;
  if (st.range(1) >= 0) o.preconditioner = NormalSolverOptions::Preconditioner(st.range(1));
  if (st.range(2) == 0) o.incremental_gap = false;
  return o;
}

// Cold: uniform starting pressure, as the first solve of a scene.
void BM_ColdHertz(benchmark::State& st) {
  const HertzCase c(int(st.range(0)));
  const NormalSolver solver(c.kernel, options_from(st));
  ContactState s;
  SolveSummary summary;
  for (auto _ : st) {
    s.p.clear();
    summary = solver.solve(c.g0, kP, s);
    benchmark::DoNotOptimize(s.p.data());
  }
  if (!summary.converged()) st.SkipWithError(summary.brief().c_str());
  st.counters["iterations"] = summary.iterations;
  st.counters["residual"] = summary.residual;
  st.SetComplexityN(st.range(0));
}

// Warm: from the solution at a 1 % lower load, as between the solves of a wear run.
void BM_WarmHertzLoad(benchmark::State& st) {
  const HertzCase c(int(st.range(0)));
  const NormalSolver solver(c.kernel, options_from(st));
  ContactState start;
  solver.solve(c.g0, 0.99 * kP, start);
  ContactState s;
  SolveSummary summary;
  for (auto _ : st) {
    s.p = start.p;
    summary = solver.solve(c.g0, kP, s);
    benchmark::DoNotOptimize(s.p.data());
  }
  if (!summary.converged()) st.SkipWithError(summary.brief().c_str());
  st.counters["iterations"] = summary.iterations;
}

// Warm: from the solution of the unworn profile, after a wear step that removed up to 0.1 µm near the centre
// (about 1 % of the peak elastic approach).
void BM_WarmHertzWorn(benchmark::State& st) {
  const HertzCase c(int(st.range(0)));
  const NormalSolver solver(c.kernel, options_from(st));
  ContactState start;
  solver.solve(c.g0, kP, start);
  std::vector<double> worn = c.g0;
  for (int i = 0; i < c.grid.n; ++i) {
    const double s = c.grid.x(i) / c.a;
    if (std::abs(s) < 1.0) worn[i] += 1e-7 * (1.0 - s * s);
  }
  ContactState s;
  SolveSummary summary;
  for (auto _ : st) {
    s.p = start.p;
    summary = solver.solve(worn, kP, s);
    benchmark::DoNotOptimize(s.p.data());
  }
  if (!summary.converged()) st.SkipWithError(summary.brief().c_str());
  st.counters["iterations"] = summary.iterations;
}

// One influence product u = K p (two real FFTs of length 2N).
void BM_ToeplitzProduct(benchmark::State& st) {
  const HertzCase c(int(st.range(0)));
  std::vector<double> p(c.g0.size(), 1.0), u(c.g0.size());
  for (auto _ : st) {
    c.kernel.apply(p, u);
    benchmark::DoNotOptimize(u.data());
  }
  st.SetComplexityN(st.range(0));
}

BENCHMARK(BM_ColdHertz)->ArgsProduct({benchmark::CreateRange(1024, 65536, 2), {-1}, {-1}})
    ->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_WarmHertzLoad)->ArgsProduct({{1024, 8192}, {-1}, {-1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WarmHertzWorn)->ArgsProduct({{1024, 8192}, {-1}, {-1}})->Unit(benchmark::kMillisecond);
// What each option buys: every preconditioner with and without the carried K p.
BENCHMARK(BM_ColdHertz)->Name("BM_ColdHertzOptions")
    ->ArgsProduct({{1024, 8192, 65536}, {0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WarmHertzLoad)->Name("BM_WarmHertzLoadOptions")->ArgsProduct({{1024, 8192}, {0, 1}, {1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ToeplitzProduct)->RangeMultiplier(2)->Range(1024, 65536)->Unit(benchmark::kMicrosecond)->Complexity();

}  // namespace
