#include "contact/fatigue_measures.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace fretwear {

namespace {
constexpr double kPi = std::numbers::pi;
// Peaks closer than this (relative) are ties, which go to the first point (the smallest x: the trailing side).
constexpr double kTie = 1e-6;

// tr σ with σzz from the plane state.
double trace(const Stress& s, const Material& m, PlaneState plane) {
  const double in_plane = s.xx + s.yy;
  return plane == PlaneState::strain ? (1.0 + m.nu) * in_plane : in_plane;
}

// θ wrapped into [0, π).
double wrap(double theta) {
  double t = std::fmod(theta, kPi);
  if (t < 0.0) t += kPi;
  return t >= kPi ? 0.0 : t;
}
}  // namespace

namespace {
// σ_n on the plane of normal (c, n) = (cos θ, sin θ).
double normal_stress_on(const Stress& s, double c, double n) { return s.xx * c * c + s.yy * n * n + 2.0 * s.xy * n * c; }
}  // namespace

double normal_stress(const Stress& s, double theta) { return normal_stress_on(s, std::cos(theta), std::sin(theta)); }

double normal_strain(const Stress& s, double theta, const Material& m, PlaneState plane) {
  return ((1.0 + m.nu) * normal_stress(s, theta) - m.nu * trace(s, m, plane)) / m.E;
}

namespace {
struct PlaneValue {
  double swt, sigma_n_max, delta_eps_n;
};

// The plane's cosine and sine once for every state: the scan evaluates this some 200 times per point.
PlaneValue on_plane(std::span<const Stress> states, double theta, const Material& m, PlaneState plane) {
  assert(states.size() >= 2);
  const double c = std::cos(theta), n = std::sin(theta);
  double s_max = -INFINITY, e_max = -INFINITY, e_min = INFINITY;
  for (const Stress& s : states) {
    const double sn = normal_stress_on(s, c, n);
    s_max = std::max(s_max, sn);
    const double e = ((1.0 + m.nu) * sn - m.nu * trace(s, m, plane)) / m.E;  // normal_strain()
    e_max = std::max(e_max, e), e_min = std::min(e_min, e);
  }
  const double de = e_max - e_min;
  return {0.5 * s_max * de, s_max, de};
}
}  // namespace

double swt_on_plane(std::span<const Stress> states, double theta, const Material& m, PlaneState plane) {
  return on_plane(states, theta, m, plane).swt;
}

SwtResult swt_critical_plane(std::span<const Stress> states, const Material& m, PlaneState plane,
                             const SwtOptions& options) {
  assert(states.size() >= 2 && options.n_scan >= 3 && options.theta_tolerance > 0.0);
  const double step = kPi / options.n_scan;
  double best_theta = 0.0;
  PlaneValue best = on_plane(states, 0.0, m, plane);
  for (int k = 1; k < options.n_scan; ++k) {
    const double theta = k * step;
    const PlaneValue v = on_plane(states, theta, m, plane);
    if (v.swt > best.swt) best = v, best_theta = theta;
  }
  // Golden-section search for the maximum over [θ_k − step, θ_k + step]; SWT(θ) is π-periodic, so the bracket may
  // cross 0 or π. The scanned plane is kept when the search does no better (a maximum on the scan grid, or a bracket
  // holding two peaks).
  constexpr double kInvPhi = 0.6180339887498949;  // (√5 − 1)/2
  double lo = best_theta - step, hi = best_theta + step;
  double t1 = hi - kInvPhi * (hi - lo), t2 = lo + kInvPhi * (hi - lo);
  double f1 = swt_on_plane(states, t1, m, plane), f2 = swt_on_plane(states, t2, m, plane);
  while (hi - lo > options.theta_tolerance) {
    if (f1 < f2) {
      lo = t1, t1 = t2, f1 = f2;
      t2 = lo + kInvPhi * (hi - lo), f2 = swt_on_plane(states, t2, m, plane);
    } else {
      hi = t2, t2 = t1, f2 = f1;
      t1 = hi - kInvPhi * (hi - lo), f1 = swt_on_plane(states, t1, m, plane);
    }
  }
  const double refined_theta = 0.5 * (lo + hi);
  const PlaneValue refined = on_plane(states, refined_theta, m, plane);
  if (refined.swt > best.swt) best = refined, best_theta = refined_theta;
  return {best.swt, wrap(best_theta), best.sigma_n_max, best.delta_eps_n};
}

RuizProfile ruiz(std::span<const double> x, std::span<const double> sigma_t, std::span<const double> q,
                 std::span<const double> delta) {
  assert(sigma_t.size() == x.size() && q.size() == x.size() && delta.size() == x.size());
  RuizProfile r;
  const std::size_t n = x.size();
  r.x.assign(x.begin(), x.end());
  r.sigma_t.assign(sigma_t.begin(), sigma_t.end());
  r.delta.assign(delta.begin(), delta.end());
  r.tau.resize(n), r.F1.resize(n), r.F2.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    r.tau[i] = std::abs(q[i]);
    r.F1[i] = r.tau[i] * delta[i];
    r.F2[i] = std::max(sigma_t[i], 0.0) * r.F1[i];
    if (i == 0 || r.F1[i] > r.F1_max * (1.0 + kTie)) r.F1_max = r.F1[i], r.F1_max_x = x[i];
    if (i == 0 || r.F2[i] > r.F2_max * (1.0 + kTie)) r.F2_max = r.F2[i], r.F2_max_x = x[i];
  }
  return r;
}

RuizProfile ruiz_along_surface(const SurfaceTractions& top, std::span<const double> slip_range) {
  const int n = top.grid.n;
  assert(int(slip_range.size()) == n);
  std::vector<double> x(std::size_t(n), 0.0), sxx(x.size(), 0.0), q(x.size(), 0.0), delta(x.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    x[i] = top.grid.x(i);
    sxx[i] = stress_at(top, x[i], 0.0).xx;
    q[i] = top.q.empty() ? 0.0 : top.q[i];
    delta[i] = 0.5 * slip_range[i];
  }
  return ruiz(x, sxx, q, delta);
}

}  // namespace fretwear
