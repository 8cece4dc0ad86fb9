// Wear under loads other than one in-phase cycle of constant P, and between dissimilar bodies
// (engine/wear_contacts.hpp, IncrementalContactResponse): the wear rate from the energy density per cycle,
// s = e / (f p_ref), which for an in-phase cycle under a constant P is the slip travelled again.
//
// The public Hertz case (PHYSICS.md): R = 10 mm, E = 200 GPa, ν = 0.3, P = 100 kN/m, f = 0.5, Q/fP = 0.5; Archard
// k = 1e-12 1/Pa; 256 cells on a window of ±0.2 mm given (the same grid for every run compared); 1e3 cycles.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr double kP = 1e5, kF = test::kHertzF, kQ = 0.5 * kF * kP, kCycles = 1e3;

Scene force_wear(TangentialRoute route = TangentialRoute::incremental) {
  Scene s = test::hertz_wear(kP, 0.0, kCycles, 256, "archard", 1e-12);
  s.Q_ratio.reset();
  s.Q_amplitude = kQ;
  s.window = std::pair{-0.2e-3, 0.2e-3};
  s.tangential->route = route;
  s.wear->record = {10, 100, kCycles};
  return s;
}

// The same cycle as a load history [t, P, Q, σ]: +Q → −Q → +Q at P.
Scene history_wear(std::vector<std::array<double, 4>> history) {
  Scene s = force_wear(TangentialRoute::automatic);
  s.Q_amplitude.reset();
  s.history = std::move(history);
  return s;
}

struct Run {
  Model model;
  NormalResult normal;
  CycleStage cycle;
  WearStage wear;
};

Run run(const Scene& s) {
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  CycleStage c = solve_cycle(s, m, n);
  WearStage w = run_wear(s, m, n, c, {});
  return {std::move(m), std::move(n), std::move(c), std::move(w)};
}

// f h Σ p s of a record: the energy per cycle the wear rate stands for (J/m).
double record_energy(const Run& r, const WearRecord& rec) {
  double e = 0.0;
  for (std::size_t i = 0; i < rec.p.size(); ++i) e += kF * rec.p[i] * rec.s[i] * r.model.grid.h();
  return e;
}

}  // namespace

// The in-phase cycle as a history has the same increments as the amplitude's (a quarter cycle of first loading,
// half a cycle each way), so the cycles agree to the solver's tolerance and s = e/(f p) is the slip travelled to
// round-off: the runs agree to the stepper's (tolerance 1e-3 per step; kSame = 2e-3 over the run, measured 0 to
// round-off).
TEST_CASE("an in-phase load history under a constant P wears as force control at its amplitude") {
  constexpr double kSame = 2e-3;
  const Run f = run(force_wear());
  const Run h = run(history_wear({{0.0, kP, kQ, 0.0}, {0.5, kP, -kQ, 0.0}, {1.0, kP, kQ, 0.0}}));
  REQUIRE(h.wear.route == "incremental");
  REQUIRE(f.wear.records.size() == h.wear.records.size());
  REQUIRE(h.model.grid.n == f.model.grid.n);
  for (std::size_t k = 0; k < f.wear.records.size(); ++k) {
    const WearRecord &rf = f.wear.records[k], &rh = h.wear.records[k];
    MESSAGE(fmt::format("N = {:g}: worn area {:.6e} (history) vs {:.6e} m² (force), {:+.3e}; max depth {:+.3e}",
                        rh.cycles, rh.worn_area, rf.worn_area, rh.worn_area / std::max(rf.worn_area, 1e-300) - 1.0,
                        rh.max_depth / std::max(rf.max_depth, 1e-300) - 1.0));
    if (k == 0) continue;
    CHECK(rh.worn_area == test::rel(rf.worn_area, kSame));
    CHECK(rh.max_depth == test::rel(rf.max_depth, kSame));
  }
  // The slip handed to the stepper on the unworn contact: the slip travelled, to round-off.
  const WearRecord &rf = f.wear.records.front(), &rh = h.wear.records.front();
  double s_max = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < rf.s.size(); ++i)
    s_max = std::max(s_max, rf.s[i]), diff = std::max(diff, std::abs(rf.s[i] - rh.s[i]));
  MESSAGE(fmt::format("unworn slip: max |s_history − s_force| = {:.3e} of s_max {:.3e} m", diff, s_max));
  CHECK(diff <= 1e-6 * s_max);
}

// P varying through the cycle (±20 % between the extremes of Q): the contact wears, and the energy the first
// record's rate stands for, f h Σ p_ref s (p_ref under the history's largest P, whose contact covers every cell that
// slips), is the cycle stage's energy per cycle to round-off.
TEST_CASE("a load history with varying P wears at the energy of its cycle") {
  const Run h = run(history_wear(
      {{0.0, kP, kQ, 0.0}, {0.25, 1.2 * kP, 0.0, 0.0}, {0.5, kP, -kQ, 0.0}, {0.75, 0.8 * kP, 0.0, 0.0},
       {1.0, kP, kQ, 0.0}}));
  const WearRecord& last = h.wear.records.back();
  CHECK(last.worn_area > 0.0);
  CHECK(last.max_depth > 0.0);
  CHECK(!h.wear.asymptote.unavailable.empty());
  const CycleResult& c = h.cycle.result;
  REQUIRE(!c.energy_density.empty());
  double total = 0.0;
  for (int i = 0; i < h.model.grid.n; ++i) total += c.energy_density[i] * h.model.grid.h();
  const double e0 = record_energy(h, h.wear.records.front());
  MESSAGE(fmt::format("energy per cycle: cycle stage {:.6e} J/m (dissipated {:.6e}); the wear rate's {:.6e}; worn "
                      "area after {:g} cycles {:.4e} m²",
                      total, c.dissipated_energy, e0, last.cycles, last.worn_area));
  CHECK(e0 == test::rel(total, 1e-9));
  CHECK(e0 == test::rel(c.dissipated_energy, 1e-9));
}

