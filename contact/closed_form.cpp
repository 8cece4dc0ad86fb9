#include "contact/closed_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <boost/math/tools/roots.hpp>

namespace fretwear::closed_form {

constexpr double kPi = std::numbers::pi;

Hertz hertz(double P, double A, double R) {
  const double a = std::sqrt(2.0 * P * A * R / kPi);
  return {a, 2.0 * P / (kPi * a)};
}

double Hertz::pressure(double x) const {
  const double s = 1.0 - (x / a) * (x / a);
  return s > 0.0 ? p0 * std::sqrt(s) : 0.0;
}

double Hertz::cell_average(double x0, double x1) const {
  // ∫ √(1 − s²) ds = (s √(1 − s²) + asin s) / 2
  auto I = [](double s) {
    s = std::clamp(s, -1.0, 1.0);
    return 0.5 * (s * std::sqrt(1.0 - s * s) + std::asin(s));
  };
  return p0 * a * (I(x1 / a) - I(x0 / a)) / (x1 - x0);
}

StickZone hertz_stick(const Hertz& h, double q_ratio, double f, double sigma) {
  return {h.a * sigma / (4.0 * f * h.p0), h.a * std::sqrt(std::max(0.0, 1.0 - q_ratio))};
}

double D(double theta) { return kPi - 2.0 * theta - std::sin(2.0 * theta); }

double B(double phi, double phi0) {
  phi = std::abs(phi);
  if (std::abs(phi - phi0) < 1e-14) {  // the logs cancel at the end of the flat
    return (kPi - 2.0 * phi0) * std::cos(phi0) +
           std::sin(phi0) * (std::log(std::sin(2.0 * phi0)) + std::log(std::tan(phi0)) - std::log(2.0));
  }
  return (kPi - 2.0 * phi0) * std::cos(phi) +
         std::sin(phi) * std::log(std::abs(std::sin(phi + phi0) / std::sin(phi - phi0))) +
         std::sin(phi0) * std::log(std::abs(std::tan(0.5 * (phi + phi0)) * std::tan(0.5 * (phi - phi0))));
}

RoundedPunch rounded_punch(double P, double A, double a, double R) {
  // P A R / a² = (π − 2φ0)/(2 sin²φ0) − cot φ0 (PHYSICS.md; paper 000 eq 3), decreasing in φ0 ∈ (0, π/2).
  const double target = P * A * R / (a * a);
  auto f = [&](double phi0) {
    const double s = std::sin(phi0);
    return (kPi - 2.0 * phi0) / (2.0 * s * s) - std::cos(phi0) / s - target;
  };
  std::uintmax_t it = 200;
  auto [lo, hi] = boost::math::tools::toms748_solve(f, 1e-12, 0.5 * kPi - 1e-15,
                                                     boost::math::tools::eps_tolerance<double>(52), it);
  const double phi0 = 0.5 * (lo + hi);
  return {a, R, P, a / std::sin(phi0), phi0};
}

double rounded_punch_stick(const RoundedPunch& r, double q_ratio) {
  if (q_ratio <= 0.0) return r.b;
  if (q_ratio >= 1.0) return r.a;
  // The right side falls from 1 at c = a (ψ0 = π/2, D = 0) to 0 at c = b.
  auto g = [&](double c) {
    return 1.0 - (c / r.b) * (c / r.b) * D(std::asin(std::min(1.0, r.a / c))) / D(r.phi0) - q_ratio;
  };
  std::uintmax_t it = 200;
  auto [lo, hi] = boost::math::tools::toms748_solve(g, r.a, r.b, boost::math::tools::eps_tolerance<double>(50), it);
  return 0.5 * (lo + hi);
}

double RoundedPunch::pressure(double x) const {
  if (std::abs(x) >= b) return 0.0;
  const double phi = std::asin(std::abs(x) / b);
  return (P / b) * (2.0 / kPi) * B(phi, phi0) / D(phi0);
}

double RoundedPunch::peak_x() const {
  // With a small corner radius the peak is a spike at the end of the flat, b − a wide (2.6e-5 a at R = 4e-6 a), that
  // a search over [0, b] alone misses (it settled 1e-5 a inside the flat, 43 % below the peak): the pressure is
  // sampled evenly in φ (x = b sin φ) and ever closer to φ0 on both sides, and the search refines the best sample
  // between its neighbours.
  std::vector<double> phis;
  for (int k = 0; k <= 200; ++k) phis.push_back(0.5 * kPi * k / 200);
  for (int k = 0; k <= 300; ++k)
    for (const double side : {-1.0, 1.0}) phis.push_back(phi0 + side * 0.5 * kPi * std::pow(10.0, -k / 20.0));
  std::vector<double> xs;
  for (const double phi : phis)
    if (phi >= 0.0 && phi <= 0.5 * kPi) xs.push_back(b * std::sin(phi));
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::size_t best = 0;
  double p_best = pressure(xs[0]);
  for (std::size_t i = 1; i < xs.size(); ++i)
    if (const double p = pressure(xs[i]); p > p_best) p_best = p, best = i;
  // Zoomed in on: 200 samples between the best one's neighbours, the best of them and its neighbours again, until
  // the bracket is a few ulps of x wide (Brent's search stops at √ε of x, wider than a sharp corner's spike top).
  double lo = xs[best > 0 ? best - 1 : 0], hi = xs[std::min(best + 1, xs.size() - 1)], x_best = xs[best];
  constexpr int kSamples = 200;
  while (hi - lo > 8.0 * std::numeric_limits<double>::epsilon() * b) {
    const double step = (hi - lo) / kSamples;
    for (int k = 0; k <= kSamples; ++k)
      if (const double x = lo + k * step, p = pressure(x); p > p_best) p_best = p, x_best = x;
    lo = std::max(lo, x_best - step), hi = std::min(hi, x_best + step);
  }
  return x_best;
}

double RoundedPunch::peak() const { return pressure(peak_x()); }

FlatPunch flat_punch(double P, double b) { return {b, P}; }

double FlatPunch::pressure(double x) const {
  return std::abs(x) < b ? P / (kPi * std::sqrt(b * b - x * x)) : 0.0;
}

double FlatPunch::cell_average(double x0, double x1) const {
  auto I = [this](double x) { return std::asin(std::clamp(x / b, -1.0, 1.0)); };  // ∫ dx/√(b² − x²)
  return P / kPi * (I(x1) - I(x0)) / (x1 - x0);
}

}  // namespace fretwear::closed_form
