// Profile: each type's gap and slope, offset_x and tilt_rad, the lowest point, kinks, and the flags the window
// chooser and the load–size integral rely on (contact/profile.hpp).
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <doctest/doctest.h>

#include "common/error.hpp"
#include "contact/profile.hpp"

using namespace fretwear;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Closed-form gaps are a few floating-point operations: a handful of ulps of the largest term involved.
constexpr double kRoundOff = 16.0 * kEps;
// A smooth minimum is located from gap values alone, which change only by O(δx²) near it: no method can place it
// better than √ε relative to the length scale (Brent's bracket stops there).
const double kMinimumLocation = 4.0 * std::sqrt(kEps);

constexpr double kR = 0.01;    // m
constexpr double kA = 1e-3;    // flat half-length (m)
constexpr double kB = 0.5e-3;  // punch half-width (m)

ProfileSpec cylinder(double R = kR, double offset = 0.0) {
  ProfileSpec s;
  s.type = ProfileType::cylinder;
  s.R = R;
  s.offset_x = offset;
  return s;
}

ProfileSpec wavy(double amplitude, double wavelength) {
  ProfileSpec s;
  s.type = ProfileType::wavy;
  s.amplitude = amplitude;
  s.wavelength = wavelength;
  return s;
}

ProfileSpec wedge(double angle_deg) {
  ProfileSpec s;
  s.type = ProfileType::wedge;
  s.angle_deg = angle_deg;
  return s;
}

ProfileSpec flat(double b) {
  ProfileSpec s;
  s.type = ProfileType::flat;
  s.b = b;
  return s;
}

ProfileSpec combine(ProfileType type, std::vector<ProfileSpec> terms) {
  ProfileSpec s;
  s.type = type;
  s.terms = std::move(terms);
  return s;
}

bool close(double got, double want, double scale) { return std::abs(got - want) <= kRoundOff * scale; }

}  // namespace

TEST_CASE("profile type words round-trip and a wrong word lists the accepted ones") {
  for (auto t : {ProfileType::cylinder, ProfileType::flat_rounded, ProfileType::flat, ProfileType::wedge,
                 ProfileType::rounded_wedge, ProfileType::wavy, ProfileType::table, ProfileType::sum,
                 ProfileType::envelope})
    CHECK(profile_type_from_string(to_string(t)) == t);
  try {
    profile_type_from_string("sphere");
    FAIL("no error for an unknown word");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("flat_rounded") != std::string::npos);
  }
}

TEST_CASE("cylinder: g0 = x²/2R, g0′ = x/R") {
  const Profile p(cylinder());
  for (double x : {-2e-3, -1e-4, 0.0, 3e-5, 1e-3}) {
    CHECK(close(p.gap(x), x * x / (2 * kR), x * x / kR));
    CHECK(close(p.slope(x), x / kR, std::abs(x) / kR));
  }
  CHECK(p.lowest_point() == 0.0);
  CHECK(p.kinks().empty());
  CHECK(p.support().first == -kInf);
  CHECK(p.support().second == kInf);
}

TEST_CASE("flat_rounded: zero on the flat, parabolic corners beyond ±a") {
  ProfileSpec s;
  s.type = ProfileType::flat_rounded;
  s.a = kA;
  s.R = kR;
  const Profile p(s);
  for (double x : {-kA, -0.3 * kA, 0.0, 0.9 * kA, kA}) {
    CHECK(p.gap(x) == 0.0);
    CHECK(p.slope(x) == 0.0);
  }
  // kA + e carries a round-off of order ε·kA, so e = |x| − a is known to that, not to ε·e.
  for (double e : {1e-6, 1e-4, 2e-3}) {
    CHECK(close(p.gap(kA + e), e * e / (2 * kR), (kA + e) * e / kR));
    CHECK(close(p.gap(-kA - e), e * e / (2 * kR), (kA + e) * e / kR));
    CHECK(close(p.slope(kA + e), e / kR, (kA + e) / kR));
    CHECK(close(p.slope(-kA - e), -e / kR, (kA + e) / kR));
  }
  CHECK(std::abs(p.lowest_point()) <= kRoundOff * kA);
  const auto k = p.kinks();
  REQUIRE(k.size() == 2);
  CHECK(k[0] == -kA);
  CHECK(k[1] == kA);
}

