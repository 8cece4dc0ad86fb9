// Helpers shared by the tests.
#pragma once

#include <doctest/doctest.h>

namespace fretwear::test {

// A strictly relative comparison: |got − want| < rel · max(|got|, |want|). doctest::Approx adds a scale of 1 to the
// magnitudes, which makes its epsilon absolute for SI-sized values (metres of 1e-4, compliances of 1e-11) and such
// a check unable to fail; never use Approx on dimensional values.
inline doctest::Approx rel(double want, double tolerance) {
  return doctest::Approx(want).epsilon(tolerance).scale(0.0);
}

}  // namespace fretwear::test
