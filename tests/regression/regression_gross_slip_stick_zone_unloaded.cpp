// cycle.stick_zone_unloaded (the stick zone at δ = 0 on the way down) reported one cell when the bodies slide
// through that instant under displacement control: every cell is at |q| = f p and the margin f p − |q| that locates
// a stick zone is zero but for round-off, which left a cell standing. It is null when the bodies slide then; when
// the stroke is short enough that δ = 0 comes before sliding resumes, the stick zone there is real and stays.
#include <string>

#include <doctest/doctest.h>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"

using namespace fretwear;

namespace {

CycleResult cycle_of(const std::string& example, int cells) {
  Scene s = load_scene(std::string(FRETWEAR_SOURCE_DIR) + "/examples/" + example + ".json");
  s.cells = cells;
  const Model m = make_model(s);
  const NormalResult n = solve_normal(s, m);
  return solve_cycle(s, m, n).result;
}

}  // namespace

TEST_CASE("gross slip sliding through the unloaded instant has no stick zone there") {
  for (const int cells : {256, 1024}) {
    CAPTURE(cells);
    // δ = ±25 µm against a stick limit of 0.68 µm: the bodies slide from δ = 24 µm down to −25 µm.
    const CycleResult r = cycle_of("gross_slip_displacement_wear", cells);
    CHECK(r.regime == Regime::gross_slip);
    CHECK(!r.stick_zone);
    CHECK(!r.stick_zone_unloaded);
  }
  // δ = ±2 µm against a stick limit of 1.22 µm: unloading by 2 µm stays within the 2.44 µm the contact takes to
  // slide again, so at δ = 0 a stick zone holds (Mindlin–Deresiewicz unloading), though the cycle slides at its ends.
  const CycleResult r = cycle_of("hertz_displacement_gross", 1024);
  CHECK(r.regime == Regime::gross_slip);
  CHECK(r.stick_zone_unloaded);
}
