// Wear under displacement control (load.control "displacement") on the worn profile (engine/wear_contacts.hpp,
// IncrementalContactResponse: below the stick limit the analogy's cycle at the Q that reaches δ, checked against the
// marched one in test_wear_displacement_analogy.cpp; beyond it the marched cycle). Below the stick limit it wears as
// force control at the same
// initial Q_max and then drifts as the worn contact's tangential compliance changes Q_max; beyond it (gross slip)
// the whole contact wears, there is no stick zone, and the wear rate is Archard's k ∫ p s dx with s the slip
// travelled per cycle, 4 × the sliding amplitude plus the elastic part. The wear balance holds on both, and a run
// stopped at a checkpoint and resumed ends as the uninterrupted one.
//
// The public Hertz case (PHYSICS.md): R = 10 mm, E = 200 GPa, ν = 0.3, P = 100 kN/m, f = 0.5, a = 0.10764 mm; the
// datum 10 half-widths below the centre. δ = 0.5 µm gives Q/fP = 0.449 (partial slip); the stick limit is δ_s =
// 1.2195 µm (test_cycle_displacement.cpp), so δ = 2 and 3 µm slide 0.78 and 1.78 µm each way beyond it.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include "common/error.hpp"
#include "engine/checkpoint.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr double kP = 1e5, kF = test::kHertzF, kK = 1e-12;

// The Hertz case under displacement control ±delta, worn by Archard's k for `cycles`, on a given window (the same
// grid for every run compared), recorded at `record` (cycles).
Scene displacement_wear(double delta, double cycles, std::vector<double> record, double k = kK,
                        double half_window = 0.2e-3, int cells = 256) {
  Scene s = test::hertz_wear(kP, 0.0, cycles, cells, "archard", k);
  s.Q_ratio.reset();
  s.control = LoadControl::displacement;
  s.delta = delta;
  s.window = std::pair{-half_window, half_window};
  s.wear->record = std::move(record);
  return s;
}

// The same profile and grid under force control at Q_max (N/m).
Scene force_wear(double Q_max, double cycles, std::vector<double> record, double half_window = 0.2e-3,
                 int cells = 256) {
  Scene s = test::hertz_wear(kP, 0.0, cycles, cells, "archard", kK);
  s.Q_ratio.reset();
  s.Q_amplitude = Q_max;
  s.window = std::pair{-half_window, half_window};
  s.wear->record = std::move(record);
  return s;
}

struct Run {
  Model model;
  NormalResult normal;
  WearStage wear;
};

Run run(const Scene& s, const WearControl& control = {}) {
  Model m = make_model(s);
  NormalResult n = solve_normal(s, m);
  WearStage w = run_wear(s, m, n, solve_cycle(s, m, n), control);
  return {std::move(m), std::move(n), std::move(w)};
}

// c ∫ p s dx of a record (m²/cycle): the rate of the worn area.
double area_rate(const WearStage& w, const WearRecord& r, double h) {
  double rate = 0.0;
  for (std::size_t i = 0; i < r.p.size(); ++i) rate += w.rate_coefficient * r.p[i] * r.s[i] * h;
  return rate;
}

std::vector<double> evenly(double step, int count) {
  std::vector<double> t;
  for (int i = 1; i <= count; ++i) t.push_back(step * i);
  return t;
}

}  // namespace

