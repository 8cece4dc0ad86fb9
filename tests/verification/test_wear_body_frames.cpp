// Each body's wear in its own frame in gross slip (engine/body_frames.hpp), on
// examples/gross_slip_displacement_wear.json
// shortened to 5000 cycles: a 6 mm cylinder on a flat, P = 18.5 kN/m, f = 0.9, δ = ±25 µm (the bodies slide
// U = 24.3 µm each way), Archard k = 5e-14 1/Pa shared equally. The pad's points stay under the contact; the
// specimen's meet the whole stroke, so its scar is wider by up to 2U and shallower, and the pad's deeper.
#include <algorithm>
#include <fstream>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "engine/body_frames.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"

using namespace fretwear;

namespace {

constexpr double kCycles = 5000;
// At 4096 cells the check runs 1000 cycles, against a reference of as many: the stepper takes some 190 steps there
// too (most of them while the contact spreads, which is where a step unstable on a fine grid alternates), at 0.4 of
// the cost of 5000 (measured: each body's depth 1.8e-4 and 1.2e-3 from the reference, the areas 1.6e-5).
constexpr double kFineCycles = 1000;
// The reference: every cycle worn at every position, on 256 cells (the explicit stability limit there is 13 cycles).
constexpr int kReferenceCells = 256;
// Each body's depth and area within half a percent of the reference: the stepper's tolerance (1e-3 of the depth per
// step) over some two hundred steps; on the reference's own grid the step agrees to about 1e-5, and the grids
// agree to 2e-4 (the rest is the positions' and the cells' discretisation, the same in both).
constexpr double kAgreement = 5e-3;
// Alternation inside the contact, as tests/verification/test_wear_gross_slip.cpp measures it: about 1 for open
// alternate cells. The discrete positions leave a ripple of their own, at the positions' spacing, in the every-cycle
// solution too (9 positions, 5000 cycles: 0.021 at 512 cells, 0.015 at 1024, the step the same to 1e-3; 17
// positions, the example's 18 000 cycles: 0.014 / 0.016 / 0.025 / 0.026 at 512 to 4096 cells); a stepper that
// lagged the coupling between positions opened every other cell. And the newest edge cells: each of the first
// kEdgeCells loaded cells within kEdgeAgreement of the every-cycle solution's on the same grid (a step that left the
// coupling between positions lagged opened every other one of them at 1024 cells).
constexpr double kAlternationTolerance = 0.05;
constexpr int kInteriorMargin = 16;  // the alternation is measured this many cells inside the contact's ends
constexpr int kEdgeCells = 8;
constexpr double kEdgeAgreement = 0.02;
// The two bodies' areas stand in the ratio of their coefficients (Archard: each wears c_body ∫ p s over the same
// positions; the reading of the specimen and its deposit are transposes, so nothing is lost): to round-off cycle by
// cycle, and up to the step's rule that wear never decreases, which clips the extrapolation cell by cell (7e-6
// measured at 1024 cells), with the implicit stepper.
constexpr double kAreaRatioExact = 1e-12;
constexpr double kAreaRatioClipped = 1e-4;

Scene example(int cells, WearStepper stepper, double cycles = kCycles) {
  Scene s = load_scene(std::string(FRETWEAR_SOURCE_DIR) + "/examples/gross_slip_displacement_wear.json");
  s.cells = cells;
  s.wear->cycles = cycles;
  s.wear->stepper = stepper;
  s.wear->record = {cycles};
  return s;
}

struct Run {
  WearStage stage;
  double h = 0.0, U = 0.0;
};

Run run(const Scene& s) {
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const CycleStage c = solve_cycle(s, m, n);
  return {run_wear(s, m, n, c, {}), m.grid.h(), c.result.sliding_amplitude};
}

std::pair<int, int> loaded(const std::vector<double>& p) {
  int first = -1, last = -1;
  for (int i = 0; i < int(p.size()); ++i)
    if (p[i] > 0.0) last = i, first = first < 0 ? i : first;
  return {first, last};
}

double relative(double a, double b) { return std::abs(a / b - 1.0); }

}  // namespace

