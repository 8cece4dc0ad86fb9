// The displacement datum (contact/reference_datum.hpp): the line-load displacements against Hooke's law and Flamant's
// stresses, the cell-integrated weights against direct quadrature of the line-load solution, and the surface limit
// against the half-plane kernel (the same datum length L).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "support.hpp"

#include "contact/elastic_pair.hpp"
#include "common/error.hpp"
#include "contact/grid.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/reference_datum.hpp"

using namespace fretwear;

namespace {

// Central differences of a field that varies on the scale of r: step 1e-5 r leaves a truncation error of ~1e-10 r²
// times the third derivative and a round-off of ~1e-16/1e-5: both far below kHooke.
constexpr double kHooke = 1e-6;
// Composite 5-point Gauss–Legendre on 64 panels against the closed-form cell integrals: round-off bound.
constexpr double kQuadrature = 1e-11;

struct Flamant {
  double xx, yy, xy;
};

// Johnson (1985) eqs 2.15 and 2.20 in Cartesian form: F in +x, P in +y (into the body y > 0), at the origin.
Flamant flamant(double x, double y, double F, double P) {
  const double r4 = std::pow(x * x + y * y, 2), c = -2.0 / std::numbers::pi;
  return {c * (F * x * x * x + P * x * x * y) / r4, c * (F * x * y * y + P * y * y * y) / r4,
          c * (F * x * x * y + P * x * y * y) / r4};
}

double gauss_legendre(double a, double b, const auto& f) {
  constexpr double z[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
  constexpr double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                           0.2369268850561891};
  constexpr int kPanels = 64;
  double sum = 0.0;
  const double hp = (b - a) / kPanels;
  for (int k = 0; k < kPanels; ++k) {
    const double m = a + (k + 0.5) * hp;
    for (int i = 0; i < 5; ++i) sum += w[i] * 0.5 * hp * f(m + 0.5 * hp * z[i]);
  }
  return sum;
}

}  // namespace

TEST_CASE("reference datum: the line-load displacements satisfy Hooke's law with Flamant's stresses") {
  const double E = 200e9, nu = 0.3, mu = E / (2.0 * (1.0 + nu)), L = 0.02;
  for (PlaneState plane : {PlaneState::strain, PlaneState::stress}) {
    const double kappa = plane == PlaneState::strain ? 3.0 - 4.0 * nu : (3.0 - nu) / (1.0 + nu);
    for (auto [F, P] : {std::pair{1e4, 0.0}, std::pair{0.0, 1e4}, std::pair{3e3, -7e3}}) {
      for (auto [x, y] : {std::pair{3e-4, 7e-4}, std::pair{-5e-4, 2e-4}, std::pair{1.2e-3, 2e-3}}) {
        CAPTURE(F);
        CAPTURE(P);
        CAPTURE(x);
        CAPTURE(y);
        const double e = 1e-5 * std::hypot(x, y);
        auto u = [&](double xx, double yy) { return line_load_displacement(xx, yy, F, P, mu, kappa, L); };
        const double exx = (u(x + e, y).ux - u(x - e, y).ux) / (2 * e);
        const double eyy = (u(x, y + e).uy - u(x, y - e).uy) / (2 * e);
        const double gxy = (u(x, y + e).ux - u(x, y - e).ux + u(x + e, y).uy - u(x - e, y).uy) / (2 * e);
        const Flamant s = flamant(x, y, F, P);
        // Hooke in κ form, plane strain and plane stress alike: 8μ ε_xx = (κ + 1) σ_xx − (3 − κ) σ_yy.
        CHECK(exx == test::rel(((kappa + 1) * s.xx - (3 - kappa) * s.yy) / (8 * mu), kHooke));
        CHECK(eyy == test::rel(((kappa + 1) * s.yy - (3 - kappa) * s.xx) / (8 * mu), kHooke));
        CHECK(gxy == test::rel(s.xy / mu, kHooke));
      }
    }
    // On the surface the tangential load gives the kernel's −(F/π)(κ + 1)/(4μ) ln(|x|/L) (Johnson eq 2.21a).
    const double x = 4e-4, F = 1e4;
    CHECK(line_load_displacement(x, 1e-14, F, 0.0, mu, kappa, L).ux ==
          test::rel(-F / std::numbers::pi * (kappa + 1) / (4 * mu) * std::log(x / L), 1e-9));
  }
}

