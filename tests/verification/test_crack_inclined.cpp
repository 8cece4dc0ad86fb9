// The inclined crack (contact/crack_solver.hpp): the general half-plane dislocation kernel against PHYSICS.md's at 90°
// and against the free-surface condition, the coupled solver against the uncoupled one near 90°, mirror symmetry,
// the edge crack in remote tension parallel to the surface with its convergence rate, and the inclined stress line.
#include <cmath>
#include <numbers>
#include <vector>

#include <doctest/doctest.h>

#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/crack_solver.hpp"
#include "common/error.hpp"

using namespace fretwear;
using fretwear::test::rel;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSigma = 1e8;  // Pa
constexpr double kL = 1e-3;     // m

// PHYSICS.md's kernel of the crack normal to the surface (HKDK 1996), written again here from the document.
double physics_kernel(double t, double s) {
  const double u = 2.0 + t + s;
  return 1.0 / (t - s) - 1.0 / u - 2.0 * (1.0 + s) / (u * u) + 4.0 * (1.0 + s) * (1.0 + s) / (u * u * u);
}

// K/(σ√(πl)) of the edge crack at angle α under a remote σxx = σ: σ_n = σ sin²α, τ = σ sin α cos α on its line.
struct Factors {
  double I, II;
};
Factors tension_factors(double angle_deg, int n) {
  const double a = angle_deg * kPi / 180.0, s = std::sin(a), c = std::cos(a);
  const CrackSolver solver({n}, CrackSpec{angle_deg, 0.0});
  const CrackSif r = solver.sif(kL, [&](double) { return kSigma * s * s; }, [&](double) { return kSigma * s * c; });
  const double scale = kSigma * std::sqrt(kPi * kL);
  return {r.K_I / scale, r.K_II / scale};
}

}  // namespace

TEST_CASE("At 90 degrees the general kernel is PHYSICS.md's, and the two modes do not couple") {
  for (double t : {-0.9, -0.3, 0.2, 0.95})
    for (double s : {-0.97, -0.5, 0.1, 0.7, 0.99}) {
      CAPTURE(t);
      CAPTURE(s);
      const CrackKernel k = crack_kernel(90.0, t, s);
      const double want = physics_kernel(t, s);
      CHECK(k[0][0] == rel(want, 1e-12));
      CHECK(k[1][1] == rel(want, 1e-12));
      CHECK(std::abs(k[0][1]) < 1e-13 * std::abs(want));
      CHECK(std::abs(k[1][0]) < 1e-13 * std::abs(want));
    }
}

TEST_CASE("The dislocations leave the free surface traction-free: at the mouth tau/sigma_n = cot(angle)") {
  // At the mouth (t = −1, on y = 0) σyy = σxy = 0, so the tractions on the crack line reduce to σ_n = σxx sin²α and
  // τ = σxx sin α cos α: their ratio is cot α whatever the dislocation. An image term with a wrong sign breaks it.
  for (double angle : {20.0, 45.0, 70.0, 120.0, 160.0})
    for (double s : {-0.6, 0.0, 0.8}) {
      CAPTURE(angle);
      CAPTURE(s);
      const CrackKernel k = crack_kernel(angle, -1.0, s);
      const double cot = 1.0 / std::tan(angle * kPi / 180.0);
      // τ − cot α σ_n = σxy − cot α σyy there; the field's scale at the mouth is 1/(1 + s).
      for (int j = 0; j < 2; ++j) CHECK(std::abs(k[1][j] - cot * k[0][j]) < 1e-12 / (1.0 + s));
    }
}

TEST_CASE("The general kernel has the Cauchy term 1/(t - s) on its diagonal and none off it") {
  // (t − s) k̂ → 1 on the diagonal and → 0 off it as s → t, at any angle: the local field of an edge dislocation.
  for (double angle : {30.0, 60.0, 135.0}) {
    CAPTURE(angle);
    const double t = 0.3, d = 1e-7;
    const CrackKernel k = crack_kernel(angle, t, t - d);
    CHECK(d * k[0][0] == rel(1.0, 1e-5));
    CHECK(d * k[1][1] == rel(1.0, 1e-5));
    CHECK(std::abs(d * k[0][1]) < 1e-5);
    CHECK(std::abs(d * k[1][0]) < 1e-5);
  }
}

