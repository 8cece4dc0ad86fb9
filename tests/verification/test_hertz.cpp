// Hertz (PHYSICS.md, "Normal contact" and the public reference case): half-width, peak pressure, the pressure
// distribution, and the load–size integral as a second, independent answer.
#include <cmath>

#include <doctest/doctest.h>

#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/load_size.hpp"
#include "engine/simulation.hpp"

using namespace fretwear;

namespace {
Scene hertz_scene(double P, int cells) {
  Scene s;
  s.name = "hertz";
  s.pad = s.specimen = {200e9, 0.3};
  s.profile.type = ProfileType::cylinder;
  s.profile.R = 0.01;
  s.P = P;
  s.cells = cells;
  return s;
}
}  // namespace

TEST_CASE("PHYSICS.md's public Hertz numbers") {
  const auto hz100 = closed_form::hertz(100e3, 1.82e-11, 0.01);
  CHECK(hz100.a == test::rel(0.107641e-3, 5e-6));
  CHECK(hz100.p0 == test::rel(591.43e6, 1e-5));
  const auto hz1000 = closed_form::hertz(1000e3, 1.82e-11, 0.01);
  CHECK(hz1000.a == test::rel(0.340389e-3, 5e-6));
  CHECK(hz1000.p0 == test::rel(1870.27e6, 1e-5));
}

TEST_CASE("the load–size integral gives the Hertz half-width to round-off") {
  ProfileSpec spec;
  spec.R = 0.01;
  const Profile cylinder(spec);
  for (double P : {1e3, 1e5, 1e7}) {
    const double want = closed_form::hertz(P, 1.82e-11, 0.01).a;
    CHECK(std::abs(half_width_for_load(cylinder, 1.82e-11, P) / want - 1.0) < 1e-12);
  }
}

TEST_CASE("Hertz with about 700 cells in contact: half-width within 0.1 %, RMS pressure error within 2e-4 p0") {
  // The accuracy budget. With ~700 cells over the contact a cell is 0.3 % of a, so 0.1 % needs the
  // sub-cell edge fit; the RMS excludes the two cells nearest each edge, where the square root is not resolved.
  const NormalResult r = solve_normal(hertz_scene(1e6, 1024));
  REQUIRE(r.reference);
  CHECK(r.cells_in_contact > 650);
  CHECK(r.cells_in_contact < 750);
  REQUIRE(r.zones.size() == 1);
  CHECK(r.zones[0].left.method == EdgeMethod::square_root_fit);
  CHECK(r.reference->extent_error < 1e-3);
  CHECK(r.reference->rms_error < 2e-4);
  CHECK(r.reference->p_max_error < 2e-4);
  double load = 0.0;
  for (double p : r.state.p) load += p * r.grid.h();
  CHECK(load == test::rel(1e6, 1e-13));
}
