// The life stage (engine/life_stage.hpp): a life prediction with wear as ARCHITECTURE.md's budget states it (1024
// cells, 10^6 cycles of Archard wear in 8 records, SWT by the line method over 20 µm, Paris growth from 20 µm to
// 1 mm), on a Hertz contact with bulk tension (R = 10 mm, P = 100 kN/m, f = 0.5, Q/fP = 0.7, σ = 250 MPa). Budget:
// ≤ 3 s for the whole run. BM_LifeStage times the life stage alone on the run's wear records; BM_LifeRun the whole
// run (normal, cycle, wear and life). docs/PERFORMANCE.md has the command and the numbers.
#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include "engine/simulation.hpp"

namespace {
using namespace fretwear;
using nlohmann::json;

Scene life_scene() {
  const json j = {
      {"name", "bench_life"},
      {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
      {"friction", 0.5},
      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.7}}}, {"bulk_stress", {{"amplitude", 250e6}}}}},
      {"grid", {{"cells", 1024}}},
      {"effects",
       {{"wear", {{"law", "archard"}, {"k", 1e-14}, {"cycles", 1e6}, {"record", 8}}},
        {"life", {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52},
                                  {"critical_distance", 2e-5}}},
                  {"growth", {{"C", 5e-30}, {"m", 3.0}, {"dK_th", 2e6}, {"a_final", 1e-3}}}}}}}};
  return parse_scene(j);
}

void BM_LifeStage(benchmark::State& st) {
  const Scene s = life_scene();
  const Setup setup = make_setup(s);
  const NormalResult n = solve_normal(s, setup.model);
  const CycleStage c = solve_cycle(s, setup.model, *setup.cycle, n);
  const WearStage w = run_wear(s, setup.model, n, c);
  for (auto _ : st) {
    LifeStage life = run_life(s, setup.model, n, c, &w);
    benchmark::DoNotOptimize(life.total_cycles);
  }
  st.counters["records"] = double(w.records.size());
}
BENCHMARK(BM_LifeStage)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_LifeRun(benchmark::State& st) {
  const Scene s = life_scene();
  for (auto _ : st) {
    RunResult r = Simulation(s).run();
    benchmark::DoNotOptimize(r.timings.total);
  }
}
BENCHMARK(BM_LifeRun)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
