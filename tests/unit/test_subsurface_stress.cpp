// Subsurface stresses from piecewise-constant cell tractions (contact/subsurface_stress.hpp): the strip loads
// against direct quadrature of Flamant's line loads, Hertz against McEwen's closed form (normal and full sliding),
// the free-surface limits, equilibrium by finite differences, the trailing edge's 2 f p0, the depth table, and the
// principal and von Mises stresses.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/minima.hpp>
#include <doctest/doctest.h>

#include "support.hpp"

#include "contact/closed_form.hpp"
#include "contact/subsurface_stress.hpp"

using namespace fretwear;
using fretwear::test::rel;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kA = 1.82e-11;  // PHYSICS.md's public steel pair (1/Pa)
constexpr double kR = 0.01;      // m
constexpr double kP = 1e5;       // N/m
constexpr double kF = 0.5;
// Adaptive Gauss–Kronrod on the smooth line-load kernels at depth y > 0.
constexpr double kQuadratureTolerance = 1e-11;

// Hertz pressure (cell averages) and full sliding q = f p on n cells over ±1.5 a.
struct HertzLoad {
  closed_form::Hertz hz = closed_form::hertz(kP, kA, kR);
  Grid grid;
  std::vector<double> p, q;
  explicit HertzLoad(int n) : grid{-1.5 * hz.a, 1.5 * hz.a, n}, p(std::size_t(n)), q(std::size_t(n)) {
    for (int i = 0; i < n; ++i) {
      p[i] = hz.cell_average(grid.left(i), grid.left(i + 1));
      q[i] = kF * p[i];
    }
  }
  SurfaceTractions normal() const { return {grid, p, {}, 0.0}; }
  SurfaceTractions sliding() const { return {grid, p, q, 0.0}; }
  SurfaceTractions shear_only() const { return {grid, zeros_, q, 0.0}; }

 private:
  std::vector<double> zeros_ = std::vector<double>(p.size(), 0.0);
};

// McEwen (1949) for the Hertz line contact (Johnson 1985, §4.2 normal, §7.2 sliding), written in our convention:
// y into the specimen, q = q0 √(1 − x²/a²) on the specimen in +x, σxy → −q at the surface. With
// m² = ½[√((a² − x² + y²)² + 4x²y²) + (a² − x² + y²)], n² = ½[√(…) − (a² − x² + y²)], m ≥ 0, sign n = sign x:
//   p: σxx = −(p0/a)[m(1 + (y² + n²)/(m² + n²)) − 2y], σyy = −(p0/a) m(1 − (y² + n²)/(m² + n²)),
//      σxy = −(p0/a) n (m² − y²)/(m² + n²);
//   q: σxx = (q0/a)[n(2 − (y² − m²)/(m² + n²)) − 2x], σyy = −(q0/a) n (m² − y²)/(m² + n²),
//      σxy = −(q0/a)[m(1 + (y² + n²)/(m² + n²)) − 2y].
Stress mcewen(double a, double p0, double q0, double x, double y) {
  const double A = a * a - x * x + y * y, root = std::sqrt(A * A + 4.0 * x * x * y * y);
  const double m = std::sqrt(0.5 * (root + A)), n = std::copysign(std::sqrt(std::max(0.0, 0.5 * (root - A))), x);
  const double d = m * m + n * n;
  Stress s;
  s.xx = -(p0 / a) * (m * (1.0 + (y * y + n * n) / d) - 2.0 * y) + (q0 / a) * (n * (2.0 - (y * y - m * m) / d) - 2.0 * x);
  s.yy = -(p0 / a) * m * (1.0 - (y * y + n * n) / d) - (q0 / a) * n * (m * m - y * y) / d;
  s.xy = -(p0 / a) * n * (m * m - y * y) / d - (q0 / a) * (m * (1.0 + (y * y + n * n) / d) - 2.0 * y);
  return s;
}

double max_difference(const Stress& a, const Stress& b) {
  return std::max({std::abs(a.xx - b.xx), std::abs(a.yy - b.yy), std::abs(a.xy - b.xy)});
}

// Interior points of the Hertz field, in units of a.
const std::vector<std::pair<double, double>> kPoints = {{0.0, 0.2}, {0.0, 0.786}, {-0.7, 0.3}, {0.4, 0.5},
                                                        {-1.2, 0.2}, {1.3, 0.6}, {0.2, 1.5}, {-1.0, 0.1}};

