#include "contact/half_plane_kernel.hpp"

#include <cmath>
#include <numbers>

namespace fretwear {
namespace {
std::vector<double> first_column(const Grid& g, double A, double L) {
  const double h = g.h();
  auto F = [L](double s) { return s == 0.0 ? 0.0 : s * std::log(std::abs(s) / L) - s; };
  std::vector<double> c(g.n);
  for (int k = 0; k < g.n; ++k) {
    const double d = k * h;
    c[k] = -(A / std::numbers::pi) * (F(d + 0.5 * h) - F(d - 0.5 * h));
  }
  return c;
}
}  // namespace

HalfPlaneKernel::HalfPlaneKernel(const Grid& grid, double A)
    : grid_(grid), A_(A), L_(grid.width()), column_(first_column(grid, A, grid.width())), fft_(column_) {
  // spectrum() is C's half spectrum divided by m = 2n; apply_spectrum wants C⁻¹'s divided by m likewise.
  const auto spec = fft_.spectrum();
  const double m = 2.0 * grid_.n;
  inverse_spectrum_.resize(spec.size());
  for (std::size_t k = 0; k < spec.size(); ++k) {
    const double lambda = spec[k].real() * m;  // C is symmetric: its spectrum is real
    if (!(lambda > 0.0)) {
      inverse_spectrum_.clear();
      break;
    }
    inverse_spectrum_[k] = 1.0 / (lambda * m);
  }
}

double HalfPlaneKernel::coefficient(double d) const {
  const double h = grid_.h();
  auto F = [this](double s) { return s == 0.0 ? 0.0 : s * std::log(std::abs(s) / L_) - s; };
  return -(A_ / std::numbers::pi) * (F(d + 0.5 * h) - F(d - 0.5 * h));
}

}  // namespace fretwear
