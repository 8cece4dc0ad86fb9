// The flat that gross slip wears (contact/worn_flat.hpp) against its closed form on a cylinder, g0 = x²/(2R): the
// flat at depth d ends at ±√(2Rd) and holds W(d) = ∫ (d − x²/(2R)) dx = (4/3) d √(2Rd), so the flat holding W is at
// d = (3W / (4√(2R)))^(2/3).
#include <cmath>
#include <tuple>

#include <doctest/doctest.h>

#include "contact/worn_flat.hpp"

using namespace fretwear;

namespace {

Profile cylinder(double R) {
  ProfileSpec spec;
  spec.type = ProfileType::cylinder;
  spec.R = R;
  return Profile(spec);
}

}  // namespace

TEST_CASE("the flat that holds a worn area on a cylinder is the closed form's") {
  const double R = 6e-3, h = 1e-6;
  const Profile profile = cylinder(R);
  for (double W : {1e-12, 1e-9, 1.8e-7}) {
    const double d = std::pow(3.0 * W / (4.0 * std::sqrt(2.0 * R)), 2.0 / 3.0), end = std::sqrt(2.0 * R * d);
    const Flat f = flat_holding(profile, W, h);
    CAPTURE(W);
    CHECK(f.area == doctest::Approx(W).epsilon(1e-6));
    CHECK(f.right == doctest::Approx(end).epsilon(1e-4));
    CHECK(f.left == doctest::Approx(-end).epsilon(1e-4));
    // The flat at the closed form's depth holds the closed form's area: W(d) by the trapezoids of h/4.
    CHECK(flat_at(profile, d, h).area == doctest::Approx(W).epsilon(1e-4));
  }
}

TEST_CASE("the window that holds a worn flat covers it, the unworn contact and the stroke with a fifth to spare") {
  const double R = 6e-3, h = 1e-6, W = 1e-9, U = 2e-5;
  const Profile profile = cylinder(R);
  const double end = flat_holding(profile, W, h).right;
  // The flat reaches further than the unworn contact [−a, a] with a = end / 2: it and U, and 20 %.
  auto [lo, hi] = window_holding(profile, W, h, U, -0.5 * end, 0.5 * end);
  CHECK(hi == doctest::Approx(1.2 * (end + U)));
  CHECK(lo == doctest::Approx(-1.2 * (end + U)));
  // An unworn contact wider than the flat (its right end at 2 × end): the window is centred on the lowest point and
  // covers the contact's further end.
  std::tie(lo, hi) = window_holding(profile, W, h, 0.0, -0.5 * end, 2.0 * end);
  CHECK(hi == doctest::Approx(2.4 * end));
  CHECK(lo == doctest::Approx(-2.4 * end));
}