double hertz_error(int n, bool sliding) {
  const HertzLoad L(n);
  const double a = L.hz.a, p0 = L.hz.p0;
  double e = 0.0;
  for (auto [x, y] : kPoints) {
    const Stress got = stress_at(sliding ? L.sliding() : L.normal(), x * a, y * a);
    e = std::max(e, max_difference(got, mcewen(a, p0, sliding ? kF * p0 : 0.0, x * a, y * a)) / p0);
  }
  return e;
}

}  // namespace

TEST_CASE("A uniform strip load equals the integral of Flamant's line loads across it") {
  // Strip [−b, b] of 5 cells carrying p and q; line loads (Johnson 1985, §2.2–2.3): a normal force P at ξ gives
  // σ = −(2P/π)(X²y, y³, Xy²)/r⁴, a tangential force Q (+x) σ = −(2Q/π)(X³, Xy², X²y)/r⁴, X = x − ξ.
  const double b = 1e-4, p = 3e8, q = -1e8;
  const Grid g{-b, b, 5};
  const std::vector<double> P(5, p), Q(5, q);
  const SurfaceTractions t{g, P, Q, 0.0};
  for (auto [x, y] : std::vector<std::pair<double, double>>{{0.0, 0.5}, {-0.9, 0.05}, {2.0, 1.0}, {-3.0, 0.2}}) {
    CAPTURE(x);
    CAPTURE(y);
    x *= b;
    y *= b;
    using boost::math::quadrature::gauss_kronrod;
    auto integral = [&](auto kernel) {
      return gauss_kronrod<double, 31>::integrate(kernel, -b, b, 15, kQuadratureTolerance);
    };
    auto r4 = [&](double xi) { const double r2 = (x - xi) * (x - xi) + y * y; return r2 * r2; };
    const double c = -2.0 / kPi;
    const double xx = integral([&](double xi) { const double X = x - xi; return c * (p * X * X * y + q * X * X * X) / r4(xi); });
    const double yy = integral([&](double xi) { const double X = x - xi; return c * (p * y * y * y + q * X * y * y) / r4(xi); });
    const double xy = integral([&](double xi) { const double X = x - xi; return c * (p * X * y * y + q * X * X * y) / r4(xi); });
    const Stress s = stress_at(t, x, y);
    const double scale = std::abs(p) + std::abs(q);
    CHECK(std::abs(s.xx - xx) < 1e-10 * scale);
    CHECK(std::abs(s.yy - yy) < 1e-10 * scale);
    CHECK(std::abs(s.xy - xy) < 1e-10 * scale);
  }
}

TEST_CASE("Hertz pressure: McEwen's stresses on the axis, sigma_yy = -p0 a/sqrt(a^2+y^2)") {
  const HertzLoad L(2048);
  const double a = L.hz.a, p0 = L.hz.p0;
  for (double u : {0.1, 0.5, 1.0, 3.0}) {
    const double y = u * a, r = std::sqrt(a * a + y * y);
    const Stress s = stress_at(L.normal(), 0.0, y);
    // Cell averages of the pressure: the error is O(h²) (next test); at 2048 cells it is 2e-7 p0.
    CHECK(s.yy == rel(-p0 * a / r, 1e-6));
    CHECK(s.xx == rel(-p0 * ((a * a + 2 * y * y) / r - 2 * y) / a, 1e-5));
    CHECK(std::abs(s.xy) < 1e-12 * p0);
  }
}

TEST_CASE("Hertz normal and full sliding: McEwen's field everywhere, converging as h^2") {
  for (bool sliding : {false, true}) {
    CAPTURE(sliding);
    const double e1 = hertz_error(512, sliding), e2 = hertz_error(1024, sliding), e3 = hertz_error(2048, sliding);
    const double order = std::log2(e2 / e3);
    MESSAGE("max error / p0 at 512, 1024, 2048 cells: " << e1 << ", " << e2 << ", " << e3 << "; order " << order);
    // Cell averages of a smooth load: O((h/a)²), observed 1.6 (h/a)² at 2048 cells over ±1.5 a.
    const double h_over_a = 3.0 / 2048;
    CHECK(e3 < 4.0 * h_over_a * h_over_a);
    CHECK(std::log2(e1 / e2) > 1.8);
    CHECK(order > 1.8);
  }
}

