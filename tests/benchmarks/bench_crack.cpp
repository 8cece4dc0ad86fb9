// The crack solver on the case: SIFs for 50 crack depths at the trailing edge of PHYSICS.md's Hertz
// contact (P = 1e5 N/m, steel pair, full sliding f = 0.5, bulk tension 0.1 p0) from 1024 cells over ±1.5 a, with
// 60 quadrature points. Budget ≤ 100 ms. docs/PERFORMANCE.md ("Crack SIFs") has the command and the numbers.
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "contact/closed_form.hpp"
#include "contact/crack_solver.hpp"

namespace {
using namespace fretwear;

struct Case {
  closed_form::Hertz hz = closed_form::hertz(1e5, 1.82e-11, 0.01);
  Grid grid{-1.5 * hz.a, 1.5 * hz.a, 1024};
  std::vector<double> p, q, lengths;
  Case() {
    for (int i = 0; i < grid.n; ++i) {
      p.push_back(hz.cell_average(grid.left(i), grid.left(i + 1)));
      q.push_back(0.5 * p.back());
    }
    for (int k = 0; k < 50; ++k) lengths.push_back(hz.a * 0.002 * std::pow(1000.0, k / 49.0));  // 0.002 a … 2 a
  }
};

// The whole call: the stress at each length's 60 collocation points, then 50 SIFs. The solver's factorisation is
// built once outside the loop, as a scene builds it once.
void BM_CrackSifs50(benchmark::State& st) {
  const Case c;
  const CrackSolver solver;
  const SurfaceTractions t{c.grid, c.p, c.q, 0.1 * c.hz.p0};
  for (auto _ : st) {
    CrackResult r = solver.solve(t, -c.hz.a, c.lengths);
    benchmark::DoNotOptimize(r.sifs.data());
  }
}
BENCHMARK(BM_CrackSifs50)->Unit(benchmark::kMillisecond);

// The same 50 depths for a crack inclined at 45° (the coupled 2N system per depth), with frictional face contact
// (f = 0.5) where the faces would overlap.
void BM_CrackSifs50Inclined(benchmark::State& st) {
  const Case c;
  const CrackSolver solver({}, CrackSpec{double(st.range(0)), 0.5});
  const SurfaceTractions t{c.grid, c.p, c.q, 0.1 * c.hz.p0};
  for (auto _ : st) {
    CrackResult r = solver.solve(t, -c.hz.a, c.lengths);
    benchmark::DoNotOptimize(r.sifs.data());
  }
}
BENCHMARK(BM_CrackSifs50Inclined)->Arg(45)->Arg(135)->Unit(benchmark::kMillisecond);

// Building the solver: the N×N factorisation and the tip functional.
void BM_CrackSolverSetup(benchmark::State& st) {
  CrackSolverOptions o;
  o.n_quadrature = int(st.range(0));
  for (auto _ : st) {
    CrackSolver s(o);
    benchmark::DoNotOptimize(s.tip_weights().data());
  }
}
BENCHMARK(BM_CrackSolverSetup)->Arg(60)->Arg(400)->Unit(benchmark::kMillisecond);

}  // namespace