// (a) Below the stick limit, δ = 0.5 µm, 256 cells, k = 1e-12 1/Pa, 1e4 cycles. The two runs part because the worn contact is more compliant tangentially: wear takes the pressure off
// the slip zones and puts it on the stick zone, so the shear is carried by a narrower region, whose compliance
// (A/π) ln[(d + √(d² + c²))/c] + … (reference_datum.hpp) is larger: the same δ is then reached with a smaller Q. The
// displacement run's Q_max falls (measured 0.09 % at 100 cycles, 0.87 % at 1e3, 4.2 % at 1e4) while the force run
// keeps its Q. A smaller Q slips less (the energy per cycle grows faster than Q: Mindlin's E ∝ Q³ for small Q), so the
// displacement run wears less, by about d ln W/d ln Q ≈ 1.7 times its Q drift while both are far from their limits
// (measured: worn area −0.16 % at 100 cycles, −1.4 % at 1e3, −4.3 % at 3e3), and the gap closes again once the force
// run has reached its asymptote (−0.44 % at 1e4, where the force run is at 1.02 of it on this grid). Tolerances: kEarly = 2e-3 at 100 cycles (the drift's 0.16 % there); over
// the whole run, 0 ≤ shortfall ≤ 2 × drift, and the worn areas within kRun = 5 %.
TEST_CASE("displacement control below the stick limit wears as force control at its initial Q_max, then less as "
          "Q_max falls") {
  constexpr double kEarly = 2e-3, kRun = 5e-2;
  const std::vector<double> records{100, 300, 1000, 3000, 10000};
  const Run d = run(displacement_wear(0.5e-6, 1e4, records));
  REQUIRE(d.wear.route.rfind("analogy (displacement control", 0) == 0);  // similar bodies in partial slip
  const double Q0 = d.wear.records.front().Q_max;
  REQUIRE(Q0 > 0.3 * kF * kP);
  REQUIRE(Q0 < 0.6 * kF * kP);
  // The limit over the first cycle's stick zone, under the Q that δ gives on it (test_wear_displacement_limit.cpp).
  CHECK(d.wear.asymptote.unavailable.empty());
  REQUIRE(d.wear.asymptote.Q_max);
  CHECK(*d.wear.asymptote.Q_max < Q0);
  const Run f = run(force_wear(Q0, 1e4, records));
  REQUIRE(f.wear.route == "analogy");
  REQUIRE(d.model.grid.n == f.model.grid.n);
  REQUIRE(d.model.grid.x_min == f.model.grid.x_min);
  REQUIRE(d.wear.records.size() == f.wear.records.size());
  const double h = d.model.grid.h();

  // The unworn contact: the same stick zone (force control at that Q), to a tenth of a cell.
  REQUIRE(d.wear.records.front().stick_zone);
  REQUIRE(f.wear.records.front().stick_zone);
  CHECK(std::abs(d.wear.records.front().stick_zone->second - f.wear.records.front().stick_zone->second) < 0.1 * h);
  for (std::size_t k = 1; k < d.wear.records.size(); ++k) {
    const WearRecord& rd = d.wear.records[k];
    const WearRecord& rf = f.wear.records[k];
    REQUIRE(rd.stick_zone);
    MESSAGE(fmt::format("N = {:g}: worn area {:.6e} (displacement) vs {:.6e} m² (force), {:+.3e}; max depth "
                        "{:+.3e}; Q_max/Q0 - 1 = {:+.3e}; stick zone right end {:.6e} vs {:.6e} m; force run at "
                        "{:.3f} of its asymptote",
                        rd.cycles, rd.worn_area, rf.worn_area, rd.worn_area / rf.worn_area - 1.0,
                        rd.max_depth / rf.max_depth - 1.0, rd.Q_max / Q0 - 1.0, rd.stick_zone->second,
                        rf.stick_zone->second, rf.fraction));
    const double drift = 1.0 - rd.Q_max / Q0;  // how far Q_max has fallen
    CHECK(drift >= -1e-9);                      // it never rises
    CHECK(rd.worn_area <= rf.worn_area * (1.0 + 1e-9));
    if (rd.cycles <= 100) {
      CHECK(rd.worn_area == test::rel(rf.worn_area, kEarly));
      CHECK(rd.max_depth == test::rel(rf.max_depth, kEarly));
    }
    CHECK(rd.worn_area == test::rel(rf.worn_area, kRun));
    // The shortfall in wear is of the order of the fall of Q_max, and no larger than twice it.
    const double shortfall = 1.0 - rd.worn_area / rf.worn_area;
    CHECK(shortfall < 2.0 * drift);
    // The stick zone moves (it stands still under force control), but by little: within two cells here.
    CHECK(std::abs(rd.stick_zone->second - d.wear.records.front().stick_zone->second) < 2.0 * h);
  }
  const WearRecord& last = d.wear.records.back();
  CHECK(1.0 - last.Q_max / Q0 > 1e-3);  // Q_max has fallen measurably: the contact compliance changed
  CHECK(std::abs(f.wear.records.back().stick_zone->second - f.wear.records.front().stick_zone->second) < h);
}

