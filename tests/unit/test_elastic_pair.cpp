// Composite compliance and Dundurs' constants (PHYSICS.md, "Conventions"; Dundurs 1969).
#include <doctest/doctest.h>

#include "support.hpp"

#include "contact/elastic_pair.hpp"
#include "common/error.hpp"

using namespace fretwear;

TEST_CASE("similar bodies: A = 4(1 − ν²)/E in plane strain, 4/E in plane stress, β = 0") {
  const Material steel{200e9, 0.3};
  const ElasticPair strain(steel, steel, PlaneState::strain);
  CHECK(strain.A() == test::rel(1.82e-11, 1e-14));
  CHECK(strain.E_star() == test::rel(109.89010989e9, 1e-10));
  CHECK(strain.beta() == 0.0);
  CHECK(strain.alpha() == 0.0);
  const ElasticPair stress(steel, steel, PlaneState::stress);
  CHECK(stress.A() == test::rel(4.0 / 200e9, 1e-14));
}

TEST_CASE("dissimilar bodies: A sums the compliances, a rigid pad gives β = −(1 − 2ν)/(2(1 − ν))") {
  const Material steel{200e9, 0.3}, aluminium{70e9, 0.33};
  const ElasticPair pair(steel, aluminium, PlaneState::strain);
  CHECK(pair.A() == test::rel(2 * ((1 - 0.09) / 200e9 + (1 - 0.33 * 0.33) / 70e9), 1e-14));
  const ElasticPair rigid({1e30, 0.3}, aluminium, PlaneState::strain);
  CHECK(rigid.beta() == test::rel(-(1 - 2 * 0.33) / (2 * (1 - 0.33)), 1e-12));
  // Swapping the bodies flips the signs of α and β.
  const ElasticPair swapped(aluminium, steel, PlaneState::strain);
  CHECK(swapped.beta() == test::rel(-pair.beta(), 1e-14));
  CHECK(swapped.alpha() == test::rel(-pair.alpha(), 1e-14));
}

TEST_CASE("plane state words") {
  CHECK(plane_state_from_string("stress") == PlaneState::stress);
  CHECK(to_string(PlaneState::strain) == "strain");
  CHECK_THROWS_WITH_AS(plane_state_from_string("strane"), doctest::Contains("\"strain\" or \"stress\""), InputError);
}
