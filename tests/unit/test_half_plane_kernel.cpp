// The influence coefficients against direct quadrature of the log kernel, and the FFT product against the dense one.
#include <cmath>
#include <numbers>
#include <random>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <doctest/doctest.h>

#include "support.hpp"

#include "contact/half_plane_kernel.hpp"

using namespace fretwear;

namespace {
// Quadrature has a log singularity at the collocation point when d = 0; tanh-sinh handles endpoint singularities,
// so the cell is split there.
double quadrature_coefficient(double A, double L, double d, double h) {
  boost::math::quadrature::tanh_sinh<double> ts;
  auto f = [&](double s) { return -(A / std::numbers::pi) * std::log(std::abs(s) / L); };
  const double lo = d - 0.5 * h, hi = d + 0.5 * h;
  if (lo < 0.0 && hi > 0.0) return ts.integrate(f, lo, 0.0) + ts.integrate(f, 0.0, hi);
  return ts.integrate(f, lo, hi);
}
}  // namespace

TEST_CASE("influence coefficients equal the quadrature of the log kernel over the cell") {
  const Grid grid{-1e-3, 2e-3, 60};
  const double A = 1.82e-11;
  const HalfPlaneKernel kernel(grid, A);
  for (int k : {0, 1, 2, 7, 59}) {
    const double d = k * grid.h();
    const double want = quadrature_coefficient(A, grid.width(), d, grid.h());
    CHECK(kernel.column()[k] == test::rel(want, 1e-12));
    CHECK(kernel.coefficient(-d) == test::rel(want, 1e-12));
  }
}

TEST_CASE("the FFT Toeplitz product equals the dense product") {
  for (int n : {16, 37, 256}) {
    const Grid grid{0.0, 1e-3, n};
    const HalfPlaneKernel kernel(grid, 1.0);
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    std::vector<double> p(n), u(n);
    for (double& v : p) v = uni(rng);
    kernel.apply(p, u);
    double scale = 0.0;
    for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(kernel.column()[i]));
    for (int i = 0; i < n; ++i) {
      double dense = 0.0;
      for (int j = 0; j < n; ++j) dense += kernel.column()[std::abs(i - j)] * p[j];
      CHECK(std::abs(u[i] - dense) <= 1e-13 * scale * n);
    }
  }
}

TEST_CASE("the influence matrix is positive definite with the window as datum length") {
  // Smallest Rayleigh quotient over a few oscillatory and smooth vectors stays positive.
  const Grid grid{-1.0, 1.0, 128};
  const HalfPlaneKernel kernel(grid, 1.0);
  std::vector<double> p(128), u(128);
  for (int mode = 0; mode < 64; ++mode) {
    for (int i = 0; i < 128; ++i) p[i] = std::cos(std::numbers::pi * mode * (i + 0.5) / 128.0);
    kernel.apply(p, u);
    double q = 0.0;
    for (int i = 0; i < 128; ++i) q += p[i] * u[i];
    CHECK(q > 0.0);
  }
}