TEST_CASE("flat: zero on [−b, b], +∞ outside, the corners are kinks and the support's ends") {
  const Profile p(flat(kB));
  CHECK(p.gap(0.0) == 0.0);
  CHECK(p.gap(0.99 * kB) == 0.0);
  CHECK(p.gap(-kB) == 0.0);
  CHECK(p.gap(1.01 * kB) == kInf);
  CHECK(p.gap(-1.01 * kB) == kInf);
  CHECK(p.slope(0.5 * kB) == 0.0);
  CHECK(p.support().first == -kB);
  CHECK(p.support().second == kB);
  const auto k = p.kinks();
  REQUIRE(k.size() == 2);
  CHECK(k[0] == -kB);
  CHECK(k[1] == kB);
  CHECK(std::abs(p.lowest_point()) <= kRoundOff * kB);
}

TEST_CASE("wedge: g0 = |x| tan θ with a kink at the apex") {
  const double m = std::tan(10.0 * std::numbers::pi / 180.0);
  const Profile p(wedge(10.0));
  for (double x : {-1e-3, -1e-6, 0.0, 2e-5, 1e-3}) {
    CHECK(close(p.gap(x), std::abs(x) * m, std::abs(x) * m));
    if (x != 0.0) CHECK(close(p.slope(x), std::copysign(m, x), m));
  }
  CHECK(p.lowest_point() == 0.0);  // the apex is a kink: exact
  const auto k = p.kinks();
  REQUIRE(k.size() == 1);
  CHECK(k[0] == 0.0);
}

TEST_CASE("rounded_wedge: parabolic tip, straight flanks, gap and slope continuous at the tangent point") {
  ProfileSpec s;
  s.type = ProfileType::rounded_wedge;
  s.angle_deg = 5.0;
  s.R = kR;
  const Profile p(s);
  const double m = std::tan(5.0 * std::numbers::pi / 180.0), xt = kR * m;
  CHECK(close(p.gap(0.5 * xt), 0.125 * xt * xt / kR, xt * xt / kR));
  CHECK(close(p.gap(3.0 * xt), 3.0 * xt * m - 0.5 * kR * m * m, 3.0 * xt * m));
  CHECK(close(p.slope(-3.0 * xt), -m, m));
  // Continuity: across ±ε about x_t the gap changes by at most the flank slope times 2ε, and the slope by the
  // parabola's curvature times 2ε (both to round-off): no jump.
  for (double side : {-1.0, 1.0}) {
    const double eps = 1e-9 * xt, x0 = side * xt;
    CHECK(std::abs(p.gap(x0 + eps) - p.gap(x0 - eps)) <= 2.0 * eps * m * (1.0 + 1e-6) + kRoundOff * xt * m);
    CHECK(std::abs(p.slope(x0 + eps) - p.slope(x0 - eps)) <= 2.0 * eps / kR + kRoundOff * m);
    CHECK(close(p.gap(x0), 0.5 * kR * m * m, kR * m * m));
    CHECK(close(p.slope(x0), side * m, m));
  }
  const auto k = p.kinks();
  REQUIRE(k.size() == 2);
  CHECK(close(k[1], xt, xt));
}

TEST_CASE("wavy: g0 = A (1 − cos 2πx/λ), a lone waviness is periodic") {
  const double amp = 1e-6, lambda = 2e-4, k = 2.0 * std::numbers::pi / lambda;
  const Profile p(wavy(amp, lambda));
  for (double x : {0.0, 0.25 * lambda, 0.5 * lambda, 1.3 * lambda, -0.7 * lambda}) {
    CHECK(close(p.gap(x), amp * (1.0 - std::cos(k * x)), 2.0 * amp));
    CHECK(close(p.slope(x), amp * k * std::sin(k * x), amp * k));
  }
  CHECK(p.periodic());
  CHECK_FALSE(p.symmetric_single_zone());
  CHECK(std::abs(p.lowest_point()) <= kMinimumLocation * lambda);
  CHECK(p.kinks().empty());
}

