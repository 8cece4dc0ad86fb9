// Helpers shared by the tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <doctest/doctest.h>

namespace fretwear::test {

// A strictly relative comparison: |got − want| < rel · max(|got|, |want|). doctest::Approx adds a scale of 1 to the
// magnitudes, which makes its epsilon absolute for SI-sized values (metres of 1e-4, compliances of 1e-11) and such
// a check unable to fail; never use Approx on dimensional values.
inline doctest::Approx rel(double want, double tolerance) {
  return doctest::Approx(want).epsilon(tolerance).scale(0.0);
}

// max_i |a_i − b_i| of two fields on the same cells (a test failure when their sizes differ).
inline double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

}  // namespace fretwear::test
