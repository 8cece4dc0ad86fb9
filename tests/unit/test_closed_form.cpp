// The closed forms the solver is verified against (contact/closed_form.hpp): the rounded punch against PHYSICS.md's
// table, its Hertz limit, and cell averages that integrate to the load.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <doctest/doctest.h>

#include "contact/closed_form.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// PHYSICS.md prints the table to 6 decimals (x/b of the peak to 4): the closed form must agree to half a unit in
// the last printed digit.
constexpr double kTableDigit = 0.5e-6;
constexpr double kTablePeakXDigit = 0.5e-4;
// The root finds (toms748 to 52 bits) and the closed forms cost a few ulps; with the cancellation in D(φ0) near
// φ0 → π/2 (D ~ (π/2 − φ0)³) a few hundred ulps of relative error remain.
constexpr double kRootTolerance = 1e-12;
// Adaptive Gauss–Kronrod on a bounded integrand with the log-type kink at x = a as a breakpoint.
constexpr double kQuadratureTolerance = 1e-10;

constexpr double kA = 1.82e-11;  // PHYSICS.md's public steel pair (1/Pa)
constexpr double kR = 0.01;      // m

struct Row {
  double a_over_b, PAR_a2, PAR_b2, pmax_b_P, x_over_b;
};
constexpr Row kTable[] = {
    {0.25, 17.216874, 1.076055, 0.610540, 0.4249},
    {0.5, 2.456739, 0.614185, 0.670453, 0.6369},
    {0.75, 0.402944, 0.226656, 0.870333, 0.8234},
    {0.9, 0.072501, 0.058726, 1.316371, 0.9301},
};

// The load that gives contact half-width b for flat half-length a = (a/b) b, from P A R / b² = D(φ0)/2.
double load_for(double a_over_b, double b) {
  return 0.5 * closed_form::D(std::asin(a_over_b)) * b * b / (kA * kR);
}

}  // namespace

TEST_CASE("rounded punch: P A R / a², P A R / b², p_max b / P and its x / b match PHYSICS.md's table") {
  const double b = 0.2e-3;
  for (const Row& row : kTable) {
    CAPTURE(row.a_over_b);
    const double a = row.a_over_b * b;
    const double P = load_for(row.a_over_b, b);
    const auto rp = closed_form::rounded_punch(P, kA, a, kR);
    // The root find of eq 3 (in its P A R / a² form) returns the half-width eq 3's b² form was set up with.
    CHECK(std::abs(rp.b / b - 1.0) <= kRootTolerance);
    CHECK(std::abs(std::sin(rp.phi0) - row.a_over_b) <= kRootTolerance);
    CHECK(std::abs(P * kA * kR / (a * a) - row.PAR_a2) <= kTableDigit);
    CHECK(std::abs(P * kA * kR / (b * b) - row.PAR_b2) <= kTableDigit);
    CHECK(std::abs(rp.peak() * b / P - row.pmax_b_P) <= kTableDigit);
    CHECK(std::abs(rp.peak_x() / b - row.x_over_b) <= kTablePeakXDigit);
  }
}

TEST_CASE("rounded punch: the pressure of eq 4 carries the load and is continuous at the end of the flat") {
  for (const Row& row : kTable) {
    CAPTURE(row.a_over_b);
    const double b = 1e-3, a = row.a_over_b * b;
    const double P = load_for(row.a_over_b, b);
    const auto rp = closed_form::rounded_punch(P, kA, a, kR);
    // P = 2 ∫_0^b p dx = 2 b ∫_0^{π/2} p(b sin φ) cos φ dφ, split at φ0.
    auto f = [&](double phi) { return rp.pressure(rp.b * std::sin(phi)) * std::cos(phi); };
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    const double load = 2.0 * rp.b * (GK::integrate(f, 0.0, rp.phi0, 15, 1e-14) +
                                      GK::integrate(f, rp.phi0, 0.5 * kPi, 15, 1e-14));
    CHECK(std::abs(load / P - 1.0) <= kQuadratureTolerance);
    // B(φ0; φ0) uses the cancelled-log form; it must join the general form on both sides.
    const double p_a = rp.pressure(a);
    for (double s : {-1e-9, 1e-9}) CHECK(std::abs(rp.pressure(a * (1.0 + s)) / p_a - 1.0) <= 1e-6);
    CHECK(rp.pressure(rp.b) == 0.0);
    CHECK(rp.pressure(-0.3 * rp.b) == rp.pressure(0.3 * rp.b));
  }
}

// With corners of a few parts in a million of the flat the peak is a spike b − a wide at the end of the flat: it is
// found there, above every pressure sampled across the contact at any density (a search over [0, b] alone settled
// inside the flat at R = 1e-9 m, a = 0.25 mm: 43 % low).
TEST_CASE("rounded punch: a sharp corner's peak is found in its spike at the end of the flat") {
  for (const double R : {1e-9, 1e-8, 1e-7}) {
    CAPTURE(R);
    const double a = 2.5e-4, P = 843660.37;
    const auto rp = closed_form::rounded_punch(P, kA, a, R);
    const double x = rp.peak_x(), peak = rp.peak();
    CHECK(x > a);
    CHECK(x < rp.b);
    double sampled = 0.0;  // every pressure on 10^6 points between a − (b − a) and b
    for (int k = 0; k <= 1000000; ++k)
      sampled = std::max(sampled, rp.pressure(a - (rp.b - a) + 2.0 * (rp.b - a) * k / 1e6));
    CHECK(peak >= sampled);
    CHECK(peak <= sampled * (1.0 + 1e-6));
  }
}

