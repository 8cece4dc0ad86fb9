// The Dundurs-β coupling kernel (contact/coupling_kernel.hpp): its cell coefficients against direct integration of
// the step kernel, the running-sum product against the dense matrix, second-order agreement with the continuous
// coupling of a smooth traction, and its signs against the half-plane line-load solutions of reference_datum.hpp
// (Johnson 1985 eqs 2.19 and 2.21), which were written independently of it.
#include <cmath>
#include <random>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <doctest/doctest.h>
#include <fmt/format.h>

#include "support.hpp"

#include "contact/coupling_kernel.hpp"
#include "contact/elastic_pair.hpp"
#include "contact/reference_datum.hpp"

using namespace fretwear;

namespace {
// (1/2) ∫ t(ξ) sgn(x − ξ) dξ over [lo, hi] by Gauss–Kronrod, split at x where the kernel jumps.
template <class T>
double step_integral(T t, double x, double lo, double hi) {
  using boost::math::quadrature::gauss_kronrod;
  double below = 0.0, above = 0.0;
  if (x > lo) below = gauss_kronrod<double, 31>::integrate(t, lo, std::min(x, hi), 10, 1e-14);
  if (x < hi) above = gauss_kronrod<double, 31>::integrate(t, std::max(x, lo), hi, 10, 1e-14);
  return 0.5 * (below - above);
}
}  // namespace

TEST_CASE("coupling kernel: the cell coefficients are the integral of the step kernel over the cell") {
  const Grid grid{-1e-3, 2e-3, 40};
  const CouplingKernel S(grid);
  const double h = grid.h();
  for (int j : {0, 7, 20, 39}) {
    for (double x : {grid.x(j), grid.x(j) + 0.3 * h, grid.x(j) - 0.45 * h, grid.x(3), grid.x(35), -2e-3, 3e-3}) {
      CAPTURE(j);
      CAPTURE(x);
      const double want = step_integral([](double) { return 1.0; }, x, grid.left(j), grid.left(j) + h);
      if (want == 0.0) {
        CHECK(S.coefficient(x, j) == 0.0);
      } else {
        CHECK(S.coefficient(x, j) == test::rel(want, 1e-12));
      }
    }
  }
  // At the centres: (h/2) sgn(i − j), antisymmetric.
  for (int i = 0; i < grid.n; i += 3)
    for (int j = 0; j < grid.n; j += 2) {
      if (i != j) CHECK(S.coefficient(grid.x(i), j) == test::rel(S.matrix(i, j), 1e-9));
      CHECK(S.matrix(i, j) == -S.matrix(j, i));
    }
  CHECK(S.matrix(5, 4) == test::rel(0.5 * h, 1e-15));
}

TEST_CASE("coupling kernel: the running-sum product equals the dense product") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {1, 2, 17, 256}) {
    const Grid grid{-0.5e-3, 0.5e-3, n};
    const CouplingKernel S(grid);
    std::vector<double> t(n), got(n);
    for (double& v : t) v = 1e8 * u(rng);
    const double scale = -3.7e-12;
    S.apply(t, got, scale);
    double worst = 0.0, size = 0.0;
    for (int i = 0; i < n; ++i) {
      double want = 0.0;
      for (int j = 0; j < n; ++j) want += scale * S.matrix(i, j) * t[j];
      worst = std::max(worst, std::abs(got[i] - want));
      size = std::max(size, std::abs(want));
    }
    CAPTURE(n);
    CHECK(worst <= 1e-13 * size);
  }
}

TEST_CASE("coupling kernel: cell averages of a smooth traction give its continuous coupling to second order") {
  // t = √(1 − ξ²/a²) on |ξ| < a (the Hertz shape): S t̄ at the centres against (1/2) ∫ t sgn(x − ξ) dξ.
  const double a = 1e-4;
  auto t = [a](double xi) { return std::abs(xi) < a ? std::sqrt(1.0 - xi * xi / (a * a)) : 0.0; };
  auto error_on = [&](int n) {
    const Grid grid{-1.5 * a, 1.5 * a, n};
    const CouplingKernel S(grid);
    std::vector<double> mean(n), u(n);
    for (int j = 0; j < n; ++j) {
      const double lo = std::max(grid.left(j), -a), hi = std::min(grid.left(j) + grid.h(), a);
      mean[j] = hi > lo ? boost::math::quadrature::gauss_kronrod<double, 31>::integrate(t, lo, hi, 10, 1e-14) /
                              grid.h()
                        : 0.0;
    }
    S.apply(mean, u);
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
      // Away from the edges, where t′ grows like (a − |x|)^(−1/2) and the local error h² t′ converges slower.
      if (std::abs(grid.x(i)) > 0.9 * a) continue;
      worst = std::max(worst, std::abs(u[i] - step_integral(t, grid.x(i), -a, a)));
    }
    return worst / a;
  };
  const double e1 = error_on(96), e2 = error_on(192), e3 = error_on(384);
  const double order = std::log2(e2 / e3);
  MESSAGE(fmt::format("coupling displacement error / a: {:.3g} {:.3g} {:.3g}, order {:.3f}", e1, e2, e3, order));
  CHECK(e3 < e2);
  CHECK(order > 1.8);
  CHECK(order < 2.2);
}

TEST_CASE("coupling kernel: A β is the difference of the bodies' (κ − 1)/(4μ), and its signs are the line loads'") {
  const ElasticPair pair({200e9, 0.3}, {110e9, 0.34}, PlaneState::strain);
  const double b_pad = (pair.kappa_pad() - 1.0) / (4.0 * pair.mu_pad());
  const double b_spec = (pair.kappa_specimen() - 1.0) / (4.0 * pair.mu_specimen());
  const double A_beta = pair.A() * pair.beta();
  MESSAGE(fmt::format("steel on titanium: beta = {:.6f}, alpha = {:.6f}", pair.beta(), pair.alpha()));
  CHECK(A_beta == test::rel(b_pad - b_spec, 1e-13));

  // Normal coupling, g = … − A β S q: a tangential line load F in +x on the specimen (−F on the pad) steps the gap
  // by −A β F from behind the load to ahead of it. The surface u_y of each body from the Flamant fields (y → 0+ in
  // each body's own frame; the pad's frame is the mirror y → −y, so its u_y changes sign and its load is −F).
  const double L = 1e-3, y = 1e-12, F = 1e4;
  auto gap = [&](double x) {
    const double spec = line_load_displacement(x, y, F, 0.0, pair.mu_specimen(), pair.kappa_specimen(), L).uy;
    const double pad = -line_load_displacement(x, y, -F, 0.0, pair.mu_pad(), pair.kappa_pad(), L).uy;
    return spec - pad;
  };
  CHECK(gap(2e-4) - gap(-2e-4) == test::rel(-A_beta * F, 1e-6));  // y/x = 5e-9 off the surface

  // Tangential coupling, s = … + A β S p: the datum's D (pad minus specimen, reference_datum.hpp) with the reference
  // points just below the surface at the centre of cell i is −(the step term of s) for a pressure on cell j ≠ i.
  const Grid grid{-1e-3, 1e-3, 50};
  const CouplingKernel S(grid);
  const int i = 21;
  const ReferenceDatum datum(grid, pair, grid.x(i), 1e-9 * grid.h());
  const std::vector<double> zero(grid.n, 0.0);
  for (int j : {3, 20, 22, 49}) {
    std::vector<double> p(grid.n, 0.0);
    p[j] = 1e8;
    CAPTURE(j);
    CHECK(datum.relative_displacement(zero, p) == test::rel(-A_beta * S.matrix(i, j) * p[j], 1e-6));
  }
}