TEST_CASE("Just off 90 degrees the coupled 2N system reproduces the uncoupled solver") {
  // The coupling terms are O(90° − α): at 1e-7 degrees off they change K by about 1e-9 relative.
  for (double angle : {90.0 - 1e-7, 90.0 + 1e-7}) {
    const CrackSolver coupled({60}, CrackSpec{angle, 0.0}), normal({60});
    auto load = [](double eta) { return kSigma * (1.0 - 0.7 * eta / kL); };
    auto shear = [](double eta) { return 0.3 * kSigma * eta / kL; };
    const CrackSif a = coupled.sif(kL, load, shear), b = normal.sif(kL, load, shear);
    CHECK(a.K_I_open == rel(b.K_I_open, 1e-7));
    CHECK(a.K_II_open == rel(b.K_II_open, 1e-7));
  }
  // At exactly 90°, a normal load gives no K_II and a shear no K_I (the modes decouple); off 90° they do not.
  const CrackSolver normal({60}), inclined({60}, CrackSpec{60.0, 0.0});
  const CrackSif n = normal.sif(kL, [](double) { return kSigma; }, {});
  const CrackSif s = normal.sif(kL, {}, [](double) { return kSigma; });
  CHECK(n.K_II == 0.0);
  CHECK(s.K_I_open == 0.0);
  CHECK(std::abs(inclined.sif(kL, [](double) { return kSigma; }, {}).K_II) > 1e-3 * kSigma * std::sqrt(kPi * kL));
}

TEST_CASE("A crack leaning the other way is the mirror image: the same K_I, the opposite K_II") {
  for (double angle : {30.0, 45.0, 75.0}) {
    CAPTURE(angle);
    const Factors a = tension_factors(angle, 60), b = tension_factors(180.0 - angle, 60);
    CHECK(b.I == rel(a.I, 1e-12));
    CHECK(b.II == rel(-a.II, 1e-12));
    CHECK(a.II > 0.0);  // τ = σ sin α cos α > 0 ahead of the tip for α < 90°
  }
}

TEST_CASE("Inclined edge crack in remote tension parallel to the surface: second-order convergence to its factors") {
  // Our converged factors K/(σ√(πl)), Richardson-extrapolated from N = 240 and 480 (the last digit is the
  // extrapolation's): 45°: F_I = 0.70491, F_II = 0.36449; 60°: F_I = 0.92010, F_II = 0.30580. At 90° they are
  // PHYSICS.md's 1.121522 and 0. NOTE: a published table for this case (Hasebe and Inohara 1980; HKDK 1996, ch. 4;
  // Murakami 1987) could not be retrieved while this test was written; these values are pinned as regression values
  // and must be checked against one before they are cited as verified.
  struct Case {
    double angle, F_I, F_II;
  };
  for (const Case c : {Case{45.0, 0.70491, 0.36449}, Case{60.0, 0.92010, 0.30580}}) {
    CAPTURE(c.angle);
    std::vector<Factors> F;
    for (int n : {30, 60, 120, 240}) F.push_back(tension_factors(c.angle, n));
    for (std::size_t i = 0; i + 2 < F.size(); ++i) {
      const double order = std::log2((F[i + 1].I - F[i].I) / (F[i + 2].I - F[i + 1].I));
      MESSAGE("angle " << c.angle << ", N = " << (30 << i) << ": F_I = " << F[i].I << ", F_II = " << F[i].II
                       << ", observed order " << order);
      CHECK(order == rel(2.0, 0.1));
    }
    // Error at N = 60 under 1.5/N² relative (observed 0.8/N² at 45°, 1.2/N² at 60°; 0.38/N² at 90°); at 240 within
    // the pinned values' rounding.
    CHECK(F[1].I == rel(c.F_I, 1.5 / (60.0 * 60.0)));
    CHECK(F[1].II == rel(c.F_II, 1.5 / (60.0 * 60.0)));
    CHECK(F[3].I == rel(c.F_I, 5e-5));
    CHECK(F[3].II == rel(c.F_II, 5e-5));
  }
  // Flatter cracks converge more slowly but still converge: 20° at N = 60 and 240 agree to 0.2 %.
  CHECK(tension_factors(20.0, 60).I == rel(tension_factors(20.0, 240).I, 2e-3));
}

