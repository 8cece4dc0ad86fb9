// The worn state at the limit, as exact as the fresh one (PHYSICS.md, "Wear"; contact/wear_limit.hpp): the worn
// zones touch (zero gap) and carry no load, so their pressure is zero, cell after cell, and Ruiz's F1 = τδ there
// tends to zero as the grid is refined instead of growing with it.
//
// Case: hertz_wear_crack's contact (Hertz, Q/fP = 0.5, bulk stress 100 MPa, Archard k = 1e-12) worn for 1e7 cycles,
// past its limit (the worn area settles from about 1e6 on). F1 is computed as the fatigue stage does at a cell,
// τδ with τ = |q| at the top of the cycle and δ = s/4 (s the slip travelled per cycle, four times the amplitude).
#include <algorithm>
#include <cmath>
#include <utility>

#include <doctest/doctest.h>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/warnings.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

struct WornZones {
  int cells = 0;     // worn cells outside the stick zone
  int loaded = 0;    // of which carry pressure
  int flips = 0;     // loaded/unloaded changes between neighbours among them
  double p_max = 0;  // their largest pressure (Pa)
  double F1 = 0;     // their largest τδ (J/m²)
  double F1_initial = 0;  // the largest τδ of the first cycle, anywhere (J/m²)
  double p0 = 0;          // the first cycle's peak pressure (Pa)
};

WornZones worn_zones(int cells) {
  Scene s = test::hertz_wear(1e5, 0.5, 1e7, cells);
  s.bulk_stress = 100e6;
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  const WearStage w = run_wear(s, m, n, solve_cycle(s, m, n));
  const WearRecord& first = w.records.front();
  const WearRecord& last = w.records.back();
  REQUIRE(last.stick_zone);
  WornZones z;
  for (int i = 0; i < m.grid.n; ++i) {
    z.F1_initial = std::max(z.F1_initial, std::abs(first.q[i]) * first.s[i] / 4.0);
    z.p0 = std::max(z.p0, first.p[i]);
  }
  bool previous = false, inside = false;
  for (int i = 0; i < m.grid.n; ++i) {
    const double x = m.grid.x(i);
    const bool worn = last.w[i] > 0.0 && (x < last.stick_zone->first || x > last.stick_zone->second);
    if (!worn) {
      inside = false;
      continue;
    }
    const bool loaded = last.p[i] > 0.0;
    ++z.cells;
    z.loaded += loaded;
    if (inside && loaded != previous) ++z.flips;
    previous = loaded, inside = true;
    z.p_max = std::max(z.p_max, last.p[i]);
    z.F1 = std::max(z.F1, std::abs(last.q[i]) * last.s[i] / 4.0);
  }
  return z;
}

}  // namespace

TEST_CASE("at the wear limit the worn zones carry no load: no alternating pressure, F1 there tends to zero") {
  // Were the worn cells held rigid once unloaded (no slip on touching where p = 0, engine/wear_contacts.cpp), the
  // worn zones' pressure would alternate from cell to cell: at 512 / 1024 / 2048 cells 45 / 92 / 187 flips, up to
  // 0.31 / 0.93 / 4.7 MPa, F1 there 0.031 / 0.098 / 0.47 J/m², growing with the grid. The limit's worn zones carry exactly zero (measured: no loaded cell at
  // any of the three grids); the bounds leave room for a stepper's last step that has not quite closed them.
  constexpr double kPressure = 1e-6;  // of p0: a step's residual wear rate, far below any cell's resolution
  constexpr double kF1 = 1e-6;        // of the first cycle's F1 peak
  for (int cells : {512, 1024, 2048}) {
    CAPTURE(cells);
    const WornZones z = worn_zones(cells);
    MESSAGE("cells ", cells, ": worn ", z.cells, ", loaded ", z.loaded, ", flips ", z.flips, ", p_max ", z.p_max,
            " Pa, F1 ", z.F1, " J/m² (first cycle ", z.F1_initial, ")");
    CHECK(z.cells > 0.2 * cells);
    CHECK(z.flips <= 4);
    CHECK(z.p_max < kPressure * z.p0);
    CHECK(z.F1 < kF1 * z.F1_initial);
  }
}

namespace {

struct Run {
  Model model;
  WearStage wear;
};

Run run_example(const std::string& name) {
  const Scene s = load_scene(std::string(FRETWEAR_SOURCE_DIR) + "/examples/" + name + ".json");
  Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  WearStage w = run_wear(s, m, n, solve_cycle(s, m, n));
  return {std::move(m), std::move(w)};
}

// The run reaches the limit of its own grid (WearAsymptote::cells_worn_area) to a few steps' tolerance of 1e-3.
constexpr double kStepper = 3e-3;

}  // namespace

// The run's stick zones are whole cells, so it tends to the complete contact over them; the direct limit's corners
// are the located edges. Measured on hertz_wear at 512 / 1024 / 2048 / 4096 cells in windows not aligned to the stick
// zone: the run settled at 101.23 / 101.08 / 99.50 / 100.17 % of the direct limit, each equal to the limit over its
// stick cells to 1e-6, while the direct limit moved by −0.39 / −0.23 / −0.04 % per doubling (within 0.8 / 0.4 / 0.15
// / 0.12 % of the closed form). With the cells aligned to the stick zone's ends (make_model) the run is within 0.1 %
// of the direct limit at each of 512, 1024 and 2048 cells.
TEST_CASE("hertz_wear at its default grid reaches the directly computed asymptote within kWearAgreement") {
  const Run r = run_example("hertz_wear");
  const WearRecord& last = r.wear.records.back();
  const WearAsymptote& a = r.wear.asymptote;
  CHECK(last.worn_area == test::rel(a.cells_worn_area, kStepper));
  CHECK(std::abs(last.fraction - 1.0) < kWearAgreement);
  CHECK(std::abs(a.cells_worn_area / a.worn_area - 1.0) < kWearAgreement);
}

TEST_CASE("two zones (paper002_two_zone_wear) at its default grid reach the asymptote within kWearAgreement") {
  // The second zone's ends fall within their cells; at 2048 cells the run's limit is 0.2 % from the direct one.
  const Run r = run_example("paper002_two_zone_wear");
  const WearRecord& last = r.wear.records.back();
  const WearAsymptote& a = r.wear.asymptote;
  CHECK(last.worn_area == test::rel(a.cells_worn_area, kStepper));
  CHECK(std::abs(last.fraction - 1.0) < kWearAgreement);
}

TEST_CASE("a worn contact at its limit touches, unloaded, out to the asymptote's worn extent") {
  // hertz_wear at 1e7 cycles: the loaded contact is the stick zone; the worn flats outside it touch at zero pressure
  // out to x_e = 1.169 a, which the located touching extent matches to a cell. Unworn, the two extents coincide.
  const Run r = run_example("hertz_wear");
  const double h = r.model.grid.h();
  const WearRecord& first = r.wear.records.front();
  const WearRecord& last = r.wear.records.back();
  CHECK(first.touching.first == first.contact.first);
  CHECK(first.touching.second == first.contact.second);
  REQUIRE(last.stick_zone);
  CHECK(std::abs(last.contact.first - last.stick_zone->first) < h);
  CHECK(std::abs(last.contact.second - last.stick_zone->second) < h);
  CHECK(std::abs(last.touching.first - r.wear.asymptote.extent.first) < h);
  CHECK(std::abs(last.touching.second - r.wear.asymptote.extent.second) < h);
}
