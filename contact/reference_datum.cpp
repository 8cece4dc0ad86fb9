#include "contact/reference_datum.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "common/error.hpp"

namespace fretwear {

LineLoadDisplacement line_load_displacement(double x, double y, double F, double P, double mu, double kappa,
                                            double L) {
  const double r2 = x * x + y * y, c = 1.0 / (4.0 * std::numbers::pi * mu);
  LineLoadDisplacement u;
  u.ux = -F * c * ((kappa + 1.0) * 0.5 * std::log(r2 / (L * L)) + 2.0 * y * y / r2) +
         P * c * (2.0 * x * y / r2 - (kappa - 1.0) * std::atan(x / y));
  // u_y of the normal load: the same radial field turned by π/2 (ψ = atan2(−x, y) from the load's line of action).
  const double psi = std::atan2(-x, y), lr = 0.5 * std::log(r2 / (L * L));
  const double a = -2.0 * P / std::numbers::pi * (kappa + 1.0) / (8.0 * mu);
  const double b = -2.0 * P / std::numbers::pi * (3.0 - kappa) / (8.0 * mu);
  const double u_r = a * std::cos(psi) * lr - 0.5 * (a - b) * (std::cos(psi) - psi * std::sin(psi));
  const double u_psi = -b * std::sin(psi) - a * std::sin(psi) * lr + 0.5 * (a - b) * psi * std::cos(psi);
  u.uy = -F * c * ((kappa - 1.0) * std::atan2(y, x) - 2.0 * x * y / r2) + u_r * std::cos(psi) - u_psi * std::sin(psi);
  return u;
}

ReferenceDatum::ReferenceDatum(const Grid& grid, const ElasticPair& pair, double x_c, double d)
    : x_c_(x_c), d_(d), h_(grid.h()), g_(grid.n), e_(grid.n) {
  if (!(d > 0.0) || !std::isfinite(d))
    throw InputError(fmt::format("reference datum: the depth {} m must be a finite number > 0", d));
  const double L = grid.width();  // HalfPlaneKernel's datum length
  const double pi = std::numbers::pi;
  // Antiderivatives over s = x_c − ξ.
  auto I_ln = [&](double s) { return s * 0.5 * std::log((s * s + d * d) / (L * L)) - s + d * std::atan(s / d); };
  auto I_d = [&](double s) { return d * std::atan(s / d); };
  auto I_xy = [&](double s) { return 0.5 * d * std::log(s * s + d * d); };
  auto I_atan = [&](double s) { return s * std::atan(s / d) - 0.5 * d * std::log(s * s + d * d); };
  const double c_pad = 1.0 / (4.0 * pi * pair.mu_pad()), c_spec = 1.0 / (4.0 * pi * pair.mu_specimen());
  const double k_pad = pair.kappa_pad(), k_spec = pair.kappa_specimen();
  const bool similar = c_pad == c_spec && k_pad == k_spec;
  for (int j = 0; j < grid.n; ++j) {
    // ξ over [left(j), left(j + 1)]: s from x_c − left(j + 1) to x_c − left(j).
    const double s1 = x_c - grid.left(j + 1), s2 = x_c - grid.left(j);
    const double ln = I_ln(s2) - I_ln(s1), dd = I_d(s2) - I_d(s1);
    g_[j] = (c_pad * ((k_pad + 1.0) * ln + 2.0 * dd) + c_spec * ((k_spec + 1.0) * ln + 2.0 * dd)) / h_;
    if (!similar) {
      const double xy = I_xy(s2) - I_xy(s1), at = I_atan(s2) - I_atan(s1);
      e_[j] = (c_pad * (2.0 * xy - (k_pad - 1.0) * at) - c_spec * (2.0 * xy - (k_spec - 1.0) * at)) / h_;
    }
  }
}

double ReferenceDatum::relative_displacement(std::span<const double> q, std::span<const double> p) const {
  assert(q.size() == g_.size() && (p.empty() || p.size() == e_.size()));
  double D = 0.0;
  for (std::size_t j = 0; j < g_.size(); ++j) D += g_[j] * q[j] + (p.empty() ? 0.0 : e_[j] * p[j]);
  return h_ * D;
}

double hertz_stuck_compliance(double A, double mu, double a, double d) {
  const double r = std::sqrt(d * d + a * a);
  return (A / std::numbers::pi) * std::log((d + r) / a) + d / (std::numbers::pi * mu * r);
}

}  // namespace fretwear
