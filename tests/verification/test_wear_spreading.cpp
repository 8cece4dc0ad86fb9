// A contact that spreads as its slip zones wear (partial slip, force control, the analogy route): the contact-implicit
// step lags, beyond the contact, the slip a cell would travel on touching (engine/wear_contacts.hpp), so that a
// cell the contact reaches within a step is worn by the step of ΔN as by the two half steps. Were it lagged at zero,
// each cell entering would make the Richardson difference first order and reject the step (PHYSICS.md's Hertz wear
// case at 4096 cells over 10^3 cycles: 102 rejected against 168 accepted; with the slip lagged, 35 against 128).
//
// The case: PHYSICS.md's Hertz wear case (P = 1e5 N/m, Q/fP = 0.5, f = 0.5, Archard k = 1e-12) on 4096 cells,
// recorded at 10^2 and 10^3 cycles (the transient, where the contact edge moves by a cell every 10–20 cycles).
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <doctest/doctest.h>

#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"

using namespace fretwear;

namespace {

constexpr int kCells = 4096;

Scene spreading(double tolerance) {
  Scene s = test::hertz_wear(1e5, 0.5, 1e3, kCells);
  s.name = "wear_spreading";
  s.wear->record = {1e2, 1e3};
  s.wear->tolerance = tolerance;
  return s;
}

struct Case {
  Scene scene = spreading(1e-3);
  Model model = make_model(scene);
  NormalResult normal = solve_normal(scene, model);
  CycleStage cycle = solve_cycle(scene, model, normal);

  WearStage run(double tolerance) const {
    const Scene s = spreading(tolerance);
    return run_wear(s, model, normal, cycle);
  }
};

const Case& the_case() {
  static const Case c;
  return c;
}

}  // namespace

TEST_CASE("the cells beyond a partial-slip contact lag the slip they would travel on touching") {
  const Case& c = the_case();
  const std::unique_ptr<WearContact> contact = make_wear_contact(c.scene, c.model, c.cycle);
  wear::CycleResponse r;
  contact->respond(std::vector<double>(std::size_t(kCells), 0.0), r);
  const std::vector<double>& s = r.slip_if_touching();
  int first = -1, last = -1;
  for (int i = 0; i < kCells; ++i)
    if (r.p[i] > 0.0) last = i, first = first < 0 ? i : first;
  REQUIRE(first > 0);
  REQUIRE(last < kCells - 1);
  // The slip continues across each contact edge: positive on the first cells out of contact, and of the size of
  // the edge cells' (the relative slip 4 f (g* − g) is continuous there, g = 0 at the edge).
  for (int i : {first - 1, last + 1}) {
    CAPTURE(i);
    CHECK(r.s[i] == 0.0);
    CHECK(s[i] > 0.0);
  }
  CHECK(s[first - 1] > 0.5 * s[first]);
  CHECK(s[last + 1] > 0.5 * s[last]);
  // The stick zone still lags none.
  const int mid = kCells / 2;
  CHECK(r.p[mid] > 0.0);
  CHECK(s[mid] == 0.0);
}

TEST_CASE("a spreading contact: few rejected steps, and the profile within the tolerance of a tight run") {
  const Case& c = the_case();
  const WearStage w = c.run(1e-3);
  const WearStage tight = c.run(1e-4);
  CAPTURE(w.steps);
  CAPTURE(w.rejected_steps);
  // Two rejections per cell entering would give more rejected steps than accepted ones here.
  CHECK(w.rejected_steps * 2 < w.steps);
  REQUIRE(w.records.size() == tight.records.size());
  for (std::size_t k = 1; k < w.records.size(); ++k) {
    double diff = 0.0, depth = 0.0;
    for (std::size_t i = 0; i < w.records[k].w.size(); ++i) {
      diff = std::max(diff, std::abs(w.records[k].w[i] - tight.records[k].w[i]));
      depth = std::max(depth, tight.records[k].w[i]);
    }
    CAPTURE(k);
    CHECK(diff <= 1e-3 * depth);
  }
}
