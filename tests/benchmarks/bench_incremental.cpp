// The incremental route of cyclic partial slip (contact/incremental_slip.hpp): one steady cycle of 40 increments
// (after the first loading's 10) at N = 1024 on PHYSICS.md's Hertz case (R = 10 mm, E = 200 GPa, ν = 0.3 both,
// plane strain, P = 1e5 N/m, f = 0.5, Q/fP = 0.6), with and without Nowell–Hills' bulk tension σ/(f p0) = 0.6 at
// Q/fP = 0.5. Budget: ≤ 50 ms per cycle. docs/PERFORMANCE.md has the command and the numbers. The normal
// solve is outside the timed loop.
#include <vector>

#include <benchmark/benchmark.h>

#include "contact/closed_form.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/simulation.hpp"
#include "scenes.hpp"

namespace {
using namespace fretwear;

Scene hertz_cycle(int cells, double ratio, double sigma_over_fp0) {
  const auto hz = closed_form::hertz(1e5, 4 * (1 - 0.3 * 0.3) / 200e9, test::kHertzR);
  Scene s = test::hertz_cycle(1e5, ratio, cells, sigma_over_fp0 * test::kHertzF * hz.p0);
  s.name = "bench";
  return s;
}

// Arguments: cells, increments per cycle, preconditioner (0 none, 1 symbol), bulk tension (0 or 1).
void BM_IncrementalCycle(benchmark::State& st) {
  const bool tension = st.range(3) != 0;
  const Scene s = hertz_cycle(int(st.range(0)), tension ? 0.5 : 0.6, tension ? 0.6 : 0.0);
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const double strain = s.bulk_stress * (m.pair.kappa_specimen() + 1.0) / (8.0 * m.pair.mu_specimen());
  const CyclicLoad load{s.P, s.Q_max(), *s.friction, strain};
  IncrementalSlipOptions o;
  o.increments_per_cycle = int(st.range(1));
  o.preconditioner = NormalSolverOptions::Preconditioner(st.range(2));
  const IncrementalSlipSolver solver(*m.kernel, o);
  IncrementalResult r;
  for (auto _ : st) {
    r = solver.solve(n.state, load);
    benchmark::DoNotOptimize(r.cycles.data());
  }
  st.counters["increments"] = r.n_increments;
  st.counters["iterations"] = r.n_iterations;
  st.counters["worst_residual"] = r.worst.residual;
}
BENCHMARK(BM_IncrementalCycle)
    ->Args({1024, 40, 1, 0})
    ->Args({1024, 40, 0, 0})
    ->Args({1024, 40, 1, 1})
    ->Args({4096, 40, 1, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