TEST_CASE("reference datum: the cell weights are the line-load solution integrated over each cell") {
  const Grid grid{-3e-4, 5e-4, 64};
  const double L = grid.width();
  for (auto [pad, spec] : {std::pair{Material{200e9, 0.3}, Material{200e9, 0.3}},
                           std::pair{Material{70e9, 0.33}, Material{200e9, 0.3}}}) {
    const ElasticPair pair(pad, spec, PlaneState::strain);
    for (double d : {2e-5, 1e-3}) {
      const double x_c = 1.1e-4;
      const ReferenceDatum datum(grid, pair, x_c, d);
      CAPTURE(d);
      CAPTURE(pad.E);
      for (int j : {0, 20, 33, 63}) {
        CAPTURE(j);
        // D = u_pad(x_c, −d) − u_spec(x_c, d); the pad is the mirror image of a half-plane loaded by −q and p.
        auto shear = [&](double xi) {
          return line_load_displacement(x_c - xi, d, -1.0, 0.0, pair.mu_pad(), pair.kappa_pad(), L).ux -
                 line_load_displacement(x_c - xi, d, 1.0, 0.0, pair.mu_specimen(), pair.kappa_specimen(), L).ux;
        };
        auto pressure = [&](double xi) {
          return line_load_displacement(x_c - xi, d, 0.0, 1.0, pair.mu_pad(), pair.kappa_pad(), L).ux -
                 line_load_displacement(x_c - xi, d, 0.0, 1.0, pair.mu_specimen(), pair.kappa_specimen(), L).ux;
        };
        const double g = gauss_legendre(grid.left(j), grid.left(j + 1), shear) / grid.h();
        CHECK(datum.shear_weights()[j] == test::rel(g, kQuadrature));
        const double e = gauss_legendre(grid.left(j), grid.left(j + 1), pressure) / grid.h();
        if (pair.similar()) {
          CHECK(datum.pressure_weights()[j] == 0.0);
          CHECK(std::abs(e) < 1e-15 * std::abs(g));
        } else {
          // e is odd about x_c and passes through zero there: compare against the largest weight, not e itself.
          double scale = 0.0;
          for (double v : datum.pressure_weights()) scale = std::max(scale, std::abs(v));
          CHECK(std::abs(datum.pressure_weights()[j] - e) < kQuadrature * scale);
        }
      }
      // relative_displacement is h Σ (g q + e p).
      std::vector<double> q(grid.n), p(grid.n);
      double want = 0.0;
      for (int j = 0; j < grid.n; ++j) {
        q[j] = 1e6 * std::sin(0.3 * j), p[j] = 2e6 + 1e5 * j;
        want += grid.h() * (datum.shear_weights()[j] * q[j] + datum.pressure_weights()[j] * p[j]);
      }
      CHECK(datum.relative_displacement(q, p) == test::rel(want, 1e-12));
    }
  }
}

TEST_CASE("reference datum: at vanishing depth the shear weights are the half-plane kernel's (the same datum L)") {
  const Grid grid{-2e-4, 2e-4, 128};
  const ElasticPair pair({200e9, 0.3}, {200e9, 0.3}, PlaneState::strain);
  const HalfPlaneKernel kernel(grid, pair.A());
  const int i = 77;
  // u_spec − u_pad at a surface cell centre is (K q)_i: D = −K q as d → 0 (to O(d/h)).
  const ReferenceDatum datum(grid, pair, grid.x(i), 1e-9 * grid.h());
  for (int j : {0, 40, 76, 77, 78, 127}) {
    CAPTURE(j);
    CHECK(grid.h() * datum.shear_weights()[j] == test::rel(-kernel.coefficient(grid.x(i) - grid.x(j)), 1e-7));
  }
  CHECK_THROWS_AS(ReferenceDatum(grid, pair, 0.0, 0.0), InputError);
}

TEST_CASE("reference datum: the closed-form stuck compliance of Hertz is the datum of q = Q/(pi sqrt(a^2 - x^2))") {
  // λ = −(A Q/π) ln(a/(2L)) on the contact, plus D of the flat-punch shear distribution by quadrature (x = a sin θ).
  const double E = 200e9, nu = 0.3, mu = E / (2 * (1 + nu)), kappa = 3 - 4 * nu, A = 4 * (1 - nu * nu) / E;
  const double a = 1e-4, L = 3e-3, Q = 1.0;
  for (double d : {0.3 * a, a, 10 * a}) {
    CAPTURE(d / a);
    const double lambda = -(A * Q / std::numbers::pi) * std::log(a / (2 * L));
    const double D = gauss_legendre(-0.5 * std::numbers::pi, 0.5 * std::numbers::pi, [&](double t) {
      const double q = Q / std::numbers::pi;  // q dx = Q/(π a cos θ) · a cos θ dθ
      return -2.0 * q * line_load_displacement(-a * std::sin(t), d, 1.0, 0.0, mu, kappa, L).ux;
    });
    CHECK(lambda + D == test::rel(Q * hertz_stuck_compliance(A, mu, a, d), kQuadrature));
  }
}