TEST_CASE("body frames: the stroke's positions are symmetric, weigh one, and span it") {
  const double h = 1e-6;
  const FramePositions few = frame_positions(3e-6, h);  // 3 cells each way: 7 positions, one a cell
  REQUIRE(few.shift.size() == 7);
  for (std::size_t k = 0; k < few.shift.size(); ++k) CHECK(few.shift[k] == doctest::Approx(double(k) - 3.0));
  CHECK(frame_positions(0.4e-6, h).shift.size() == 3);  // a stroke under a cell: its ends and the middle
  const FramePositions many = frame_positions(24.3e-6, h);  // capped: 2 kFrameIntervals + 1, the stroke's ends included
  REQUIRE(many.shift.size() == std::size_t(2 * kFrameIntervals + 1));
  CHECK(many.shift.front() == doctest::Approx(-24.3));
  CHECK(many.shift.back() == doctest::Approx(24.3));
  for (const FramePositions* f : {&few, &many}) {
    CHECK(std::accumulate(f->weight.begin(), f->weight.end(), 0.0) == doctest::Approx(1.0).epsilon(1e-14));
    // The shares tile the stroke, each position inside its own, and weigh its length.
    const double U = f->share.back().second;
    CHECK(f->share.front().first == doctest::Approx(-U));
    for (std::size_t k = 0; k < f->shift.size(); ++k) {
      CHECK(f->share[k].first <= f->shift[k]);
      CHECK(f->shift[k] <= f->share[k].second);
      CHECK(f->weight[k] == doctest::Approx((f->share[k].second - f->share[k].first) / (2.0 * U)));
      if (k > 0) CHECK(f->share[k].first == doctest::Approx(f->share[k - 1].second));
    }
    for (std::size_t k = 0; k < f->shift.size(); ++k) {
      CHECK(f->shift[k] == doctest::Approx(-f->shift[f->shift.size() - 1 - k]));
      CHECK(f->weight[k] == doctest::Approx(f->weight[f->shift.size() - 1 - k]));
    }
  }
}

namespace {

// The reference: every cycle worn at every position on kReferenceCells, for kCycles or kFineCycles.
const Run& reference(double cycles = kCycles) {
  REQUIRE((cycles == kCycles || cycles == kFineCycles));
  if (cycles == kFineCycles) {
    static const Run fine = run(example(kReferenceCells, WearStepper::cycle_by_cycle, kFineCycles));
    return fine;
  }
  static const Run ref = run(example(kReferenceCells, WearStepper::cycle_by_cycle));
  return ref;
}

// The implicit step on `cells` against the reference: each body's depth, area and ends, and no alternation.
void check_against_reference(int cells, double cycles = kCycles) {
  const Run& ref = reference(cycles);
  const WearStage::Scar& pad_ref = ref.stage.pad;
  const WearStage::Scar& spec_ref = ref.stage.specimen;
  CAPTURE(cells);
  const Run r = run(example(cells, WearStepper::implicit, cycles));
  REQUIRE(r.stage.frame_positions > 0);
  CHECK(relative(r.stage.pad.max_depth, pad_ref.max_depth) < kAgreement);
  CHECK(relative(r.stage.specimen.max_depth, spec_ref.max_depth) < kAgreement);
  CHECK(relative(r.stage.pad.worn_area, pad_ref.worn_area) < kAgreement);
  CHECK(relative(r.stage.specimen.worn_area, spec_ref.worn_area) < kAgreement);
  CHECK(relative(r.stage.pad.worn_area, r.stage.specimen.worn_area) < kAreaRatioClipped);
  // The scars' ends within a reference cell of the reference's.
  CHECK(std::abs(r.stage.specimen.extent.first - spec_ref.extent.first) <= ref.h);
  CHECK(std::abs(r.stage.pad.extent.first - pad_ref.extent.first) <= ref.h);

  const WearRecord& last = r.stage.records.back();
  REQUIRE(last.w_pad.size() == std::size_t(cells));
  const auto [first, end] = loaded(last.p);
  int open = 0;
  for (int i = first; i <= end; ++i) open += last.p[i] > 0.0 ? 0 : 1;
  CHECK(open == 0);
  const double p_mean = 18500.0 / (double(end - first + 1) * r.h);
  double alternation = 0.0;
  for (int i = first + kInteriorMargin; i <= end - kInteriorMargin; ++i)
    alternation = std::max(alternation, std::abs(last.p[i] - 0.5 * (last.p[i - 1] + last.p[i + 1])) / p_mean);
  CHECK(alternation < kAlternationTolerance);
}

}  // namespace

