// The intensity of a square-root singular contact edge (PHYSICS.md, "Singular edges"): where the pressure near an
// edge behaves like K_N / √(2πr), r the distance from the edge into the contact, its strength is
//     K_N = lim_{r→0} p(r) √(2πr)   (Pa·m^0.5).
// Sharp flat punch of half-width b: K_N = P/√(πb); the Hertz wear limit over the stick zone [−c, c]:
// K_N = P(1 − c²/a²)/√(πc).
//
// Near a corner of a complete contact whose gap is smooth inside it the pressure is r^{-1/2} times a smooth function
// of r (Muskhelishvili 1953 §88: p = w(x)/√(b² − x²), w smooth), so over the stretch [0, L] next to the edge
//     p(r) = Σ_{k=0}^{m−1} a_k r^{k − 1/2} + O(r^{m − 1/2}),   K_N = √(2π) a_0.
// The solver's cell values are, up to its discretisation error, averages of p over whole cells, and the average of
// r^{k − 1/2} over [r0, r1] is exactly (r1^{k+1/2} − r0^{k+1/2}) / ((k + 1/2)(r1 − r0)); the a_k are the least-squares
// fit of these averages to the cell pressures of the whole cells in [s L, L], each row divided by the leading
// term's average so that every cell counts by its relative misfit. The fit reproduces pressures of that form exactly
// (for the sharp punch with m = 4, s = 1/4 and L = b/4 the truncation leaves 1e-5 of K_N).
//
// Why the cells next to the edge are left out. Piecewise-constant collocation at a corner has an error on the scale of
// the cell h: cell i from the edge carries (1 + ε_i) times the average of the exact pressure, with ε_i independent of
// h (−4.5 % in the first cell, −1.8 % in the second, +2.5 % in the third, then ε ≈ 0.09 h/r), plus the contact's own
// first-order error. A fit that used a fixed number of cells would keep an error that no refinement removes; one over
// [0, L] converges only like (h/L) ln(L/h). Over [s L, L] every cell has r ≥ s L, so ε = O(h/L) there and K_N converges
// at first order in h/L (measured: order 0.95–0.99 from 512 to 4096 cells across a sharp punch;
// tests/verification/test_edge_intensity.cpp).
#pragma once

#include <optional>
#include <span>

#include "contact/grid.hpp"

namespace fretwear {

struct EdgeIntensityOptions {
  int terms = 4;         // m: the powers r^{-1/2}, r^{1/2}, …, r^{m − 3/2} fitted
  double skip = 0.25;    // s: cells nearer the edge than s·L are left out; in [0, 1)
  int min_cells = 8;     // fewer whole cells in [s L, L]: no fit (and never fewer than `terms`)
};

// The fit length callers take: this fraction of the length of the contact (or stick) zone the edge bounds, so that
// the regular part of p varies little over it and the fit converges at first order in h / (zone length).
inline constexpr double kEdgeFitFraction = 1.0 / 8.0;

// K_N at the edge x_edge of the contact on `grid`, fitted to the cell pressures p over the whole cells on the
// contact's side of the edge in [s·length, length] (m). side = +1: the contact lies at x > x_edge (a left edge);
// side = −1: at x < x_edge (a right edge). The edge may sit anywhere in a cell (a boundary within 1e-9 h of it
// counts as the edge); the cell it cuts is never used. Empty when too few whole cells lie in the fit's range, or
// when the fitted K_N is not positive (no compressive singularity there).
std::optional<double> edge_intensity(const Grid& grid, std::span<const double> p, double x_edge, int side,
                                     double length, const EdgeIntensityOptions& options = {});

// The average of r^{k − 1/2} over [r0, r1], 0 ≤ r0 < r1: (r1^{k+1/2} − r0^{k+1/2}) / ((k + 1/2)(r1 − r0)).
double edge_power_average(int k, double r0, double r1);

// The edge intensities at the two ends of one zone (Pa·m^0.5); empty where the edge is not singular or the zone is too
// short to fit.
struct EdgeIntensities {
  std::optional<double> left, right;
};

}  // namespace fretwear
