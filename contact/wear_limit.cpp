#include "contact/wear_limit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"

namespace fretwear {
namespace {

// K_N at the ends of each stick zone from the complete contact's pressure p on the aligned grid, whose gap g is +∞
// outside the zones: an end is singular where the located contact zone inside it ends at that corner.
std::vector<EdgeIntensities> stick_edge_intensities(const Grid& aligned, const std::vector<double>& p,
                                                    const std::vector<double>& g,
                                                    const std::vector<Zone>& stick_zones) {
  const std::vector<Zone> contact = locate_zones(aligned, p, g);
  std::vector<EdgeIntensities> k(stick_zones.size());
  for (std::size_t s = 0; s < stick_zones.size(); ++s) {
    const double mid = 0.5 * (stick_zones[s].left.x + stick_zones[s].right.x);
    const double length = kEdgeFitFraction * (stick_zones[s].right.x - stick_zones[s].left.x);
    for (const Zone& z : contact) {
      if (z.left.x > mid || z.right.x < mid) continue;  // the contact zone over this stick zone
      if (z.left.method == EdgeMethod::corner) k[s].left = edge_intensity(aligned, p, z.left.x, +1, length);
      if (z.right.method == EdgeMethod::corner) k[s].right = edge_intensity(aligned, p, z.right.x, -1, length);
    }
  }
  return k;
}

}  // namespace

WearLimit wear_limit(const Profile& profile, double A, const Grid& grid, double P,
                     const std::vector<Zone>& stick_zones) {
  const int n = grid.n;
  WearLimit a;
  a.w.assign(n, 0.0);
  a.p.assign(n, 0.0);
  if (stick_zones.empty()) return a;
  auto stuck = [&stick_zones](double x) {
    return std::any_of(stick_zones.begin(), stick_zones.end(),
                       [x](const Zone& z) { return x > z.left.x && x < z.right.x; });
  };
  // The grid aligned to the first zone [c_l, c_r]: whole cells across it, the window shifted by less than a cell.
  const double cl = stick_zones.front().left.x, cr = stick_zones.front().right.x;
  const double h = (cr - cl) / std::max(1.0, std::round((cr - cl) / grid.h()));
  const double lo = cl - std::round((cl - grid.x_min) / h) * h;
  const Grid aligned{lo, lo + n * h, n};
  const HalfPlaneKernel kernel(aligned, A);
  std::vector<double> g0(n), g(n);
  for (int i = 0; i < n; ++i) {
    g0[i] = profile.gap(aligned.x(i));
    g[i] = stuck(aligned.x(i)) ? g0[i] : std::numeric_limits<double>::infinity();
  }
  ContactState state;
  const NormalSolver solver(kernel);
  const SolveSummary s = solver.solve(g, P, state);
  if (!s.converged())
    throw ConvergenceError(fmt::format("wear: the asymptotic complete-contact solve stopped ({}) with residual {:.3g}",
                                       to_string(s.termination), s.residual));
  // The overlap outside the stick zones, on the aligned grid.
  std::vector<double> u(n), w(n, 0.0);
  kernel.apply(state.p, u);
  a.extent = {aligned.x_max, aligned.x_min};
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(g[i]) || !std::isfinite(g0[i])) continue;
    const double overlap = -(g0[i] + u[i] - state.approach);
    if (overlap <= 0.0) continue;
    w[i] = overlap;
    a.worn_area += overlap * h;
    if (overlap > a.max_depth) a.max_depth = overlap, a.x_max_depth = aligned.x(i);
    a.extent = {std::min(a.extent.first, aligned.left(i)), std::max(a.extent.second, aligned.left(i + 1))};
  }
  a.edge_intensities = stick_edge_intensities(aligned, state.p, g, stick_zones);
  // Linear interpolation between aligned centres.
  auto on_aligned = [&](const std::vector<double>& v, double x) {
    const double t = (x - aligned.x_min) / h - 0.5;
    const int i = std::clamp(int(std::floor(t)), 0, n - 2);
    const double f = std::clamp(t - i, 0.0, 1.0);
    return (1.0 - f) * v[i] + f * v[i + 1];
  };
  for (int i = 0; i < n; ++i) {
    a.w[i] = on_aligned(w, grid.x(i));
    a.p[i] = stuck(grid.x(i)) ? on_aligned(state.p, grid.x(i)) : 0.0;
  }
  return a;
}

}  // namespace fretwear
