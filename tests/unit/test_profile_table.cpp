// A table profile read between its points (contact/profile.hpp, Interpolation): linear has a kink at every point;
// pchip, makima and cubic pass through the points with a continuous slope; each refuses a table it cannot read.
#include <cmath>
#include <limits>
#include <vector>

#include <doctest/doctest.h>

#include "common/error.hpp"
#include "contact/profile.hpp"

using namespace fretwear;

namespace {

constexpr double kR = 0.01;
// pchip and makima keep the points themselves: at a point they return it to a few ulps of the largest height.
constexpr double kNodeTolerance = 16 * std::numeric_limits<double>::epsilon();
// The cardinal B-spline returns a sum of coefficients from a banded solve that also carries the estimated end
// slopes; at a point it lands within 1e-12 of the largest height (6e-13 here), far below any measured profile's
// digits.
constexpr double kSplineNodeTolerance = 1e-12;

// g0 = x²/(2R) sampled at n uniformly spaced points over [−L, L].
ProfileSpec sampled_cylinder(int n, double L, Interpolation interpolation) {
  ProfileSpec s;
  s.type = ProfileType::table;
  s.interpolation = interpolation;
  for (int i = 0; i < n; ++i) {
    const double x = -L + 2.0 * L * i / (n - 1);
    s.x.push_back(x);
    s.h.push_back(x * x / (2.0 * kR));
  }
  return s;
}

}  // namespace

TEST_CASE("interpolation words: to_string and from_string agree, a wrong word names the accepted ones") {
  for (Interpolation i : {Interpolation::linear, Interpolation::pchip, Interpolation::makima, Interpolation::cubic})
    CHECK(interpolation_from_string(to_string(i)) == i);
  CHECK_THROWS_WITH_AS(interpolation_from_string("spline"),
                       doctest::Contains("use \"linear\", \"pchip\", \"makima\" or \"cubic\""), InputError);
  CHECK(min_table_points(Interpolation::linear) == 2);
  CHECK(min_table_points(Interpolation::pchip) == 4);
  CHECK(min_table_points(Interpolation::makima) == 4);
  CHECK(min_table_points(Interpolation::cubic) == 5);
}

TEST_CASE("pchip, makima and cubic pass through the points, with the slope continuous across each point") {
  const double L = 0.5e-3, g_max = L * L / (2.0 * kR);
  for (Interpolation i : {Interpolation::pchip, Interpolation::makima, Interpolation::cubic}) {
    CAPTURE(to_string(i));
    const ProfileSpec spec = sampled_cylinder(21, L, i);
    const Profile p(spec);
    const double node = i == Interpolation::cubic ? kSplineNodeTolerance : kNodeTolerance;
    for (std::size_t k = 0; k < spec.x.size(); ++k) CHECK(std::abs(p.gap(spec.x[k]) - spec.h[k]) <= node * g_max);
    // Slopes just left and right of an interior point: equal to first order in the offset (no kink).
    const double dx = 1e-9 * L, s_max = L / kR;
    for (std::size_t k = 1; k + 1 < spec.x.size(); ++k)
      CHECK(std::abs(p.slope(spec.x[k] - dx) - p.slope(spec.x[k] + dx)) <= 1e-6 * s_max);
    // Only the ends split quadratures: the curve is smooth between them.
    CHECK(p.kinks() == std::vector<double>{-L, L});
    CHECK(std::isinf(p.gap(1.01 * L)));
  }
}

TEST_CASE("a linear table keeps a kink at every point") {
  const ProfileSpec spec = sampled_cylinder(21, 0.5e-3, Interpolation::linear);
  const Profile p(spec);
  CHECK(p.kinks() == spec.x);
  const double dx = 1e-9 * 0.5e-3, h = spec.x[1] - spec.x[0];
  // The slope jumps by the second difference over the spacing: h/R on a parabola.
  CHECK(std::abs(p.slope(spec.x[5] + dx) - p.slope(spec.x[5] - dx) - h / kR) <= 1e-6 * h / kR);
}

TEST_CASE("a table with too few points for its interpolation, or cubic on non-uniform x, is refused") {
  CHECK_THROWS_WITH_AS(Profile(sampled_cylinder(3, 1e-4, Interpolation::makima)),
                       doctest::Contains("needs at least 4 points"), InputError);
  CHECK_THROWS_WITH_AS(Profile(sampled_cylinder(4, 1e-4, Interpolation::cubic)),
                       doctest::Contains("needs at least 5 points"), InputError);
  ProfileSpec uneven = sampled_cylinder(9, 1e-4, Interpolation::cubic);
  uneven.x[4] += 0.1 * (uneven.x[5] - uneven.x[4]);
  CHECK_FALSE(uniformly_spaced(uneven.x));
  CHECK_THROWS_WITH_AS(Profile{uneven}, doctest::Contains("uniformly spaced x"), InputError);
  uneven.interpolation = Interpolation::makima;
  CHECK_NOTHROW(Profile{uneven});
}

TEST_CASE("a copied profile evaluates alike: the curve is shared, not rebuilt") {
  const Profile p(sampled_cylinder(41, 0.5e-3, Interpolation::makima));
  const Profile q = p;
  for (double x : {-0.3e-3, 0.0, 0.17e-3}) CHECK(q.gap(x) == p.gap(x));
  CHECK(q.lowest_point() == p.lowest_point());
}
