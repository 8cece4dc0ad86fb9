// `fretwear convergence` (engine/convergence.hpp): the normal problem and, with effects.tangential, the stick zone on
// grids of doubling size against PHYSICS.md's closed forms.
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include "contact/closed_form.hpp"
#include "engine/convergence.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

TEST_CASE("convergence reports the stick-zone error against Hertz, falling with the grid") {
  // Nowell–Hills: Q/fP = 0.5, σ/(f p0) = 0.6, so e/a = 0.15 and the stick zone is [−0.557107, 0.857107] a.
  const double P = 1e5, A = 4.0 * (1.0 - test::kHertzNu * test::kHertzNu) / test::kHertzE;
  const double p0 = closed_form::hertz(P, A, test::kHertzR).p0;
  const Scene s = test::hertz_cycle(P, 0.5, 256, 0.6 * test::kHertzF * p0);
  const ConvergenceStudy study = run_convergence(s, 256, 4096, nullptr);
  CHECK(study.against == "hertz");
  REQUIRE(study.stick_against == "hertz");
  REQUIRE(study.rows.size() == 5);
  const double a = closed_form::hertz(P, A, test::kHertzR).a;
  for (const ConvergenceRow& r : study.rows) {
    CAPTURE(r.cells);
    CHECK(r.has_stick);
    // The reported error is the stick zone's distance from the closed form, over c = 0.707107 a.
    const double c = std::sqrt(0.5);  // e = 0.15: [−0.557107, 0.857107] a to six digits
    const double e = std::max(std::abs(r.stick_left / a - (0.15 - c)), std::abs(r.stick_right / a - (0.15 + c)));
    CHECK(r.stick_error == test::rel(e / c, 1e-6));
    CHECK(r.stick_error < 5e-3);
  }
  // Sub-cell edge fits make the error uneven from grid to grid, but over 16× more cells it falls by more than 8×.
  CHECK(study.rows.back().stick_error < study.rows.front().stick_error / 8.0);
  CHECK(study.observed_stick_order().size() == 4);
  const std::string csv = study.csv();
  CHECK(csv.find("stick_left_m,stick_right_m,stick_error") != std::string::npos);
  CHECK(study.table().find("stick zone at the top of the cycle, errors against hertz") != std::string::npos);
}

TEST_CASE("convergence reports the rounded punch's stick zone against eq 9, and none without a cycle") {
  Scene s = test::hertz_cycle(843660.71, 0.5, 256);
  s.profile.type = ProfileType::flat_rounded;
  s.profile.a = 0.25e-3;  // a/b = 0.5, b = 0.5 mm: c/b = 0.831044 at Q/fP = 0.5 (PHYSICS.md)
  const ConvergenceStudy study = run_convergence(s, 512, 2048, nullptr);
  REQUIRE(study.stick_against == "rounded_punch");
  for (const ConvergenceRow& r : study.rows) {
    CAPTURE(r.cells);
    CHECK(r.stick_right / 0.5e-3 == test::rel(0.831044, 2e-3));
    CHECK(r.stick_error < 2e-3);
  }
  s.tangential.reset();
  const ConvergenceStudy normal_only = run_convergence(s, 512, 1024, nullptr);
  CHECK(normal_only.stick_against.empty());
  CHECK(normal_only.csv().find("stick") == std::string::npos);
}
