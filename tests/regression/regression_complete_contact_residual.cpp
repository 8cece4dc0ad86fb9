// Regression: a sharp flat punch never converged. Its contact loads every admissible cell, so the residual's scale,
// the largest open gap, was itself only round-off and the relative residual stayed near 0.3 for 20 000 iterations.
// The scale is now at least A P.
#include <cmath>

#include <doctest/doctest.h>

#include "engine/simulation.hpp"

using namespace fretwear;

TEST_CASE("a sharp flat punch (complete contact) converges, with its edges at the corners") {
  Scene s;
  s.name = "flat";
  s.pad = s.specimen = {200e9, 0.3};
  s.profile.type = ProfileType::flat;
  s.profile.b = 0.5e-3;
  s.P = 2e5;
  s.cells = 1024;
  const NormalResult r = solve_normal(s);
  CHECK(r.summary.converged());
  CHECK(r.summary.iterations < 1000);
  REQUIRE(r.zones.size() == 1);
  CHECK(r.zones[0].left.method == EdgeMethod::corner);
  CHECK(r.zones[0].right.method == EdgeMethod::corner);
  // The corners lie on cell boundaries (the window is aligned to them): exact to round-off.
  CHECK(std::abs(r.zones[0].right.x - 0.5e-3) < 1e-12 * 0.5e-3);
}