TEST_CASE("A bulk tension alone gives the same SIFs through the inclined stress line as the direct loads") {
  const Grid g{-1e-3, 1e-3, 64};
  const std::vector<double> zero(64, 0.0);
  const SurfaceTractions t{g, zero, zero, kSigma};
  const std::vector<double> lengths = {1e-6, 1e-4};
  for (double angle : {45.0, 120.0}) {
    CAPTURE(angle);
    const CrackSolver s({60}, CrackSpec{angle, 0.0});
    const Factors want = tension_factors(angle, 60);
    for (const CrackSif& c : s.solve(t, 0.0, lengths).sifs) {
      const double scale = kSigma * std::sqrt(kPi * c.l);
      CHECK(c.K_I / scale == rel(want.I, 1e-12));
      CHECK(c.K_II / scale == rel(want.II, 1e-12));
    }
  }
}

TEST_CASE("Below a Hertz contact in full sliding: the inclined stress table gives the SIFs of direct evaluation") {
  // The table's Hermite cubics need the derivative along the line, cos α ∂σ/∂x + sin α ∂σ/∂y: a wrong ∂σ/∂x shows.
  const closed_form::Hertz hz = closed_form::hertz(1e5, 1.82e-11, 0.01);
  const int n = 1024;
  const Grid grid{-1.5 * hz.a, 1.5 * hz.a, n};
  std::vector<double> p(n), q(n);
  for (int i = 0; i < n; ++i) {
    p[i] = hz.cell_average(grid.left(i), grid.left(i + 1));
    q[i] = 0.5 * p[i];
  }
  const SurfaceTractions t{grid, p, q, 0.1 * hz.p0};
  const double x_c = -hz.a;
  for (double angle : {45.0, 135.0}) {
    CAPTURE(angle);
    const double a = angle * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    std::vector<double> lengths;
    for (int k = 0; k < 6; ++k) lengths.push_back(hz.a * 0.01 * std::pow(100.0, k / 5.0));
    const CrackSolver solver({60}, CrackSpec{angle, 0.0});
    const CrackResult r = solver.solve(t, x_c, lengths);
    for (std::size_t k = 0; k < lengths.size(); ++k) {
      CAPTURE(lengths[k] / hz.a);
      auto at = [&](double eta) { return stress_at(t, x_c + eta * c, eta * s); };
      const CrackSif d = solver.sif(
          lengths[k],
          [&](double eta) { const Stress x = at(eta); return x.xx * s * s + x.yy * c * c - 2 * x.xy * s * c; },
          [&](double eta) { const Stress x = at(eta); return (x.xx - x.yy) * s * c - x.xy * (c * c - s * s); });
      const double scale = hz.p0 * std::sqrt(kPi * lengths[k]);
      CHECK(std::abs(r.sifs[k].K_I_open - d.K_I_open) < 1e-5 * scale);
      CHECK(std::abs(r.sifs[k].K_II_open - d.K_II_open) < 1e-5 * scale);
    }
  }
}

TEST_CASE("The crack's angle and friction are validated") {
  CHECK(!CrackSpec{14.0, 0.0}.validate().empty());
  CHECK(!CrackSpec{166.0, 0.0}.validate().empty());
  CHECK(!CrackSpec{45.0, -0.1}.validate().empty());
  CHECK(CrackSpec{15.0, 0.0}.validate().empty());
  CHECK_THROWS_AS(CrackSolver({60}, CrackSpec{5.0, 0.0}), InputError);
}