TEST_CASE("body frames: in gross slip the specimen's scar spreads over the stroke, wider and shallower than the pad's") {
  const Run& ref = reference();
  REQUIRE(ref.stage.frame_positions > 0);
  const WearStage::Scar& pad_ref = ref.stage.pad;
  const WearStage::Scar& spec_ref = ref.stage.specimen;
  // The frames matter: the specimen's scar is wider by more than one sliding amplitude and by at most two (plus a cell
  // each side for the threshold), and shallower; with one shared profile both would be the same.
  const double widening =
      (spec_ref.extent.second - spec_ref.extent.first) - (pad_ref.extent.second - pad_ref.extent.first);
  CHECK(widening > ref.U);
  CHECK(widening < 2.0 * ref.U + 2.0 * ref.h);
  CHECK(spec_ref.max_depth < 0.9 * pad_ref.max_depth);
  CHECK(relative(pad_ref.worn_area, spec_ref.worn_area) < kAreaRatioExact);
  check_against_reference(kReferenceCells);
}

TEST_CASE("body frames: each body's scar follows every cycle worn at 1024 and 2048 cells") {
  for (const int cells : {1024, 2048}) check_against_reference(cells);
}

TEST_CASE("body frames: each body's scar follows every cycle worn at 4096 cells") {
  check_against_reference(4096, kFineCycles);
}

TEST_CASE("body frames: the newest edge cells carry the every-cycle solution's pressure at the default tolerance") {
  const int cells = 512;
  const Run every = run(example(cells, WearStepper::cycle_by_cycle));
  const Run step = run(example(cells, WearStepper::implicit));
  const std::vector<double>& pe = every.stage.records.back().p;
  const std::vector<double>& ps = step.stage.records.back().p;
  const auto [first, last] = loaded(pe);
  REQUIRE(loaded(ps) == std::make_pair(first, last));
  const double p_max = *std::max_element(pe.begin(), pe.end());
  for (int k = 0; k < kEdgeCells; ++k) {
    CAPTURE(k);
    CHECK(std::abs(ps[first + k] - pe[first + k]) < kEdgeAgreement * p_max);
    CHECK(std::abs(ps[last - k] - pe[last - k]) < kEdgeAgreement * p_max);
  }
}

namespace {

// The example at 256 cells as JSON, its load replaced.
Scene with_load(const nlohmann::json& load, double cycles) {
  std::ifstream in(std::string(FRETWEAR_SOURCE_DIR) + "/examples/gross_slip_displacement_wear.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["grid"]["cells"] = 256;
  j["load"] = load;
  j["effects"]["wear"]["cycles"] = cycles;
  return parse_scene(j);
}

}  // namespace

TEST_CASE("body frames under load.blocks: a sliding block wears each body in its own frame, as its own load does") {
  // One block of the example's load is the example (5000 cycles, 256 cells) to the bit: the same steps from the
  // same state. Two blocks of it restart the stepper at 2000 cycles: within the stepper's tolerance of it.
  const nlohmann::json delta = {{"P", 18500}, {"control", "displacement"}, {"delta", 25e-6}};
  const Run plain = run(with_load(delta, 5000));
  const Run one = run(with_load({{"P", 18500}, {"blocks", {{{"delta", 25e-6}, {"cycles", 5000}}}}}, 5000));
  const Run two = run(with_load(
      {{"P", 18500}, {"blocks", {{{"delta", 25e-6}, {"cycles", 2000}}, {{"delta", 25e-6}, {"cycles", 3000}}}}}, 5000));
  REQUIRE(plain.stage.frame_positions > 0);
  CHECK(one.stage.frame_positions == plain.stage.frame_positions);
  CHECK(one.stage.pad.max_depth == plain.stage.pad.max_depth);
  CHECK(one.stage.specimen.max_depth == plain.stage.specimen.max_depth);
  CHECK(one.stage.records.back().w_specimen == plain.stage.records.back().w_specimen);
  CHECK(relative(two.stage.pad.max_depth, plain.stage.pad.max_depth) < kAgreement);
  CHECK(relative(two.stage.specimen.max_depth, plain.stage.specimen.max_depth) < kAgreement);
  CHECK(relative(two.stage.specimen.worn_area, plain.stage.specimen.worn_area) < kAgreement);
}

TEST_CASE("body frames under load.blocks: partial-slip blocks around a sliding one split their wear by pad_fraction") {
  // δ = 0.5 µm (partial slip; the stick limit is 0.68 µm) for 2000 cycles, 25 µm (gross slip) for 5000, 0.5 µm for
  // 2000, pad_fraction 0.5. The first block wears the shared profile; the sliding block starts the two profiles from it, split by pad_fraction, and
  // wears them in their own frames; the last block wears the gap's profile w_pad + w_spec and adds half its wear to
  // each. Every record from the sliding block on holds both profiles, summing to the gap's wear.
  const Run r = run(with_load({{"P", 18500},
                               {"blocks",
                                {{{"delta", 0.5e-6}, {"cycles", 2000}},
                                 {{"delta", 25e-6}, {"cycles", 5000}},
                                 {{"delta", 0.5e-6}, {"cycles", 2000}}}}},
                              9000));
  REQUIRE(r.stage.frame_positions > 0);
  const std::vector<WearRecord>& records = r.stage.records;
  const auto starts = [&](int block) {
    return std::find_if(records.begin(), records.end(), [block](const WearRecord& x) { return x.block == block; });
  };
  for (auto k = records.begin(); k != records.end(); ++k) {
    CAPTURE(k->cycles);
    CHECK(k->w_pad.empty() == (k->block == 0));
    if (k->w_pad.empty()) continue;
    double worst = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < k->w.size(); ++i)
      worst = std::max(worst, std::abs(k->w_pad[i] + k->w_specimen[i] - k->w[i])), largest = std::max(largest, k->w[i]);
    CHECK(worst <= 1e-12 * largest);
  }
  // The last block adds the same wear to both bodies, cell by cell (pad_fraction 0.5), and the sliding block spread
  // the specimen's scar past the pad's.
  const WearRecord &before = *starts(2), &last = records.back();
  double worst = 0.0;
  for (std::size_t i = 0; i < last.w.size(); ++i)
    worst = std::max(worst, std::abs((last.w_pad[i] - before.w_pad[i]) - (last.w_specimen[i] - before.w_specimen[i])));
  CHECK(worst <= 1e-12 * last.w[std::size_t(last.w.size() / 2)]);
  CHECK(r.stage.specimen.extent.second - r.stage.specimen.extent.first >
        r.stage.pad.extent.second - r.stage.pad.extent.first + 20e-6);  // the stroke: 24.3 µm each way
  CHECK(relative(r.stage.pad.worn_area, r.stage.specimen.worn_area) < kAreaRatioClipped);
}