// Dissimilar bodies whose moduli differ by 0.1 % (β ≈ 1e-4): the coupled route wears as the similar pair (both on
// the incremental route), kContinuity = 0.5 % in worn area and max depth.
TEST_CASE("wear between dissimilar bodies tends to the similar pair's as the moduli meet") {
  constexpr double kContinuity = 5e-3;
  const Run similar = run(force_wear());
  Scene s = force_wear(TangentialRoute::automatic);
  s.pad.E *= 1.001;
  s.similar = false;
  const Run dissimilar = run(s);
  REQUIRE(std::abs(dissimilar.model.pair.beta()) > 1e-12);
  REQUIRE(dissimilar.wear.route == "incremental");
  const WearRecord &a = similar.wear.records.back(), &b = dissimilar.wear.records.back();
  MESSAGE(fmt::format("beta = {:.3e}: worn area {:.6e} (dissimilar) vs {:.6e} m² (similar), {:+.3e}; max depth {:+.3e}",
                      dissimilar.model.pair.beta(), b.worn_area, a.worn_area, b.worn_area / a.worn_area - 1.0,
                      b.max_depth / a.max_depth - 1.0));
  CHECK(b.worn_area == test::rel(a.worn_area, kContinuity));
  CHECK(b.max_depth == test::rel(a.max_depth, kContinuity));
}

// And at the wear limit, where the worn area depends on where the stick zone's ends fall within their cells (1 % for
// a third of a cell on 1024 cells): the default window of nearly similar bodies puts cell boundaries at the similar
// pair's stick zone, as the similar run's does at its own, so the two limits meet (with the cells where they fell the
// dissimilar run's was 1.5 % off at β = 1.4e-7). Q/fP = 0.5 and 0.95, 10^7 cycles, on the default windows.
TEST_CASE("wear between nearly similar bodies reaches the similar pair's limit on the default window") {
  constexpr double kContinuity = 5e-3;
  for (const double ratio : {0.5, 0.95}) {
    CAPTURE(ratio);
    const Scene similar = test::hertz_wear(kP, ratio, 1e7, 1024);
    Scene nearly = similar;
    nearly.specimen.E *= 1.001;
    nearly.similar = false;
    const RunResult a = Simulation(similar).run(), b = Simulation(nearly).run();
    REQUIRE(std::abs(Model(make_model(nearly)).pair.beta()) > 1e-12);
    const double wa = a.wear->records.back().worn_area, wb = b.wear->records.back().worn_area;
    MESSAGE(fmt::format("Q/fP = {}: worn area {:.6e} (moduli 0.1 % apart) vs {:.6e} m² (similar), {:+.2e}", ratio, wb,
                        wa, wb / wa - 1.0));
    CHECK(wb == test::rel(wa, kContinuity));
  }
}

// load.blocks: two blocks of the same load, 300 and 700 cycles, wear as one of 1000 (the second block restarts the
// stepper from the first's profile, so they agree to its tolerance: kSame = 2e-3). A second block at a smaller Q
// wears more slowly than the same block at the first's Q, and every record names its block.
TEST_CASE("load blocks of the same load wear as one block of their total") {
  constexpr double kSame = 2e-3;
  Scene one = force_wear();
  one.blocks = {LoadBlock{kQ, std::nullopt, std::nullopt, {}, kCycles}};
  Scene two = one;
  two.blocks = {LoadBlock{kQ, std::nullopt, std::nullopt, {}, 300}, LoadBlock{kQ, std::nullopt, std::nullopt, {}, 700}};
  const Run a = run(one), b = run(two);
  const WearRecord &ra = a.wear.records.back(), &rb = b.wear.records.back();
  MESSAGE(fmt::format("after {:g} cycles: worn area {:.6e} (two blocks) vs {:.6e} m² (one), {:+.3e}; max depth "
                      "{:+.3e}",
                      rb.cycles, rb.worn_area, ra.worn_area, rb.worn_area / ra.worn_area - 1.0,
                      rb.max_depth / ra.max_depth - 1.0));
  CHECK(rb.cycles == kCycles);
  CHECK(rb.worn_area == test::rel(ra.worn_area, kSame));
  CHECK(rb.max_depth == test::rel(ra.max_depth, kSame));
  CHECK(b.wear.records.front().block == 0);
  CHECK(rb.block == 1);
  for (const WearRecord& r : b.wear.records) CHECK(r.block == (r.cycles < 300 || (r.cycles == 300 && r.block == 0) ? 0 : 1));
  // The same against one block of 1000 cycles without load.blocks (the plain run): the blocks' route is the
  // incremental one, as force_wear's.
  Scene plain = force_wear();
  const Run c = run(plain);
  CHECK(ra.worn_area == test::rel(c.wear.records.back().worn_area, kSame));

  // A lighter second block wears less than the same second block at the first's Q.
  Scene lighter = two;
  lighter.blocks[1].Q_amplitude = 0.5 * kQ;
  const Run d = run(lighter);
  MESSAGE(fmt::format("second block at Q/2: worn area {:.6e} m²", d.wear.records.back().worn_area));
  CHECK(d.wear.records.back().worn_area < rb.worn_area);
  CHECK(d.wear.records.back().worn_area > 0.0);
}