TEST_CASE("rounded punch → Hertz as a → 0: b/a_H − 1 ≈ (2/π)(a/a_H), p → Hertz") {
  // D(φ0) = π − 4φ0 + O(φ0³) and b² = 2 P A R / D, so b/a_H = 1 + (2/π) φ0 + O(φ0²) with φ0 ≈ a/a_H: the error
  // falls linearly, and (b/a_H − 1)/(a/a_H) tends to 2/π with an O(a/a_H) remainder.
  const double P = 1e5;
  const auto hz = closed_form::hertz(P, kA, kR);
  double previous_pressure_error = kPi;
  for (double ratio : {1e-2, 1e-3, 1e-4}) {
    CAPTURE(ratio);
    const auto rp = closed_form::rounded_punch(P, kA, ratio * hz.a, kR);
    const double slope = (rp.b / hz.a - 1.0) / ratio;
    CHECK(std::abs(slope - 2.0 / kPi) <= 2.0 * ratio);
    // The pressure converges to Hertz's like a/a_H (with a log factor from B's log terms): check it at least
    // halves per decade and ends below 1e-3 p0 at a/a_H = 1e-4.
    double err = 0.0;
    for (double s : {0.0, 0.3, 0.6, 0.9}) err = std::max(err, std::abs(rp.pressure(s * hz.a) - hz.pressure(s * hz.a)));
    err /= hz.p0;
    CHECK(err < 0.5 * previous_pressure_error);
    previous_pressure_error = err;
  }
  CHECK(previous_pressure_error < 1e-3);
}

TEST_CASE("cell averages of the flat punch and of Hertz integrate to the load") {
  // The averages are differences of an antiderivative, so their sum telescopes: the load to round-off, even with
  // the flat punch's inverse-square-root singularities in the end cells.
  const double P = 3e5, b = 0.5e-3;
  const auto fp = closed_form::flat_punch(P, b);
  const auto hz = closed_form::hertz(P, kA, kR);
  for (int n : {8, 64, 1000}) {
    CAPTURE(n);
    double load_flat = 0.0, load_hertz = 0.0;
    const double h = 2.0 * b / n, hh = 3.0 * hz.a / n;
    for (int i = 0; i < n; ++i) {
      load_flat += h * fp.cell_average(-b + i * h, -b + (i + 1) * h);
      load_hertz += hh * hz.cell_average(-1.5 * hz.a + i * hh, -1.5 * hz.a + (i + 1) * hh);
    }
    CHECK(std::abs(load_flat / P - 1.0) <= 8.0 * n * kEps);
    CHECK(std::abs(load_hertz / P - 1.0) <= 8.0 * n * kEps);
  }
  // Away from the corners a small cell's average is the point value: p = P / (π √(b² − x²)).
  // The midpoint rule's error is p''·h²/24 relative ~ (h/b)² (here h/b = 4e-6), far below the asin differences'
  // cancellation error ε·b/h ~ 1e-10.
  CHECK(std::abs(fp.cell_average(0.3 * b - 1e-9, 0.3 * b + 1e-9) / fp.pressure(0.3 * b) - 1.0) <= 1e-9);
  CHECK(std::abs(fp.pressure(0.0) / (P / (kPi * b)) - 1.0) <= 4.0 * kEps);
  CHECK(fp.pressure(1.1 * b) == 0.0);
}

TEST_CASE("stick zones: the rounded punch's eq 9 gives PHYSICS.md's c/b, Hertz c/a = √(1 − Q/fP), e/a = σ/(4fp0)") {
  // PHYSICS.md's table: c/b at Q/fP = 0.2, 0.5, 0.8 for a/b = 0.25, 0.5, 0.75, 0.9.
  const double want[4][3] = {{0.913933, 0.762002, 0.554325},
                             {0.938398, 0.831044, 0.688676},
                             {0.967249, 0.911177, 0.839268},
                             {0.986460, 0.963558, 0.934753}};
  const double ratios[3] = {0.2, 0.5, 0.8};
  const double b = 0.2e-3;
  for (int i = 0; i < 4; ++i) {
    const auto rp = closed_form::rounded_punch(load_for(kTable[i].a_over_b, b), kA, kTable[i].a_over_b * b, kR);
    for (int k = 0; k < 3; ++k) {
      CAPTURE(kTable[i].a_over_b);
      CAPTURE(ratios[k]);
      CHECK(std::abs(closed_form::rounded_punch_stick(rp, ratios[k]) / b - want[i][k]) <= kTableDigit);
    }
    CHECK(closed_form::rounded_punch_stick(rp, 0.0) == rp.b);  // no load: all stick
    CHECK(closed_form::rounded_punch_stick(rp, 1.0) == rp.a);  // sliding: the stick zone shrinks to the flat
  }
  // PHYSICS.md's Nowell–Hills case: Q/fP = 0.5, σ/(f p0) = 0.6 gives e/a = 0.15, stick zone [−0.557107, 0.857107] a.
  const auto h = closed_form::hertz(1e5, kA, kR);
  const double f = 0.5;
  const auto z = closed_form::hertz_stick(h, 0.5, f, 0.6 * f * h.p0);
  CHECK(z.centre / h.a == test::rel(0.15, 1e-12));
  CHECK((z.centre - z.c) / h.a == test::rel(-0.557107, 1e-6));
  CHECK((z.centre + z.c) / h.a == test::rel(0.857107, 1e-6));
}
