// The cost of Dundurs' coupling in a wear run (issue: a dissimilar 10^6-cycle wear run at 1024 cells within 3× the
// similar one). The case: the Hertz wear scene of PHYSICS.md (R = 10 mm, P = 100 kN/m, f = 0.5, Q/fP = 0.5, Archard
// k = 1e-12 1/Pa, 10^6 cycles, 8 records, 1024 cells, force control), once with two steel bodies (β = 0: the
// Ciavarella–Jäger analogy) and once with a steel pad on an aluminium specimen (E = 71 GPa, ν = 0.33; β ≈ −0.11:
// the coupled incremental route, which solves normal and tangential problems together, with its lagged coupling and
// its settling march: engine/wear_contacts.hpp). Each iteration runs the whole
// scene (normal, cycle, wear) as the command line does, without writing files. docs/PERFORMANCE.md ("Dissimilar
// bodies") has the command and the measured ratio.
#include <benchmark/benchmark.h>

#include "engine/simulation.hpp"
#include "scenes.hpp"

namespace {
using namespace fretwear;

Scene wear_scene(bool dissimilar) {
  Scene s = test::hertz_wear(1e5, 0.5, 1e6, 1024);
  s.name = dissimilar ? "bench_dissimilar" : "bench_similar";
  if (dissimilar) s.specimen = {71e9, 0.33};
  return s;
}

void run(benchmark::State& state, bool dissimilar) {
  const Scene scene = wear_scene(dissimilar);
  double steps = 0.0;
  for (auto _ : state) {
    const RunResult r = Simulation(scene).run();
    benchmark::DoNotOptimize(r.wear->records.back().worn_area);
    steps = double(r.wear->steps);
  }
  state.counters["steps"] = steps;
}

void BM_wear_similar(benchmark::State& state) { run(state, false); }
void BM_wear_dissimilar(benchmark::State& state) { run(state, true); }

BENCHMARK(BM_wear_similar)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_wear_dissimilar)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
