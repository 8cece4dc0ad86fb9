#include "contact/worn_flat.hpp"

#include <algorithm>
#include <cstdint>

#include <boost/math/tools/toms748_solve.hpp>

namespace fretwear {

Flat flat_at(const Profile& profile, double d, double h) {
  const double dx = 0.25 * h, x0 = profile.lowest_point();
  Flat f{0.0, x0, x0, d};
  for (int side : {-1, 1}) {
    double x = x0, v = std::max(0.0, d - profile.gap(x0));
    for (int k = 1; v > 0.0 && k < 100000000; ++k) {
      const double xn = x0 + side * k * dx, vn = std::max(0.0, d - profile.gap(xn));
      // the end between x and xn, where d − g0 falls to zero (linear)
      const double t = vn > 0.0 ? 1.0 : v / (v - (d - profile.gap(xn)));
      f.area += 0.5 * (v + (vn > 0.0 ? vn : 0.0)) * dx * t;
      (side < 0 ? f.left : f.right) = x + side * t * dx;
      x = xn, v = vn;
    }
  }
  return f;
}

Flat flat_holding(const Profile& profile, double area, double h) {
  double hi = 1e-9;
  Flat top = flat_at(profile, hi, h);
  for (; top.area < area && hi < 1.0; top = flat_at(profile, hi, h)) hi *= 2.0;
  if (!(top.area >= area)) return top;
  std::uintmax_t iterations = 200;
  const auto [lo_d, hi_d] = boost::math::tools::toms748_solve(
      [&](double d) { return flat_at(profile, d, h).area - area; }, 0.0, hi, -area, top.area - area,
      boost::math::tools::eps_tolerance<double>(30), iterations);
  return flat_at(profile, 0.5 * (lo_d + hi_d), h);
}

std::pair<double, double> window_holding(const Profile& profile, double area, double h, double U, double left,
                                         double right) {
  const Flat end = flat_holding(profile, area, h);
  const double x0 = profile.lowest_point();
  const double half = 1.2 * (std::max(x0 - std::min(end.left, left), std::max(end.right, right) - x0) + U);
  return {x0 - half, x0 + half};
}

}  // namespace fretwear