// (b) Gross slip: δ beyond the stick limit. The slip travelled per cycle is 4 × the sliding amplitude everywhere
// plus the elastic slip of the partial-slip phases; the energy dissipated per cycle is f ∫ p s dx (every slipping
// cell at |q| = f p), so c ∫ p s dx = c E / f; and one more micrometre of δ adds 4 µm of sliding per cycle at every
// point, so the rate grows by exactly c P · 4 µm: Archard's k P s_slide for uniform sliding (to the cycle's 1e-6,
// test_cycle_displacement.cpp).
TEST_CASE("gross slip: no stick zone, the whole contact wears, and the rate is Archard's k P s for the sliding") {
  constexpr double kK_gross = 2e-15;
  auto gross = [&](double delta) {
    return run(displacement_wear(delta, 2e5, evenly(2e4, 10), kK_gross, 0.3e-3));
  };
  const Run r2 = gross(2e-6), r3 = gross(3e-6);
  const double h = r2.model.grid.h();
  for (const Run* r : {&r2, &r3}) {
    const WearStage& w = r->wear;
    REQUIRE(w.route == "incremental");
    for (std::size_t k = 0; k < w.records.size(); ++k) {
      const WearRecord& rec = w.records[k];
      CHECK_FALSE(rec.stick_zone);
      CHECK(rec.Q_max == test::rel(kF * kP, 1e-12));
      if (k > 0) {
        CHECK(rec.worn_area > w.records[k - 1].worn_area);
        CHECK(rec.max_depth > w.records[k - 1].max_depth);
        CHECK(rec.contact.second >= w.records[k - 1].contact.second);
        CHECK(rec.contact.first <= w.records[k - 1].contact.first);
      }
    }
    // The whole initial contact has worn by the first record.
    const WearRecord& r0 = w.records.front();
    const WearRecord& r1 = w.records[1];
    int unworn = 0, contact = 0;
    for (std::size_t i = 0; i < r0.p.size(); ++i)
      if (r0.p[i] > 0.0) ++contact, unworn += !(r1.w[i] > 0.0);
    CHECK(contact > 80);
    CHECK(unworn == 0);
    // The contact flattens: the peak pressure falls and the contact widens.
    CHECK(w.records.back().contact.second > 1.2 * r0.contact.second);
  }
  // c ∫ p s dx = c E / f with E the dissipated energy of the cycle stage on the unworn contact.
  for (const Run* r : {&r2, &r3}) {
    Scene s = displacement_wear(r == &r2 ? 2e-6 : 3e-6, 2e5, evenly(2e4, 10), kK_gross, 0.3e-3);
    const CycleStage cycle = solve_cycle(s, r->model, r->normal);
    REQUIRE(cycle.result.regime == Regime::gross_slip);
    const double rate = area_rate(r->wear, r->wear.records.front(), h);
    MESSAGE(fmt::format("delta = {} µm: c ∫ p s dx = {:.10e} m²/cycle, c E/f = {:.10e}; sliding amplitude {:.6e} "
                        "m, uniform sliding alone c P 4 A_s = {:.10e} (elastic share {:.4f})",
                        r == &r2 ? 2 : 3, rate, kK_gross * cycle.result.dissipated_energy / kF,
                        cycle.result.sliding_amplitude, kK_gross * kP * 4 * cycle.result.sliding_amplitude,
                        rate / (kK_gross * kP * 4 * cycle.result.sliding_amplitude) - 1.0));
    CHECK(rate == test::rel(kK_gross * cycle.result.dissipated_energy / kF, 1e-9));
    CHECK(rate > kK_gross * kP * 4 * cycle.result.sliding_amplitude);
  }
  const double extra = area_rate(r3.wear, r3.wear.records.front(), h) - area_rate(r2.wear, r2.wear.records.front(), h);
  MESSAGE(fmt::format("rate(3 µm) - rate(2 µm) = {:.10e} m²/cycle; k P 4 (1 µm) = {:.10e}", extra,
                      kK_gross * kP * 4e-6));
  CHECK(extra == test::rel(kK_gross * kP * 4e-6, 1e-6));
}

// (c) The wear balance, W(N) = Σ c ∫ p s dx ΔN. At the start, as in test_wear.cpp: W(N)/(N c ∫ p s dx) − 1 is the
// first-order change of the rate as the profile wears, so it vanishes linearly in N. Over a whole gross-slip run the
// rate changes slowly (the contact flattens but ∫ p s dx stays near P s): the trapezoidal sum of the recorded rates
// over ten even records gives the worn area to the rule's error (measured at most 1.8e-4 over 2e5 cycles at
// δ = 2 µm): kTrapezoid = 5e-4.
TEST_CASE("the wear balance under displacement control, in partial and in gross slip") {
  auto deviation = [](double delta, double cycles, double k, double half_window) {
    Scene s = displacement_wear(delta, cycles, {cycles}, k, half_window);
    const Run r = run(s);
    const double rate = area_rate(r.wear, r.wear.records.front(), r.model.grid.h());
    return r.wear.records.back().worn_area / (cycles * rate) - 1.0;
  };
  for (const auto& [delta, k, window, n1] : {std::tuple{0.5e-6, kK, 0.2e-3, 1.0}, std::tuple{2e-6, 2e-15, 0.3e-3, 100.0}}) {
    CAPTURE(delta);
    const double d1 = deviation(delta, n1, k, window), d8 = deviation(delta, 8 * n1, k, window);
    MESSAGE(fmt::format("delta = {:g} m: W/(N c ∫ p s dx) - 1 = {:.4e} at N = {:g}, {:.4e} at N = {:g}", delta, d1,
                        n1, d8, 8 * n1));
    CHECK(std::abs(d1) < 2e-4);
    CHECK(d8 / d1 == test::rel(8.0, 0.1));  // first order
  }
  constexpr double kTrapezoid = 5e-4;
  const Run r = run(displacement_wear(2e-6, 2e5, evenly(2e4, 10), 2e-15, 0.3e-3));
  const double h = r.model.grid.h();
  double balance = 0.0;
  for (std::size_t k = 1; k < r.wear.records.size(); ++k) {
    const WearRecord& a = r.wear.records[k - 1];
    const WearRecord& b = r.wear.records[k];
    balance += 0.5 * (area_rate(r.wear, a, h) + area_rate(r.wear, b, h)) * (b.cycles - a.cycles);
    MESSAGE(fmt::format("N = {:g}: worn area {:.8e} m², Σ c ∫ p s dx ΔN {:.8e} ({:+.3e})", b.cycles, b.worn_area,
                        balance, b.worn_area / balance - 1.0));
    CHECK(b.worn_area == test::rel(balance, kTrapezoid));
  }
}

