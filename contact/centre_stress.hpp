// The stresses at every cell centre of a grid, row by row in depth, by FFT: the fast form of stress_along_depth
// (contact/subsurface_stress.hpp) where many columns under the same tractions are wanted.
//
// subsurface_stress.hpp writes the field as a sum over the cell boundaries ξ_b = ξ_0 + b h, b = 0 … n, of the jumps
// Δp_b, Δq_b of the piecewise-constant tractions:
//     σ(x, y) = Σ_b [Δp_b F(x − ξ_b, y) + Δq_b G(x − ξ_b, y)] + σ_bulk e_x ⊗ e_x.
// At the cell centres x_i = ξ_0 + (i + ½) h the argument x_i − ξ_b = (i − b + ½) h depends on i − b alone, so each
// depth row is a discrete convolution of the jumps with the kernels sampled at X_m = (m + ½) h, m = −n … n − 1.
// Of F's and G's six components four functions are distinct (F_xy = G_yy and G_xy = F_xx), each times −1/π:
//     a = θ − X y/r²,   b = θ + X y/r²,   c = X²/r²,   d = ln r² + y²/r²,
//     σxx = Δp ∗ a + Δq ∗ d,   σyy = Δp ∗ b + Δq ∗ c,   σxy = Δp ∗ c + Δq ∗ a.
// The convolutions are circular on L = 2n + 2 points (the jumps at 0 … n, the kernel at m mod L), which holds every
// i − b without wrapping. The kernels' spectra depend on the grid and the depths only and are computed once; each
// set of tractions then costs two forward and three inverse real transforms per depth, O(L log L), where the sum
// point by point costs O(n × jumps) per depth. The round-off, ε Σ|Δ| max|kernel| (ln r² included: Σ Δq = 0 makes
// its length unit cancel exactly in the sum, and to round-off here), is far below the stresses' discretisation
// error; tests/unit/test_centre_stress.cpp compares with stress_along_depth.
#pragma once

#include <complex>
#include <memory>
#include <span>
#include <vector>

#include "contact/grid.hpp"
#include "contact/subsurface_stress.hpp"

namespace fretwear {

class CentreStresses {
 public:
  // The kernels of `grid` at the depths y_k ≥ 0 (m).
  CentreStresses(const Grid& grid, std::vector<double> depths);
  ~CentreStresses();
  CentreStresses(const CentreStresses&) = delete;
  CentreStresses& operator=(const CentreStresses&) = delete;
  // σ at (grid.x(i), y_k) for every cell i and depth k: out[k n + i]. t's grid must be this one's. Reentrant: the
  // plans are executed on buffers of the call's own.
  std::vector<Stress> operator()(const SurfaceTractions& t) const;
  const std::vector<double>& depths() const { return depths_; }

 private:
  struct Plans;
  Grid grid_;
  std::vector<double> depths_;
  int L_ = 0;  // circulant size 2n + 2
  // Per depth, the half spectra (L/2 + 1 entries, divided by L) of a, b, c and d, times −1/π.
  std::vector<std::complex<double>> a_, b_, c_, d_;
  std::unique_ptr<Plans> plans_;  // made once, under the planner's lock
};

}  // namespace fretwear
