#include "contact/tangential_solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/error.hpp"

namespace fretwear {

std::string to_string(Regime r) {
  switch (r) {
    case Regime::partial_slip: return "partial_slip";
    case Regime::reverse_slip: return "reverse_slip";
    case Regime::gross_slip: return "gross_slip";
  }
  return "?";
}

TangentialSolver::TangentialSolver(const HalfPlaneKernel& kernel, TangentialSolverOptions options)
    : kernel_(kernel), options_(options), normal_(kernel, options.normal) {}

ContactState TangentialSolver::corrective(std::span<const double> g0, double tilt, double L,
                                          const ContactState& start, CycleResult& result) const {
  const Grid& grid = kernel_.grid();
  std::vector<double> g(grid.n);
  for (int i = 0; i < grid.n; ++i) g[i] = g0[i] - tilt * grid.x(i);
  ContactState state;
  state.p = start.p;
  const SolveSummary s = normal_.solve(g, L, state);
  result.solves.push_back(s);
  if (!s.converged())
    throw ConvergenceError(fmt::format("cyclic slip: the corrective normal problem at load {:.6g} N/m stopped ({}) "
                                       "with residual {:.3g}",
                                       L, to_string(s.termination), s.residual));
  return state;
}

CycleResult TangentialSolver::solve_cycle(std::span<const double> g0, const ContactState& contact,
                                          const std::vector<Zone>& zones, const CyclicLoad& load) const {
  const Grid& grid = kernel_.grid();
  const int n = grid.n;
  const double f = load.f, P = load.P, Q = load.Q_max;
  CycleResult r;
  if (Q >= f * P) {
    r.regime = Regime::gross_slip;
    r.message = fmt::format("Q = {:.6g} N/m reaches f P = {:.6g} N/m: the bodies slide, and under force control the "
                            "slip is not determined",
                            Q, f * P);
    return r;
  }

  const std::vector<double>& p = contact.p;
  // Top of the cycle: p* at P − Q/f with tilt ε/f. Unloaded: p** at P − Q/(2f) with tilt ε/(2f).
  const ContactState top = corrective(g0, load.bulk_strain / f, P - Q / f, contact, r);
  const ContactState mid = corrective(g0, load.bulk_strain / (2.0 * f), P - Q / (2.0 * f), contact, r);

  // The analogy holds while the stick zone lies inside the contact: every cell p* loads must be loaded by p.
  for (int i = 0; i < n; ++i) {
    if (top.p[i] > 0.0 && !(p[i] > 0.0)) {
      r.regime = Regime::reverse_slip;
      r.message = fmt::format("the stick zone of the analogy reaches beyond the contact at x = {:.6g} m: the "
                              "leading edge slips backwards (reverse slip), which needs the incremental route",
                              grid.x(i));
      return r;
    }
  }

  const std::vector<double> g_top(top.gap.begin(), top.gap.end());
  r.q_top.resize(n);
  r.q_unloaded.resize(n);
  r.q_bottom.resize(n);
  r.q_reloaded.resize(n);
  r.slip_range.assign(n, 0.0);
  r.slip_travelled.assign(n, 0.0);
  r.energy_density.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    r.q_top[i] = f * (p[i] - top.p[i]);
    r.q_unloaded[i] = f * (-p[i] - top.p[i] + 2.0 * mid.p[i]);
    r.q_bottom[i] = -r.q_top[i];
    r.q_reloaded[i] = -r.q_unloaded[i];
    if (p[i] > 0.0 && !(top.p[i] > 0.0)) {
      const double gs = std::max(g_top[i], 0.0);
      r.slip_range[i] = 2.0 * f * gs;
      r.slip_travelled[i] = 4.0 * f * gs;
      r.energy_density[i] = f * p[i] * r.slip_travelled[i];
      r.dissipated_energy += r.energy_density[i] * grid.h();
    }
    r.slip_max = std::max(r.slip_max, r.slip_range[i]);
  }

  const auto stick = locate_zones(grid, top.p, g0);
  // The slip range peaks at the contact's outer edges, inside a cell: g* is smooth there, so interpolate it at the
  // located edge between the cell centres that straddle it. Not where the stick zone reaches the edge: its slip zone
  // is narrower than a cell, g* is 0 at the edge to within it, and the interpolation would read the gap beyond the
  // contact (a slip of the order of the gap one cell out, where the load's is far below it).
  const auto stuck = [&](double xe) {
    const double tol = 1e-9 * grid.h();
    return std::any_of(stick.begin(), stick.end(), [&](const Zone& s) {
      return s.left.x <= xe + tol && xe - tol <= s.right.x;
    });
  };
  for (const Zone& z : zones) {
    for (double xe : {z.left.x, z.right.x}) {
      if (stuck(xe)) continue;
      const double s = (xe - grid.x_min) / grid.h() - 0.5;
      const int i0 = std::clamp(int(std::floor(s)), 0, n - 2);
      const double w = std::clamp(s - i0, 0.0, 1.0);
      if (!std::isfinite(g_top[i0]) || !std::isfinite(g_top[i0 + 1])) continue;
      const double gs = std::max((1.0 - w) * g_top[i0] + w * g_top[i0 + 1], 0.0);
      r.slip_max = std::max(r.slip_max, 2.0 * f * gs);
    }
  }

  for (const Zone& z : stick) r.stick_zones.emplace_back(z.left.x, z.right.x);
  if (!stick.empty()) r.stick_zone = Interval{stick.front().left.x, stick.back().right.x};
  const auto stick_mid = locate_zones(grid, mid.p, g0);
  if (!stick_mid.empty()) r.stick_zone_unloaded = Interval{stick_mid.front().left.x, stick_mid.back().right.x};
  return r;
}

}  // namespace fretwear