// (d) A displacement-controlled wear run stopped at a step boundary and resumed from its checkpoint takes the
// uninterrupted run's steps: the same records to 1e-10 (the warm starts of the normal and contact-implicit solves
// travel in the checkpoint; the incremental march starts from rest each time).
TEST_CASE("a displacement-controlled wear run resumed from a checkpoint ends as the uninterrupted one") {
  for (const double delta : {0.5e-6, 2e-6}) {
    CAPTURE(delta);
    const Scene s = delta < 1e-6 ? displacement_wear(delta, 1e4, {}, kK) :
                                   displacement_wear(delta, 1e5, {}, 2e-15, 0.3e-3);
    Scene scene = s;
    scene.wear->record_count = 6;
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        fmt::format("fretwear-wear-displacement-{}-{}.checkpoint", ::getpid(), std::random_device{}());
    WearControl whole_control;
    whole_control.scene_hash = scene_hash(scene);
    const Run whole = run(scene, whole_control);

    WearControl stop;
    stop.checkpoint = path;
    stop.checkpoint_interval = 0.0;
    stop.scene_hash = scene_hash(scene);
    int boundaries = 0;
    stop.stop_requested = [&boundaries](const WearProgress&) { return ++boundaries == 12; };
    const Run stopped = run(scene, stop);
    REQUIRE(stopped.wear.interrupted);
    REQUIRE(std::filesystem::exists(path));

    WearControl resume;
    resume.scene_hash = scene_hash(scene);
    resume.resume = read_checkpoint(path, scene);
    REQUIRE(resume.resume);
    const Run resumed = run(scene, resume);
    std::filesystem::remove(path);
    REQUIRE(resumed.wear.resumed_from);
    MESSAGE(fmt::format("stopped at cycle {:g} after {} boundaries; {} steps uninterrupted, {} resumed",
                        *resumed.wear.resumed_from, boundaries, whole.wear.steps, resumed.wear.steps));
    CHECK(*resumed.wear.resumed_from > 0.0);
    CHECK(resumed.wear.steps == whole.wear.steps);
    REQUIRE(resumed.wear.records.size() == whole.wear.records.size());
    auto same = [](double a, double b) { return b == 0.0 ? a == 0.0 : a == test::rel(b, 1e-10); };
    for (std::size_t k = 0; k < whole.wear.records.size(); ++k) {
      const WearRecord& a = resumed.wear.records[k];
      const WearRecord& b = whole.wear.records[k];
      CAPTURE(k);
      CHECK(a.cycles == b.cycles);
      CHECK(same(a.worn_area, b.worn_area));
      CHECK(same(a.max_depth, b.max_depth));
      CHECK(same(a.Q_max, b.Q_max));
      CHECK(same(a.p_max, b.p_max));
      CHECK(a.stick_zone.has_value() == b.stick_zone.has_value());
      if (a.stick_zone && b.stick_zone) CHECK(same(a.stick_zone->second, b.stick_zone->second));
      int differ = 0;
      for (std::size_t i = 0; i < b.w.size(); ++i)
        differ += !same(a.w[i], b.w[i]) || !same(a.p[i], b.p[i]) || !same(a.s[i], b.s[i]);
      CHECK(differ == 0);
    }
  }
}

TEST_CASE("wear refusal: force control in gross slip names displacement control") {
  Scene s = test::hertz_wear(kP, 1.2, 1e3, 256);
  const Model m = make_model(test::hertz_wear(kP, 0.5, 1e3, 256));
  const NormalResult n = solve_normal(s, m);
  try {
    run_wear(s, m, n, solve_cycle(s, m, n));
    FAIL("force control in gross slip was not refused");
  } catch (const UnsupportedError& e) {
    CHECK(std::string(e.what()).find("load.control \"displacement\"") != std::string::npos);
  }
}
