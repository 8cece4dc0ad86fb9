// Accuracy against cost of the three wear steppers (ARCHITECTURE.md, "Wear in time") and the budget "≤ 50 steps for
// 1 % wear-profile error" at N = 512 over 10^5 cycles. The case: PHYSICS.md's Hertz wear case (R = 10 mm, E = 200 GPa,
// ν = 0.3 both, plane strain, P = 1e5 N/m, f = 0.5, Q/fP = 0.5, Archard k = 1e-12 1/Pa) on 512 cells, recorded at
// 10^3, 10^4 and 10^5 cycles: the worn area is 19.5 %, 100.4 % and 101.2 % of the asymptote's there, so the records
// see the transient as well as the limit (an attractor, which damps earlier errors: an error taken at 10^5 cycles
// alone would flatter every stepper). docs/PERFORMANCE.md ("Wear steppers") has the command and the table.
//
// Each row runs the whole wear stage (the asymptote, the run, the record) on a model and normal solution built once.
// Counters: tolerance, steps (accepted) and rejected, responses (steady-cycle solves: two contact solves each),
// implicit_solves, error_cbc (the worst over the three records of max_i |w − w_cbc| / max_i w_cbc, against cycle
// by cycle), error_tight (the same against the implicit stepper at 1e-5), cap (the explicit stepper's cap on ΔN,
// cycles). The
// references are computed once, outside the timed loops. BM_budget runs the implicit stepper from tolerance 0.1
// down by factors of 10^(1/4) until the error against cycle by cycle is ≤ 1 % and reports that run (met = 1 when it
// took ≤ 50 steps); its time is the whole search.
//
// tolerance/<tol> asks whether the tolerance bounds the error it leaves: the implicit stepper at 1e-1 … 1e-4 against
// itself at 1e-5, the tightest it runs on this case (below about 7e-6 its first step's estimate does not fall with
// ΔN: 1e-6 ends in odeint's "a new step size was not found", 1e-7 shrinks ΔN toward 1e-305 and does not finish),
// with counters error (the same max-norm over the records) and ratio = error / tolerance. long_run/N and gross_slip_example time the wear stage of examples/hertz_wear.json (N cells) and
// of examples/gross_slip_displacement_wear.json (1024 cells, the incremental route in gross slip).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"