TEST_CASE("table: linear interpolation, segment slopes, +∞ outside, nodes as kinks") {
  ProfileSpec s;
  s.type = ProfileType::table;
  s.x = {-2e-4, -1e-4, 0.0, 1e-4, 3e-4};
  s.h = {4e-6, 1e-6, 0.0, 1e-6, 9e-6};
  const Profile p(s);
  CHECK(close(p.gap(-1.5e-4), 2.5e-6, 1e-5));
  CHECK(close(p.gap(0.5e-4), 0.5e-6, 1e-5));
  CHECK(close(p.gap(2e-4), 5e-6, 1e-5));
  CHECK(close(p.gap(3e-4), 9e-6, 1e-5));
  CHECK(close(p.slope(-1.5e-4), -3e-2, 1e-1));
  CHECK(close(p.slope(2e-4), 4e-2, 1e-1));
  CHECK(p.gap(-2.01e-4) == kInf);
  CHECK(p.gap(3.01e-4) == kInf);
  CHECK(p.support().first == -2e-4);
  CHECK(p.support().second == 3e-4);
  CHECK(p.lowest_point() == 0.0);  // a node: exact
  CHECK(p.kinks().size() == 5);
  CHECK_FALSE(p.symmetric_single_zone());
}

TEST_CASE("sum adds gaps and slopes, envelope takes the lowest term") {
  const double amp = 1e-7, lambda = 5e-5;
  const Profile sum(combine(ProfileType::sum, {cylinder(), wavy(amp, lambda)}));
  const Profile cyl(cylinder()), wav(wavy(amp, lambda));
  for (double x : {-1e-4, 1.3e-5, 2e-4}) {
    CHECK(close(sum.gap(x), cyl.gap(x) + wav.gap(x), 1e-6));
    CHECK(close(sum.slope(x), cyl.slope(x) + wav.slope(x), 1.0));
  }
  CHECK_FALSE(sum.periodic());
  CHECK_FALSE(sum.symmetric_single_zone());

  const double d = 2e-3;
  const Profile env(combine(ProfileType::envelope, {cylinder(kR, -d), cylinder(2 * kR, d)}));
  for (double x : {-2.5e-3, -1e-3, 0.0, 0.5e-3, 2.2e-3}) {
    const double g1 = (x + d) * (x + d) / (2 * kR), g2 = (x - d) * (x - d) / (4 * kR);
    CHECK(close(env.gap(x), std::min(g1, g2), std::max(g1, g2)));
    CHECK(close(env.slope(x), g1 < g2 ? (x + d) / kR : (x - d) / (2 * kR), 1.0));
  }
  CHECK(std::abs(std::abs(env.lowest_point()) - d) <= kMinimumLocation * d);
  CHECK_FALSE(env.symmetric_single_zone());
  CHECK_FALSE(env.periodic());
}

TEST_CASE("offset_x shifts a profile, its lowest point and its kinks") {
  const double x0 = 7e-4;
  const Profile p(cylinder(kR, x0));
  CHECK(close(p.gap(x0 + 1e-4), 1e-8 / (2 * kR), 1e-8 / kR));
  CHECK(std::abs(p.lowest_point() - x0) <= kMinimumLocation * x0);
  CHECK(p.symmetric_single_zone());

  ProfileSpec s = flat(kB);
  s.offset_x = x0;
  const Profile f(s);
  CHECK(close(f.support().first, x0 - kB, x0));
  CHECK(close(f.kinks().back(), x0 + kB, x0));
  CHECK(f.gap(x0 - 1.01 * kB) == kInf);
  CHECK(f.gap(x0 + 0.99 * kB) == 0.0);

  // Offsets compose through sums and envelopes.
  ProfileSpec outer = combine(ProfileType::sum, {flat(kB)});
  outer.terms[0].offset_x = x0;
  outer.offset_x = -x0;
  const Profile o(outer);
  CHECK(close(o.support().first, -kB, x0));
  CHECK(close(o.kinks().front(), -kB, x0));
}

