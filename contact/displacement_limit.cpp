#include "contact/displacement_limit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "common/error.hpp"

namespace fretwear {
namespace {

// The root finds stop at a relative bracket of 2⁻⁴⁰ (1e-12), far below the grid's error in Q, or after this many
// evaluations (toms748 takes about a dozen here).
constexpr int kRootBits = 40;
constexpr std::uintmax_t kRootIterations = 100;

void require_converged(const SolveSummary& s, const char* what) {
  if (!s.converged())
    throw ConvergenceError(fmt::format("wear: the {} solve of the displacement-control limit stopped ({}) with "
                                       "residual {:.3g}",
                                       what, to_string(s.termination), s.residual));
}

template <class F>
double root(F f, double lo, double hi, const char* what) {
  std::uintmax_t it = kRootIterations;
  const auto [a, b] = boost::math::tools::toms748_solve(f, lo, hi, boost::math::tools::eps_tolerance<double>(kRootBits),
                                                        it);
  if (it >= kRootIterations)
    throw ConvergenceError(fmt::format("wear: the root find for {} took {} evaluations without closing its bracket "
                                       "[{:.6g}, {:.6g}]",
                                       what, it, a, b));
  return 0.5 * (a + b);
}

}  // namespace

double stuck_compliance(const Grid& grid, const ElasticPair& pair, double x_c, double d,
                        const std::vector<Zone>& zones) {
  if (zones.empty()) throw InputError("stuck_compliance: no zone to stick");
  const int n = grid.n;
  // The grid aligned to the first zone [c_l, c_r]: whole cells across it, the window shifted by less than a cell.
  const double cl = zones.front().left.x, cr = zones.front().right.x;
  const double h = (cr - cl) / std::max(1.0, std::round((cr - cl) / grid.h()));
  const double lo = cl - std::round((cl - grid.x_min) / h) * h;
  const Grid aligned{lo, lo + n * h, n};
  const HalfPlaneKernel kernel(aligned, pair.A());
  // The stuck shear solves K q = λ on Z, q = 0 outside: the normal problem of a flat, rigid punch over Z (gap 0 on
  // Z, +∞ outside), whose approach is λ. Solved under a unit load.
  std::vector<double> g(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) {
    const double x = aligned.x(i);
    if (std::any_of(zones.begin(), zones.end(), [x](const Zone& z) { return x > z.left.x && x < z.right.x; }))
      g[i] = 0.0;
  }
  ContactState stuck;
  require_converged(NormalSolver(kernel).solve(g, 1.0, stuck), "stuck complete-contact");
  const ReferenceDatum datum(aligned, pair, x_c, d);
  return stuck.approach + datum.relative_displacement(stuck.p, {});
}

double settled_worn_area(const Grid& grid, const HalfPlaneKernel& kernel, std::span<const double> g0,
                         std::span<const double> w, double P, const std::vector<Zone>& zones) {
  const int n = grid.n;
  auto inside = [&zones](double x) {
    return std::any_of(zones.begin(), zones.end(), [x](const Zone& z) { return x > z.left.x && x < z.right.x; });
  };
  std::vector<double> g(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i)
    if (inside(grid.x(i))) g[i] = g0[i] + w[i];
  ContactState s;
  require_converged(NormalSolver(kernel).solve(g, P, s), "settled complete-contact");
  std::vector<double> u(n);
  kernel.apply(s.p, u);
  double W = 0.0;
  for (int i = 0; i < n; ++i)
    if (std::isfinite(g0[i])) W += inside(grid.x(i)) ? w[i] : std::max(0.0, -(g0[i] + u[i] - s.approach));
  return W * grid.h();
}

double analogy_delta_top(const ReferenceDatum& datum, double f, const ContactState& normal,
                         const ContactState& corrective, std::vector<double>& q) {
  q.resize(normal.p.size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = f * (normal.p[i] - corrective.p[i]);
  return f * (normal.approach - corrective.approach) + datum.relative_displacement(q, {});
}

double analogy_stick_limit(const ReferenceDatum& datum, double f, const ContactState& normal, std::span<const double> g,
                           std::vector<double>& q) {
  // At Q = fP: q = f p everywhere, and the corrective contact has shrunk onto the lowest point of g (δ* → min g).
  q.resize(normal.p.size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = f * normal.p[i];
  const double g_min = *std::min_element(g.begin(), g.end());
  return f * (normal.approach - g_min) + datum.relative_displacement(q, {});
}

AnalogyDisplacement::AnalogyDisplacement(const Grid& grid, const HalfPlaneKernel& kernel, std::span<const double> g0,
                                         double P, double f, const ReferenceDatum& datum)
    : grid_(grid), g0_(g0), P_(P), f_(f), datum_(datum), solver_(kernel) {
  require_converged(solver_.solve(g0_, P_, normal_), "normal");
  std::vector<double> q;
  stick_limit_ = analogy_stick_limit(datum_, f_, normal_, g0_, q);
}

AnalogyTop AnalogyDisplacement::at(double Q) const {
  ContactState corrective;
  require_converged(solver_.solve(g0_, P_ - Q / f_, corrective), "corrective");
  std::vector<double> q;
  AnalogyTop top;
  top.Q = Q;
  top.delta = analogy_delta_top(datum_, f_, normal_, corrective, q);
  top.stick_zones = locate_zones(grid_, corrective.p, g0_);
  return top;
}

AnalogyTop AnalogyDisplacement::at_displacement(double delta) const {
  if (!(delta > 0.0) || !(delta < stick_limit_))
    throw InputError(fmt::format("at_displacement: δ = {:.6g} m is outside (0, {:.6g}) m, below the stick limit",
                                 delta, stick_limit_));
  const double fP = f_ * P_;
  // δ_top(0) = 0 and δ_top(fP) = δ_s bracket the root; the ends are evaluated in closed form.
  const double Q0 = root(
      [&](double Q) {
        if (Q <= 0.0) return -delta;
        if (Q >= fP) return stick_limit_ - delta;
        return at(Q).delta - delta;
      },
      0.0, fP, "the first cycle's Q");
  return at(Q0);
}

DisplacementLimit displacement_limit(const AnalogyDisplacement& analogy, const Grid& grid, const ElasticPair& pair,
                                     double x_c, double d, double delta, double Q_initial) {
  DisplacementLimit lim;
  lim.Q_initial = Q_initial;
  lim.initial_compliance = delta / Q_initial;
  lim.stick_zones = analogy.at(Q_initial).stick_zones;
  lim.compliance = stuck_compliance(grid, pair, x_c, d, lim.stick_zones);
  lim.Q = delta / lim.compliance;
  if (lim.Q <= Q_initial) return lim;
  // The stick zone shrinks: C(Z(Q)) Q − δ is negative at Q0 (C(Z0) Q0 < δ) and, as the zone shrinks with Q and its
  // compliance grows, positive at δ/C(Z0) and toward fP.
  lim.shrinks = true;
  const double hi = std::min(lim.Q, analogy.friction() * analogy.load() * (1.0 - 1e-9));
  auto excess = [&](double Q) {
    const std::vector<Zone> zones = analogy.at(Q).stick_zones;
    if (zones.empty()) return delta;  // shrunk below a cell: as compliant as the grid can tell, past δ
    return stuck_compliance(grid, pair, x_c, d, zones) * Q - delta;
  };
  const double Q_star = excess(hi) > 0.0 ? root(excess, Q_initial, hi, "the shrunk stick zone's Q") : hi;
  lim.stick_zones = analogy.at(Q_star).stick_zones;
  lim.compliance = stuck_compliance(grid, pair, x_c, d, lim.stick_zones);
  lim.Q = Q_star;
  return lim;
}

}  // namespace fretwear