TEST_CASE("Free surface: sigma_yy -> -p and sigma_xy -> -q approaching a cell centre") {
  const HertzLoad L(256);
  const SurfaceTractions t = L.sliding();
  const double h = L.grid.h();
  for (int i : {60, 100, 128, 200}) {  // inside the contact (cells 43–212)
    CAPTURE(i);
    const double x = L.grid.x(i);
    const Stress s0 = stress_at(t, x, 0.0);
    CHECK(s0.yy == rel(-L.p[i], 1e-12));
    CHECK(s0.xy == rel(-L.q[i], 1e-12));
    // From inside: ∂σyy/∂y = ∂q/∂x = 0 within a cell, so σyy + p = O(y²); σxy + q = O(y) (scale: the half cell
    // to the next jump).
    const double e1 = std::abs(stress_at(t, x, 1e-2 * h).yy + L.p[i]);
    const double e2 = std::abs(stress_at(t, x, 1e-3 * h).yy + L.p[i]);
    CHECK(e1 < 1e-3 * L.hz.p0);
    CHECK(e2 < 0.02 * e1);
    const double f1 = std::abs(stress_at(t, x, 1e-2 * h).xy + L.q[i]);
    const double f2 = std::abs(stress_at(t, x, 1e-3 * h).xy + L.q[i]);
    CHECK(f1 < 1e-1 * L.hz.p0);
    CHECK(f2 == rel(0.1 * f1, 0.05));
  }
  // Outside the contact the surface is traction-free.
  const Stress out = stress_at(t, 1.3 * L.hz.a, 0.0);
  CHECK(std::abs(out.yy) < 1e-9 * L.hz.p0);
  CHECK(std::abs(out.xy) < 1e-9 * L.hz.p0);
}

TEST_CASE("Equilibrium: d(sxx)/dx + d(sxy)/dy = 0 and d(sxy)/dx + d(syy)/dy = 0 by central differences") {
  const HertzLoad L(128);
  const SurfaceTractions t{L.grid, L.p, L.q, 2e8};
  const double a = L.hz.a;
  for (auto [x, y] : kPoints) {
    CAPTURE(x);
    CAPTURE(y);
    x *= a;
    y *= a;
    const double d = 1e-4 * y;  // central differences: error O(d² ∂³σ) ~ (d/y)² relative
    const Stress xp = stress_at(t, x + d, y), xm = stress_at(t, x - d, y);
    const Stress yp = stress_at(t, x, y + d), ym = stress_at(t, x, y - d);
    const double sxx_x = (xp.xx - xm.xx) / (2 * d), sxy_y = (yp.xy - ym.xy) / (2 * d);
    const double sxy_x = (xp.xy - xm.xy) / (2 * d), syy_y = (yp.yy - ym.yy) / (2 * d);
    const double scale1 = std::abs(sxx_x) + std::abs(sxy_y), scale2 = std::abs(sxy_x) + std::abs(syy_y);
    CHECK(std::abs(sxx_x + sxy_y) < 1e-6 * scale1);
    CHECK(std::abs(sxy_x + syy_y) < 1e-6 * scale2);
  }
}

TEST_CASE("Full sliding: the surface sigma_xx peaks at 2 f p0 at the trailing edge x = -a, as h^(1/2)") {
  // Surface, full sliding: σxx = −p − (2/π) PV∫ q/(x − ξ) dξ = −p0√(1 − x²/a²) − 2 f p0 x/a inside and
  // (2 f p0/a)(|x| − √(x² − a²)) behind the contact: the maximum is 2 f p0 at x = −a. The edge's square root makes
  // the cell-average error O(h^{1/2}) there, so the peak converges at order ½ and Richardson at order ½ applies.
  auto peak = [](int n) {
    const HertzLoad L(n);
    const double a = L.hz.a, h = L.grid.h();
    double best = -1e300;
    for (int k = -64; k <= 64; ++k) best = std::max(best, stress_at(L.sliding(), -a + (k + 0.01) * h / 8, 0.0).xx);
    return best / (kF * L.hz.p0);
  };
  const double m1 = peak(1024), m2 = peak(4096);
  const double order = std::log2((2.0 - m1) / (2.0 - m2)) / 2.0;  // h ratio 4
  const double extrapolated = 2.0 * m2 - m1;                       // (4^{1/2} m2 − m1)/(4^{1/2} − 1)
  MESSAGE("peak / (f p0) at 1024, 4096 cells: " << m1 << ", " << m2 << "; order " << order
                                               << "; extrapolated " << extrapolated);
  CHECK(m2 < 2.0);
  CHECK(order == rel(0.5, 0.1));
  CHECK(extrapolated == rel(2.0, 1e-3));
}

