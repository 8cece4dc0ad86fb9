// Wear near the stick limit on a fine grid (the Standards' hard cases: friction ratios near one, fine grids): a steel
// pad on an aluminium specimen (β ≈ −0.11), Hertz, f = 0.9, Q/fP = 0.99, Archard k = 1e-12 1/Pa, 10^7 cycles. Its
// slip zones wear until the stick zone, some 17 cells wide at 512 cells, stands 2.4 µm proud of them and carries
// most of the load, up to 10 GPa at its corners; the constrained CG's working sets cycled on such contacts
// (tests/regression/regression_normal_solve_worn_punch_corners.cpp), and the run stopped with exit 3 at 9255 cycles.
// It runs now, but beside its stick zone the worn depth zigzags from cell to cell (docs/METHODS.md, "Known to
// fail"), and the run says so: the warning worn_profile_zigzag.
// The same scene at 1024 and 2048 cells (9 s and 55 s, too long for the suite) ends at worn areas of 8.7842e-10 and
// 8.9181e-10 m², against 8.9820e-10 here. That 2.3 % is not the grid's alone: the stick zone, 17 to 70 cells wide,
// breaks into fragments of a few cells as it wears, and the 1024-cell run has ended anywhere from 8.78e-10 to
// 8.98e-10 m² as its failing solves were rescued by one path or another to the same tolerance (docs/METHODS.md,
// "Known to fail"). The reference is the 2048-cell run's, to that spread.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "engine/simulation.hpp"
#include "engine/warnings.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

TEST_CASE("dissimilar wear at Q/fP = 0.99 runs 10^7 cycles on 512 cells and warns of the zigzag at its stick zone") {
  Scene s = test::hertz_wear(1e5, 0.99, 1e7, 512);
  s.friction = 0.9;
  s.specimen = {71e9, 0.33};
  const RunResult r = Simulation(s).run();
  REQUIRE(r.wear);
  const WearStage& wear = *r.wear;
  CHECK(wear.cycles_reached == 1e7);
  const WearRecord& last = wear.records.back();
  CHECK(last.cycles == 1e7);
  // The 2048-cell run's worn area (header), to the spread of the grids and paths, 2.3 %.
  CHECK(last.worn_area == test::rel(8.9181e-10, 3e-2));

  // The zigzag: cells in the stick zone's outer cells alternate between worn and not, by more than 1 % of the deepest
  // wear (five cells in from each end at 512 cells), and nowhere beyond four cells from it; the warning names it.
  REQUIRE(last.stick_zone);
  const Grid& grid = r.normal.grid;
  const std::vector<double>& w = last.w;
  const double w_max = *std::max_element(w.begin(), w.end());
  int at_stick = 0, elsewhere = 0;
  for (int i = 1; i + 2 < grid.n; ++i) {
    const double a = w[i - 1] - 2.0 * w[i] + w[i + 1], b = w[i] - 2.0 * w[i + 1] + w[i + 2];
    if (!(a * b < 0.0 && std::min(std::abs(a), std::abs(b)) > 0.01 * w_max)) continue;
    const double x = grid.x(i);
    const bool beside = x > last.stick_zone->first - 4.0 * grid.h() && x < last.stick_zone->second + 4.0 * grid.h();
    (beside ? at_stick : elsewhere)++;
  }
  CHECK(at_stick > 0);
  CHECK(elsewhere == 0);
  const std::vector<Warning> warnings = result_warnings(s, r);
  CHECK(std::any_of(warnings.begin(), warnings.end(),
                    [](const Warning& warning) { return warning.code == "worn_profile_zigzag"; }));
}

TEST_CASE("a smooth worn profile gives no zigzag warning: the Hertz wear case at Q/fP = 0.5") {
  const Scene s = test::hertz_wear(1e5, 0.5, 1e5, 512);
  const RunResult r = Simulation(s).run();
  const std::vector<Warning> warnings = result_warnings(s, r);
  CHECK(std::none_of(warnings.begin(), warnings.end(),
                     [](const Warning& warning) { return warning.code == "worn_profile_zigzag"; }));
}

// A slip zone narrower than a cell wears a single cell at each edge of the contact: its second differences alternate
// three times (+, −2, +), which is no zigzag, and the warning that it was ("more grid.cells do not remove it") was
// false: found on a random scene, a cylinder under displacement control at Q/fP = 0.06 on 64 and 256 cells (slip
// zones of 0.68 and 2.65 cells; on 1024 cells the worn profile is smooth). slip_zone_under_resolved says what it is.
TEST_CASE("a worn zone a cell wide is an under-resolved slip zone, not a zigzag") {
  for (const int cells : {64, 256}) {
    CAPTURE(cells);
    Scene s = test::hertz_wear(852959.6, 0.5, 1e4, cells);
    s.pad = s.specimen = {84.7e9, 0.383};
    s.profile.R = 0.0853;
    s.friction = 1.466;
    s.Q_ratio.reset();
    s.control = LoadControl::displacement;
    s.delta = 3.72e-6;
    s.wear->coefficient = 1.5e-16;
    const RunResult r = Simulation(s).run();
    const std::vector<Warning> warnings = result_warnings(s, r);
    CHECK(std::none_of(warnings.begin(), warnings.end(),
                       [](const Warning& w) { return w.code == "worn_profile_zigzag"; }));
    CHECK(std::any_of(warnings.begin(), warnings.end(),
                      [](const Warning& w) { return w.code == "slip_zone_under_resolved"; }));
  }
}

TEST_CASE("under a load history the zigzag at the contact's edge is the increments', and more of them remove it") {
  // examples/hertz_history_out_of_phase.json's history without its bulk stress, worn at 512 cells: at 40 increments
  // a cycle the contact's edge sweeps over some three cells an increment as P moves, and the worn depth there
  // zigzags; at 80 it does not (docs/METHODS.md, "Load histories").
  for (const int increments : {40, 80}) {
    CAPTURE(increments);
    Scene s = test::hertz_wear(1e5, 0.5, 1e5, 512);
    s.Q_ratio.reset();
    s.history = {{0, 1e5, 2.5e4, 0}, {1, 7e4, 0, 0}, {2, 1e5, -2.5e4, 0}, {3, 1.3e5, 0, 0}, {4, 1e5, 2.5e4, 0}};
    s.tangential->increments = increments;
    const RunResult r = Simulation(s).run();
    const std::vector<Warning> warnings = result_warnings(s, r);
    const auto zigzag = std::find_if(warnings.begin(), warnings.end(),
                                     [](const Warning& w) { return w.code == "worn_profile_zigzag"; });
    CHECK((zigzag != warnings.end()) == (increments == 40));
    if (zigzag != warnings.end()) {
      MESSAGE(zigzag->message);
      CHECK(zigzag->message.find("raise effects.tangential.increments (40 now") != std::string::npos);
    }
  }
}