namespace {
using namespace fretwear;

constexpr double kCycles = 1e5;
constexpr int kCells = 512;
constexpr double kTightTolerance = 1e-5;  // the implicit stepper's reference (its floor is about 1e-5: below, the
                                          // first step's error estimate meets the contact solves' own residual)
constexpr double kBudgetError = 1e-2;     // ARCHITECTURE.md: 1 % wear-profile error ...
constexpr int kBudgetSteps = 50;          // ... in ≤ 50 steps

Scene hertz_wear(const std::string& stepper, double tolerance) {
  Scene s = test::hertz_wear(1e5, 0.5, kCycles, kCells);
  s.name = "bench_wear_steppers";
  s.wear->record = {1e3, 1e4, kCycles};
  s.wear->stepper = stepper_from_string(stepper);
  s.wear->tolerance = tolerance;
  return s;
}

struct Case {
  Scene scene = hertz_wear("implicit", 1e-3);
  Model model = make_model(scene);
  NormalResult normal = solve_normal(scene, model);
};

const Case& the_case() {
  static const Case c;
  return c;
}

WearStage run(const std::string& stepper, double tolerance) {
  const Scene s = hertz_wear(stepper, tolerance);
  return run_wear(s, the_case().model, the_case().normal, solve_cycle(s, the_case().model, the_case().normal));
}

std::vector<WearRecord>& cbc_cache() {
  static std::vector<WearRecord> records;
  return records;
}

const std::vector<WearRecord>& cycle_by_cycle_records() {
  if (cbc_cache().empty()) cbc_cache() = run("cycle_by_cycle", 1e-3).records;
  return cbc_cache();
}

const std::vector<WearRecord>& tight_records() {
  static const std::vector<WearRecord> records = run("implicit", kTightTolerance).records;
  return records;
}

// The worst over the records after the unworn one of max_i |w_i − w_ref,i| / max_i w_ref,i.
double profile_error(const std::vector<WearRecord>& got, const std::vector<WearRecord>& ref) {
  double e = 0.0;
  for (std::size_t r = 1; r < ref.size(); ++r) {
    double diff = 0.0, depth = 0.0;
    for (std::size_t i = 0; i < ref[r].w.size(); ++i) {
      diff = std::max(diff, std::abs(got[r].w[i] - ref[r].w[i]));
      depth = std::max(depth, ref[r].w[i]);
    }
    e = std::max(e, diff / depth);
  }
  return e;
}

void report(benchmark::State& st, const WearStage& w, double tolerance) {
  st.counters["tolerance"] = tolerance;
  st.counters["steps"] = w.steps;
  st.counters["rejected"] = w.rejected_steps;
  st.counters["responses"] = w.responses;
  st.counters["implicit_solves"] = w.implicit_solves;
  st.counters["error_cbc"] = profile_error(w.records, cycle_by_cycle_records());
  st.counters["error_tight"] = profile_error(w.records, tight_records());
  if (w.explicit_step_cap > 0.0) st.counters["cap"] = w.explicit_step_cap;
}

void BM_stepper(benchmark::State& st, const std::string& stepper, double tolerance) {
  (void)the_case();  // the model and the normal solve, outside the timing
  WearStage w;
  for (auto _ : st) w = run(stepper, tolerance);
  if (stepper == "cycle_by_cycle" && cbc_cache().empty()) cbc_cache() = w.records;
  report(st, w, tolerance);
}

void BM_budget(benchmark::State& st) {
  (void)cycle_by_cycle_records();
  double tolerance = 0.1;
  WearStage w;
  for (auto _ : st) {
    for (tolerance = 0.1; tolerance >= 1e-4; tolerance /= std::pow(10.0, 0.25)) {
      w = run("implicit", tolerance);
      if (profile_error(w.records, cycle_by_cycle_records()) <= kBudgetError) break;
    }
  }
  report(st, w, tolerance);
  st.counters["met"] = w.steps <= kBudgetSteps && st.counters["error_cbc"] <= kBudgetError;
}

void BM_honest(benchmark::State& st, double tolerance) {
  (void)tight_records();
  WearStage w;
  for (auto _ : st) w = run("implicit", tolerance);
  const double error = profile_error(w.records, tight_records());
  st.counters["tolerance"] = tolerance;
  st.counters["steps"] = w.steps;
  st.counters["rejected"] = w.rejected_steps;
  st.counters["error"] = error;
  st.counters["ratio"] = error / tolerance;
}

// The budget "a 10^7-cycle partial-slip Hertz wear run: ≤ 1 s at N = 1024, ≤ 10 s at N = 4096" (ARCHITECTURE.md):
// the same case over 10^7 cycles at the default tolerance (1e-3) with 16 log-spaced records, as
// examples/hertz_wear.json runs it; the model and the normal solve are built outside the timing.
void BM_long_run(benchmark::State& st) {
  const int cells = int(st.range(0));
  Scene s = test::hertz_wear(1e5, 0.5, 1e7, cells);
  s.name = "bench_long_run";
  s.wear->record_count = 16;
  const Model model = make_model(s);
  const NormalResult normal = solve_normal(s, model);
  WearStage w;
  const CycleStage cycle = solve_cycle(s, model, normal);
  for (auto _ : st) w = run_wear(s, model, normal, cycle);
  st.counters["steps"] = w.steps;
  st.counters["rejected"] = w.rejected_steps;
  st.counters["implicit_solves"] = w.implicit_solves;
  st.counters["implicit_iterations"] = w.mean_iterations_implicit;
  st.counters["cycle_iterations"] = w.mean_iterations_cycle;
  st.counters["of_asymptote"] = w.records.back().fraction;
  st.counters["responses"] = w.responses;
}

// examples/gross_slip_displacement_wear.json (18 000 cycles, displacement control in gross slip: the incremental
// route) at `cells` cells: both bodies wearing, each in its own frame (engine/body_frames.hpp), or with
// pad_fraction = 1, one profile (only the pad wears: the shared profile's stepper); with `dissimilar`, a titanium
// specimen (110 GPa, 0.34; β = −0.052), whose frames solve each position's pressure for both sliding directions.
// The model, the normal solve and the cycle stage outside the timing.
void BM_gross_slip_example(benchmark::State& st, bool frames, bool dissimilar) {
  Scene s = load_scene(std::string(FRETWEAR_SOURCE_DIR) + "/examples/gross_slip_displacement_wear.json");
  s.cells = int(st.range(0));
  if (!frames) s.wear->pad_fraction = 1.0;
  if (dissimilar) s.similar = false, s.specimen = Material{110e9, 0.34};
  const Model model = make_model(s);
  const NormalResult normal = solve_normal(s, model);
  const CycleStage cycle = solve_cycle(s, model, normal);
  WearStage w;
  for (auto _ : st) w = run_wear(s, model, normal, cycle);
  st.counters["steps"] = w.steps;
  st.counters["rejected"] = w.rejected_steps;
  st.counters["implicit_solves"] = w.implicit_solves;
  st.counters["responses"] = w.responses;
  st.counters["implicit_iterations"] = w.mean_iterations_implicit;
  st.counters["worn_area"] = w.records.back().worn_area;
  st.counters["positions"] = w.frame_positions;
  st.counters["passes"] = double(w.frame_iterations);
  st.counters["directions"] = w.frame_directions;
  st.counters["pad_depth"] = w.pad.max_depth;
  st.counters["specimen_depth"] = w.specimen.max_depth;
}

const bool registered = [] {
  benchmark::RegisterBenchmark("long_run", BM_long_run)
      ->Arg(1024)
      ->Arg(4096)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1)
      ->Repetitions(3);
  benchmark::RegisterBenchmark("gross_slip_example/frames", BM_gross_slip_example, true, false)
      ->Arg(256)
      ->Arg(512)
      ->Arg(1024)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1)
      ->Repetitions(3);
  benchmark::RegisterBenchmark("gross_slip_example/frames_dissimilar", BM_gross_slip_example, true, true)
      ->Arg(256)
      ->Arg(512)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1)
      ->Repetitions(3);
  benchmark::RegisterBenchmark("gross_slip_example/pad_only", BM_gross_slip_example, false, false)
      ->Arg(1024)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1)
      ->Repetitions(3);
  for (double tol : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4})
    benchmark::RegisterBenchmark(fmt::format("tolerance/{:.0e}", tol).c_str(), BM_honest, tol)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
  for (double tol : {1e-1, 3e-2, 1e-2, 5e-3, 3e-3, 1e-3, 1e-4})
    benchmark::RegisterBenchmark(fmt::format("implicit/tol:{:.0e}", tol).c_str(), BM_stepper, "implicit", tol)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  for (double tol : {1e-2, 1e-3, 1e-4})
    benchmark::RegisterBenchmark(fmt::format("explicit/tol:{:.0e}", tol).c_str(), BM_stepper, "explicit", tol)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
  benchmark::RegisterBenchmark("cycle_by_cycle", BM_stepper, "cycle_by_cycle", 0.0)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  benchmark::RegisterBenchmark("budget/implicit", BM_budget)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
  return true;
}();

}  // namespace