TEST_CASE("stress_along_line is stress_at at each point of the line, and stress_along_depth at 90 degrees") {
  const HertzLoad L(1024);
  const SurfaceTractions t{L.grid, L.p, L.q, 1e8};
  const double a = L.hz.a, x = -0.93 * a;
  std::vector<double> r;
  for (int k = 0; k < 50; ++k) r.push_back(1.5 * a * std::pow(k / 49.0, 2.5));
  const std::vector<Stress> depth = stress_along_depth(t, x, r), normal = stress_along_line(t, x, 90.0, r);
  for (std::size_t k = 0; k < r.size(); ++k) CHECK(max_difference(normal[k], depth[k]) == 0.0);
  for (const double angle : {30.0, 135.0}) {
    CAPTURE(angle);
    const std::vector<Stress> line = stress_along_line(t, x, angle, r);
    const double c = std::cos(angle * kPi / 180.0), sn = std::sin(angle * kPi / 180.0);
    for (std::size_t k = 0; k < r.size(); k += 7)
      CHECK(max_difference(line[k], stress_at(t, x + c * r[k], sn * r[k])) < 1e-12 * L.hz.p0);
  }
  // stress_along_depth is stress_at, depth by depth.
  for (std::size_t k = 0; k < r.size(); k += 7) CHECK(max_difference(depth[k], stress_at(t, x, r[k])) == 0.0);
}

TEST_CASE("Principal stresses: invariants, and Hertz's largest shear 0.30 p0 at 0.786 a on the axis") {
  const Stress s{3e8, -1e8, 1.5e8};
  const Principal pr = principal(s);
  CHECK(pr.s1 + pr.s2 == rel(s.xx + s.yy, 1e-14));
  CHECK(pr.s1 * pr.s2 == rel(s.xx * s.yy - s.xy * s.xy, 1e-14));
  // σ1 acts along (cos α, sin α): the traction on that plane is σ1 times the normal.
  const double c = std::cos(pr.angle), sn = std::sin(pr.angle);
  CHECK(s.xx * c + s.xy * sn == rel(pr.s1 * c, 1e-14));
  CHECK(s.xy * c + s.yy * sn == rel(pr.s1 * sn, 1e-12));

  // On the axis (σxy = 0) τ1 = (σxx − σyy)/2 = (p0/a)(y − y²/√(a² + y²)) from McEwen; Johnson (1985, §4.2):
  // τ1 max = 0.300 p0 at y = 0.786 a.
  const HertzLoad L(2048);
  const double a = L.hz.a, p0 = L.hz.p0;
  auto tau = [&](double u) { return u - u * u / std::sqrt(1.0 + u * u); };
  const auto [u_max, neg] = boost::math::tools::brent_find_minima([&](double u) { return -tau(u); }, 0.1, 2.0, 40);
  CHECK(u_max == rel(0.786, 1e-3));
  CHECK(-neg == rel(0.300, 2e-3));
  const Principal at = principal(stress_at(L.normal(), 0.0, u_max * a));
  CHECK(0.5 * (at.s1 - at.s2) == rel(-neg * p0, 1e-6));
}

TEST_CASE("Von Mises in plane strain") {
  constexpr double s = 2e8;
  CHECK(von_mises({s, 0.0, 0.0}, 0.0) == rel(s, 1e-15));                  // uniaxial, σzz = 0
  CHECK(von_mises({0.0, 0.0, s}, 0.3) == rel(std::sqrt(3.0) * s, 1e-15));  // pure shear
  CHECK(von_mises({s, s, 0.0}, 0.5) < 1e-6);                               // hydrostatic when ν = ½
  // σxx = s, σyy = −s, ν: σzz = 0, so σ_vm = √(½(4 + 1 + 1)) s = √3 s.
  CHECK(von_mises({s, -s, 0.0}, 0.3) == rel(std::sqrt(3.0) * s, 1e-15));
  // Hertz on the axis: the field's σ_vm equals the one built from McEwen's components.
  const HertzLoad L(2048);
  const double a = L.hz.a, p0 = L.hz.p0;
  for (double u : {0.3, 0.7, 1.2}) {
    CHECK(von_mises(stress_at(L.normal(), 0.0, u * a), 0.3) ==
          rel(von_mises(mcewen(a, p0, 0.0, 0.0, u * a), 0.3), 1e-5));
  }
}
