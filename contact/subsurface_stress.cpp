#include "contact/subsurface_stress.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace fretwear {

namespace {

constexpr double kPi = std::numbers::pi;

// A cell boundary where p or q jumps: Δ = value to the right − value to the left.
struct Jump {
  double xi, dp, dq;
};

std::vector<Jump> jumps(const SurfaceTractions& t) {
  const int n = t.grid.n;
  assert(int(t.p.size()) == n && (t.q.empty() || int(t.q.size()) == n));
  auto p = [&](int i) { return i < 0 || i >= n ? 0.0 : t.p[i]; };
  auto q = [&](int i) { return i < 0 || i >= n || t.q.empty() ? 0.0 : t.q[i]; };
  std::vector<Jump> out;
  for (int b = 0; b <= n; ++b) {
    const double dp = p(b) - p(b - 1), dq = q(b) - q(b - 1);
    if (dp != 0.0 || dq != 0.0) out.push_back({t.grid.left(b), dp, dq});
  }
  return out;
}

// Σ_b [Δp_b F + Δq_b G] at (x, y) (header), and its y-derivative when ds is given, without σ_bulk.
Stress sum_over_jumps(const std::vector<Jump>& J, double x, double y, Stress* ds, Stress* dsx = nullptr) {
  double xx = 0.0, yy = 0.0, xy = 0.0, dxx = 0.0, dyy = 0.0, dxy = 0.0, exx = 0.0, eyy = 0.0, exy = 0.0;
  for (const Jump& j : J) {
    const double X = x - j.xi, r2 = X * X + y * y;
    double theta = 0.0, Xy = 0.0, X2 = 1.0, y2 = 0.0, ln_r2 = 0.0, inv = 0.0;
    if (r2 > 0.0) {  // else: on a boundary at the surface, the header's mean limit
      inv = 1.0 / r2;
      theta = std::atan2(X, y);
      Xy = X * y * inv;
      X2 = X * X * inv;
      y2 = y * y * inv;
      if (j.dq != 0.0) ln_r2 = std::log(r2);
    }
    xx += j.dp * (theta - Xy) + j.dq * (ln_r2 + y2);
    yy += j.dp * (theta + Xy) + j.dq * X2;
    xy += j.dp * X2 + j.dq * (theta - Xy);
    if (ds) {
      const double inv2 = inv * inv;
      const double d_theta = -X * inv, d_Xy = X * (X * X - y * y) * inv2, d_X2 = -2.0 * X * X * y * inv2;
      const double d_ln = 2.0 * y * inv, d_y2 = 2.0 * y * X * X * inv2;
      dxx += j.dp * (d_theta - d_Xy) + j.dq * (d_ln + d_y2);
      dyy += j.dp * (d_theta + d_Xy) + j.dq * d_X2;
      dxy += j.dp * d_X2 + j.dq * (d_theta - d_Xy);
    }
    if (dsx) {  // ∂/∂x = ∂/∂X
      const double inv2 = inv * inv;
      const double e_theta = y * inv, e_Xy = y * (y * y - X * X) * inv2, e_X2 = 2.0 * X * y * y * inv2;
      const double e_ln = 2.0 * X * inv, e_y2 = -2.0 * X * y * y * inv2;
      exx += j.dp * (e_theta - e_Xy) + j.dq * (e_ln + e_y2);
      eyy += j.dp * (e_theta + e_Xy) + j.dq * e_X2;
      exy += j.dp * e_X2 + j.dq * (e_theta - e_Xy);
    }
  }
  constexpr double c = -1.0 / kPi;
  if (ds) *ds = {c * dxx, c * dyy, c * dxy};
  if (dsx) *dsx = {c * exx, c * eyy, c * exy};
  return {c * xx, c * yy, c * xy};
}

}  // namespace

Stress stress_at(const SurfaceTractions& t, double x, double y) {
  assert(y >= 0.0);
  Stress s = sum_over_jumps(jumps(t), x, y, nullptr);
  s.xx += t.sigma_bulk;
  return s;
}

std::vector<Stress> stress_along_depth(const SurfaceTractions& t, double x, std::span<const double> y) {
  const std::vector<Jump> J = jumps(t);
  std::vector<Stress> out(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) {
    assert(y[k] >= 0.0);
    out[k] = sum_over_jumps(J, x, y[k], nullptr);
    out[k].xx += t.sigma_bulk;
  }
  return out;
}

std::vector<Stress> stress_along_line(const SurfaceTractions& t, double x, double angle_deg, std::span<const double> r) {
  assert(angle_deg > 0.0 && angle_deg < 180.0);
  // Direction (cos α, sin α), exact at α = 90°: the depth line x + 0 r.
  const double c = std::sin((90.0 - angle_deg) * kPi / 180.0), s = std::cos((90.0 - angle_deg) * kPi / 180.0);
  const std::vector<Jump> J = jumps(t);
  std::vector<Stress> out(r.size());
  for (std::size_t k = 0; k < r.size(); ++k) {
    assert(r[k] >= 0.0);
    out[k] = sum_over_jumps(J, x + c * r[k], s * r[k], nullptr);
    out[k].xx += t.sigma_bulk;
  }
  return out;
}

Principal principal(const Stress& s) {
  const double mean = 0.5 * (s.xx + s.yy), half = 0.5 * (s.xx - s.yy);
  const double radius = std::hypot(half, s.xy);
  return {mean + radius, mean - radius, 0.5 * std::atan2(2.0 * s.xy, s.xx - s.yy)};
}

double von_mises(const Stress& s, double nu) {
  const double zz = nu * (s.xx + s.yy);
  const double a = s.xx - s.yy, b = s.yy - zz, c = zz - s.xx;
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * s.xy * s.xy);
}

}  // namespace fretwear
