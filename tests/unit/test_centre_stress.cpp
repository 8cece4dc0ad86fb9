// The stresses at every cell centre by FFT (contact/centre_stress.hpp) against the sum over the jumps point by point
// (stress_along_depth): the same discrete field, so they agree to round-off, on the surface and below it, for a
// Hertz pressure under a partial-slip shear (both jumps), with and without bulk stress, on grids of every size class
// the transform length takes (2n + 2 rounded up to 2^a 3^b 5^c).
#include <algorithm>
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "contact/centre_stress.hpp"
#include "contact/closed_form.hpp"
#include "contact/subsurface_stress.hpp"

using namespace fretwear;

namespace {

constexpr double kA = 1.82e-11;  // PHYSICS.md's public steel pair (1/Pa)
constexpr double kR = 0.01;      // m
constexpr double kP = 1e5;       // N/m
constexpr double kF = 0.5;
// Round-off of a convolution by FFT: about ε log₂ L times Σ|Δ| max|kernel| (kernels up to |ln r²| ≈ 30 here, Σ|Δp|
// ≈ 2 p0): some 1e-13 p0. The bound allows a hundred times that; a wrong index or sign is O(p0).
constexpr double kRoundOff = 1e-11;

}  // namespace

TEST_CASE("centre stresses by FFT equal the sum over jumps at every centre and depth") {
  const closed_form::Hertz hz = closed_form::hertz(kP, kA, kR);
  const double c = hz.a * std::sqrt(0.5);  // the stick zone of Q/fP = 0.5
  for (int n : {7, 64, 333, 1024}) {
    CAPTURE(n);
    const Grid grid{-1.5 * hz.a, 1.7 * hz.a, n};  // off-centre: the kernel's odd parts are tested
    std::vector<double> p(static_cast<std::size_t>(n)), q(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double x = grid.x(i);
      p[i] = hz.cell_average(grid.left(i), grid.left(i + 1));
      const double qs = std::abs(x) < c ? kF * hz.p0 * (c / hz.a) * std::sqrt(1.0 - x * x / (c * c)) : 0.0;
      q[i] = kF * p[i] - qs;
    }
    const std::vector<double> depths{0.0, 1e-3 * hz.a, 0.1 * hz.a, 0.78 * hz.a, 3.0 * hz.a};
    const CentreStresses fast(grid, depths);
    for (double bulk : {0.0, 2.5e8}) {
      CAPTURE(bulk);
      const SurfaceTractions t{grid, p, q, bulk};
      const std::vector<Stress> rows = fast(t);
      REQUIRE(rows.size() == depths.size() * std::size_t(n));
      double worst = 0.0;
      for (int i = 0; i < n; ++i) {
        const std::vector<Stress> column = stress_along_depth(t, grid.x(i), depths);
        for (std::size_t k = 0; k < depths.size(); ++k) {
          const Stress& a = rows[k * std::size_t(n) + std::size_t(i)];
          worst = std::max({worst, std::abs(a.xx - column[k].xx), std::abs(a.yy - column[k].yy),
                            std::abs(a.xy - column[k].xy)});
        }
      }
      CHECK(worst <= kRoundOff * hz.p0);
    }
  }
}

TEST_CASE("centre stresses without a shear traction are the pressure's alone") {
  const closed_form::Hertz hz = closed_form::hertz(kP, kA, kR);
  const Grid grid{-1.5 * hz.a, 1.5 * hz.a, 128};
  std::vector<double> p(128);
  for (int i = 0; i < 128; ++i) p[i] = hz.cell_average(grid.left(i), grid.left(i + 1));
  const std::vector<double> depths{0.0, 0.5 * hz.a};
  const std::vector<Stress> rows = CentreStresses(grid, depths)(SurfaceTractions{grid, p, {}, 0.0});
  double worst = 0.0;
  for (int i = 0; i < 128; ++i) {
    const std::vector<Stress> column = stress_along_depth(SurfaceTractions{grid, p, {}, 0.0}, grid.x(i), depths);
    for (std::size_t k = 0; k < 2; ++k)
      worst = std::max({worst, std::abs(rows[k * 128 + i].xx - column[k].xx),
                        std::abs(rows[k * 128 + i].yy - column[k].yy), std::abs(rows[k * 128 + i].xy - column[k].xy)});
  }
  CHECK(worst <= kRoundOff * hz.p0);
  // On the surface σyy = −p at every centre (the free-surface limit).
  for (int i = 0; i < 128; ++i) CHECK(std::abs(rows[std::size_t(i)].yy + p[i]) <= kRoundOff * hz.p0);
}
