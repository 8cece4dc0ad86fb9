// Influence coefficients of the half-plane for piecewise-constant pressure on a uniform grid.
//
// A pressure p(ξ) on the surface of two half-planes with composite compliance A changes their gap by
//     u(x) = −(A/π) ∫ p(ξ) ln(|x − ξ|/L) dξ,
// whose derivative is the Cauchy kernel of PHYSICS.md's normal-contact equation. For a uniform p = 1 on the cell
// [ξ_j − h/2, ξ_j + h/2] observed at the centre x_i (d = x_i − ξ_j) this is, exactly,
//     K(d) = −(A/π) [F(d + h/2) − F(d − h/2)],   F(s) = s ln(|s|/L) − s.
// The datum length L only adds a constant times the total load (in 2D the rigid approach is defined only relative
// to a datum); solvers remove it by balancing the load. We take L = the window width, which keeps K positive
// definite on the grid (the logarithmic capacity of an interval is a quarter of its length).
#pragma once

#include <complex>
#include <vector>

#include "contact/grid.hpp"
#include "contact/toeplitz_fft.hpp"

namespace fretwear {

class HalfPlaneKernel {
 public:
  HalfPlaneKernel(const Grid& grid, double A);

  // K(d) for centre-to-centre distance d (m) per unit pressure (m/Pa).
  double coefficient(double d) const;
  // K(k h), k = 0..n−1: the first column of the Toeplitz influence matrix.
  const std::vector<double>& column() const { return column_; }
  // u = K p by FFT.
  void apply(std::span<const double> p, std::span<double> u) const { fft_.apply(p, u); }
  const ToeplitzFFT& fft() const { return fft_; }
  // The preconditioner of the solvers on this grid: the inverse of the circulant C that embeds K, as
  // ToeplitzFFT::apply_spectrum takes it (its half spectrum over m = 2n). Empty when C is not positive definite,
  // and a solver then runs without it.
  const std::vector<std::complex<double>>& inverse_spectrum() const { return inverse_spectrum_; }
  const Grid& grid() const { return grid_; }
  double A() const { return A_; }

 private:
  Grid grid_;
  double A_, L_;
  std::vector<double> column_;
  ToeplitzFFT fft_;
  std::vector<std::complex<double>> inverse_spectrum_;
};

}  // namespace fretwear
