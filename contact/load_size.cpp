#include "contact/load_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>

#include "common/error.hpp"

namespace fretwear {

double load_for_half_width(const Profile& profile, double A, double b) {
  const double xc = profile.lowest_point();
  // By symmetry, P = (2/A) ∫_0^{π/2} g0′(xc + b sin θ) b sin θ dθ; split at the kinks inside (0, b).
  std::vector<double> cuts{0.0};
  for (double k : profile.kinks()) {
    const double s = (k - xc) / b;
    if (s > 1e-15 && s < 1.0 - 1e-15) cuts.push_back(std::asin(s));
  }
  cuts.push_back(0.5 * std::numbers::pi);
  std::sort(cuts.begin(), cuts.end());
  auto f = [&](double th) {
    const double t = b * std::sin(th);
    return profile.slope(xc + t) * t;
  };
  // Between kinks the integrand is smooth, so the 31-point Kronrod result is exact to round-off long before its
  // error estimate (the distance to the embedded Gauss rule) says so. The requested tolerance must stay above what
  // round-off lets that estimate reach: at 1e-15 (≈ 4.5 ε) it often never does, and the quadrature bisects to its
  // maximum depth (2^15 panels, a tenth of a second per P(b)) for no gain.
  constexpr double kTolerance = 64.0 * std::numeric_limits<double>::epsilon();
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    sum += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, cuts[i], cuts[i + 1], 15, kTolerance);
  return 2.0 * sum / A;
}

double half_width_for_load(const Profile& profile, double A, double P) {
  if (!profile.symmetric_single_zone())
    throw InputError("the load–size integral needs a symmetric single-zone profile");
  // Bracket: P(b) grows with b; start from a length the profile itself suggests and expand.
  double hi = 1e-9;
  while (load_for_half_width(profile, A, hi) < P) {
    hi *= 2.0;
    if (hi > 1e3) throw InputError("the load–size integral found no contact half-width below 1 km for this load");
  }
  double lo = 0.5 * hi;
  while (load_for_half_width(profile, A, lo) > P) lo *= 0.5;  // a load so small that b < 1 nm
  std::uintmax_t max_iter = 200;
  auto [a, b] = boost::math::tools::toms748_solve(
      [&](double x) { return load_for_half_width(profile, A, x) - P; }, lo, hi,
      boost::math::tools::eps_tolerance<double>(50), max_iter);
  return 0.5 * (a + b);
}

}  // namespace fretwear