TEST_CASE("body frames: every stepper and both pairs wear each body in its own frame, and agree") {
  // The example at 256 cells for 2000 cycles, steel on steel and steel on titanium: the stepper "explicit"
  // (Dormand–Prince under its error control, capped below the stability limit) against the implicit step, each
  // body's depth and area to kAgreement (measured 2e-5). Only the pad wearing, or a stroke under half a cell
  // (δ = 1 µm: 0.32 µm each way, cells of 4.7 µm), wears one profile.
  for (const bool dissimilar : {false, true}) {
    CAPTURE(dissimilar);
    Scene s = example(256, WearStepper::implicit);
    s.wear->cycles = 2000;
    s.wear->record = {2000};
    if (dissimilar) s.similar = false, s.specimen = Material{110e9, 0.34};
    const Run implicit = run(s);
    s.wear->stepper = WearStepper::explicit_capped;
    const Run explicit_run = run(s);
    REQUIRE(implicit.stage.frame_positions > 0);
    REQUIRE(explicit_run.stage.frame_positions > 0);
    CHECK(explicit_run.stage.frame_directions == (dissimilar ? 2 : 1));
    CHECK(relative(explicit_run.stage.pad.max_depth, implicit.stage.pad.max_depth) < kAgreement);
    CHECK(relative(explicit_run.stage.specimen.max_depth, implicit.stage.specimen.max_depth) < kAgreement);
    CHECK(relative(explicit_run.stage.specimen.worn_area, implicit.stage.specimen.worn_area) < kAgreement);
    CHECK(relative(explicit_run.stage.pad.worn_area, explicit_run.stage.specimen.worn_area) < kAreaRatioClipped);
  }
  Scene pad_only = example(256, WearStepper::implicit);
  pad_only.wear->cycles = 500;
  pad_only.wear->record = {500};
  pad_only.wear->pad_fraction = 1.0;
  CHECK(run(pad_only).stage.frame_positions == 0);
  Scene short_stroke = example(256, WearStepper::implicit);
  short_stroke.wear->cycles = 500;
  short_stroke.wear->record = {500};
  short_stroke.delta = 1e-6;
  CHECK(run(short_stroke).stage.frame_positions == 0);
}