TEST_CASE("tilt_rad lifts the +x side: a tilted cylinder's lowest point is −tilt·R") {
  for (double tilt : {1e-3, -2e-3}) {
    ProfileSpec s = cylinder();
    s.tilt_rad = tilt;
    const Profile p(s);
    const double xl = -tilt * kR;
    CHECK(std::abs(p.lowest_point() - xl) <= kMinimumLocation * std::abs(xl));
    // The normalised gap is the same parabola about the new lowest point.
    // Round-off of the largest term in the sum x²/2R + tilt·x − g_low.
    for (double dx : {-1e-4, 0.0, 5e-5}) {
      const double x = xl + dx;
      CHECK(close(p.gap(x), dx * dx / (2 * kR), x * x / (2 * kR) + std::abs(tilt * x) + tilt * tilt * kR));
    }
    CHECK(close(p.slope(xl + 1e-4), 1e-4 / kR, 1e-4 / kR + std::abs(tilt)));
    CHECK_FALSE(p.symmetric_single_zone());
  }
}

TEST_CASE("a tilted flat punch touches first at its low corner") {
  ProfileSpec s = flat(kB);
  s.tilt_rad = 1e-4;
  const Profile p(s);
  CHECK(std::abs(p.lowest_point() - (-kB)) <= kRoundOff * kB);
  CHECK(p.gap(-kB) == 0.0);
  CHECK(close(p.gap(kB), 2.0 * kB * 1e-4, kB * 1e-4));
  s.tilt_rad = -1e-4;
  CHECK(std::abs(Profile(s).lowest_point() - kB) <= kRoundOff * kB);
}

TEST_CASE("symmetric_single_zone: untilted convex even profiles about one centre") {
  ProfileSpec fr;
  fr.type = ProfileType::flat_rounded;
  fr.a = kA;
  fr.R = kR;
  CHECK(Profile(cylinder()).symmetric_single_zone());
  CHECK(Profile(fr).symmetric_single_zone());
  CHECK(Profile(wedge(10.0)).symmetric_single_zone());
  CHECK(Profile(combine(ProfileType::sum, {cylinder(), wedge(3.0)})).symmetric_single_zone());
  CHECK_FALSE(Profile(flat(kB)).symmetric_single_zone());  // complete contact: no load–size integral
  CHECK_FALSE(Profile(combine(ProfileType::sum, {cylinder(), cylinder(kR, 1e-4)})).symmetric_single_zone());
  CHECK_FALSE(Profile(combine(ProfileType::envelope, {cylinder()})).symmetric_single_zone());
  // A nested sum whose own centre is offset is not symmetric about the outer centre.
  ProfileSpec inner = combine(ProfileType::sum, {cylinder(kR, 1e-4)});
  CHECK(Profile(inner).symmetric_single_zone());
  CHECK_FALSE(Profile(combine(ProfileType::sum, {cylinder(), inner})).symmetric_single_zone());
  // ... and is when both centres agree.
  inner.offset_x = -1e-4;
  CHECK(Profile(combine(ProfileType::sum, {cylinder(), inner})).symmetric_single_zone());
}

TEST_CASE("periodic: a lone waviness, or a sum of them, not once a cylinder is added") {
  CHECK(Profile(wavy(1e-6, 1e-4)).periodic());
  CHECK(Profile(combine(ProfileType::sum, {wavy(1e-6, 1e-4), wavy(1e-7, 3e-5)})).periodic());
  CHECK_FALSE(Profile(combine(ProfileType::sum, {cylinder(), wavy(1e-6, 1e-4)})).periodic());
  CHECK_FALSE(Profile(cylinder()).periodic());
}

TEST_CASE("a tilt steeper than a wedge's flank has no lowest point: InputError naming tilt_rad") {
  ProfileSpec s = wedge(10.0);
  s.tilt_rad = 0.2;  // tan 10° = 0.176
  try {
    const Profile p(s);
    FAIL("no error for a tilt steeper than the flank");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("tilt_rad") != std::string::npos);
  }
  s.tilt_rad = 0.15;  // gentler than the flank: the apex stays the lowest point
  CHECK(std::abs(Profile(s).lowest_point()) <= kMinimumLocation * 1e-3);
  // A tilted lone waviness has no lowest point either.
  ProfileSpec w = wavy(1e-6, 1e-4);
  w.tilt_rad = 1e-3;
  CHECK_THROWS_AS(Profile{w}, InputError);
}
