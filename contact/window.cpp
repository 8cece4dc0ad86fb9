#include "contact/window.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "contact/contact_zones.hpp"
#include "common/error.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/load_size.hpp"
#include "contact/normal_solver.hpp"

namespace fretwear {
namespace {

constexpr double kMargin = kWindowMargin;
constexpr int kTrialCells = 512;

// Walks from x0 in direction dir until g0 exceeds level; returns the crossing (or the support's end).
double crossing(const Profile& profile, double x0, double dir, double level) {
  auto [s0, s1] = profile.support();
  double step = 1e-9;
  double inside = x0, outside = x0 + dir * step;
  while (profile.gap(outside) <= level) {
    if (outside <= s0 || outside >= s1 || std::abs(outside - x0) > 1e3) return std::clamp(outside, s0, s1);
    inside = outside;
    step *= 2.0;
    outside = x0 + dir * step;
  }
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (inside + outside);
    (profile.gap(mid) <= level ? inside : outside) = mid;
  }
  return std::clamp(inside, s0, s1);
}

// The lowest point of every asperity of an envelope (recursively), in global x with the tilts of the enclosing nodes
// added: places that may touch however far they lie from the profile's lowest point.
void asperity_minima(const ProfileSpec& s, double shift, double tilt, std::vector<double>& out) {
  if (s.type != ProfileType::envelope) return;
  for (const ProfileSpec& term : s.terms) {
    ProfileSpec alone = term;
    alone.offset_x = shift + s.offset_x + term.offset_x;
    alone.tilt_rad = term.tilt_rad + tilt + s.tilt_rad;
    if (term.type == ProfileType::envelope) {
      asperity_minima(term, shift + s.offset_x, tilt + s.tilt_rad, out);
      continue;
    }
    try {
      out.push_back(Profile(alone).lowest_point());
    } catch (const InputError&) {
      // A term without a lowest point of its own (a lone waviness) adds no separate place.
    }
  }
}

// The places within 100 level-set widths of the lowest point x_low where g0 ≤ level (a scan of kScan points), and
// the lowest point of every asperity of an envelope whose gap is within level: where a load of A P / 2 may touch.
// With `troughs`, also every local minimum of g0 on that scan, however high: a plane contact's approach is not
// bounded by A P / 2 (the troughs of a waviness on a cylinder, R = 9.8 mm, A P / 2 below their gap, were pressed
// 50 µm out while the chosen window held ±20 µm). A periodic profile has none such: its troughs are all the lowest.
std::vector<double> low_places(const Profile& profile, double level, bool troughs = false) {
  const double x_low = profile.lowest_point();
  const double lo = crossing(profile, x_low, -1.0, level), hi = crossing(profile, x_low, +1.0, level);
  const double w = std::max(hi - lo, 1e-9);
  auto [s0, s1] = profile.support();
  const double r0 = std::max(x_low - 100.0 * w, s0), r1 = std::min(x_low + 100.0 * w, s1);
  constexpr int kScan = 20001;
  std::vector<double> places{lo, hi}, g(kScan), xs(kScan);
  for (int i = 0; i < kScan; ++i) {
    xs[i] = r0 + (r1 - r0) * i / (kScan - 1);
    g[i] = profile.gap(xs[i]);
    if (g[i] <= level) places.push_back(xs[i]);
  }
  if (troughs && !profile.periodic())
    for (int i = 1; i + 1 < kScan; ++i)
      if (g[i] > level && g[i] < g[i - 1] && g[i] <= g[i + 1] && std::isfinite(g[i])) places.push_back(xs[i]);
  std::vector<double> asperities;
  asperity_minima(profile.spec(), 0.0, 0.0, asperities);
  for (double x : asperities)
    if (profile.gap(x) <= level) places.push_back(x);
  return places;
}

// The gap at x (outside the trial grid) left by the trial solution: g0 + K p − δ.
double gap_after(const Profile& profile, const HalfPlaneKernel& kernel, const ContactState& state, double x) {
  const Grid& g = kernel.grid();
  double u = 0.0;
  for (int j = 0; j < g.n; ++j)
    if (state.p[j] > 0.0) u += kernel.coefficient(x - g.x(j)) * state.p[j];
  return profile.gap(x) + u - state.approach;
}

}  // namespace

std::vector<double> asperity_lowest_points(const Profile& profile) {
  std::vector<double> points;
  asperity_minima(profile.spec(), 0.0, 0.0, points);
  return points;
}

std::optional<PressedOutside> pressed_outside(const Profile& profile, const HalfPlaneKernel& kernel,
                                              const ContactState& state, double P) {
  if (profile.periodic()) return std::nullopt;  // a lone waviness: its window picks one of equal troughs
  const Grid& g = kernel.grid();
  // Below this the gap is the solution's own round-off (its approach is of the order of A P).
  const double tolerance = 1e-9 * kernel.A() * P;
  std::vector<double> places = low_places(profile, 0.5 * kernel.A() * P, /*troughs=*/true);
  asperity_minima(profile.spec(), 0.0, 0.0, places);  // however high: the approach may exceed A P / 2
  std::optional<PressedOutside> worst;
  for (double x : places) {
    if (x >= g.x_min && x <= g.x_max) continue;
    const double gap = gap_after(profile, kernel, state, x);
    if (gap < -tolerance && (!worst || gap < worst->gap)) worst = PressedOutside{x, gap};
  }
  return worst;
}

Grid align_to_support(const Profile& profile, double x_min, double x_max, int cells) {
  auto [s0, s1] = profile.support();
  const double h0 = (x_max - x_min) / cells;
  const bool left = std::isfinite(s0) && s0 > x_min && s0 < x_max;
  const bool right = std::isfinite(s1) && s1 > x_min && s1 < x_max;
  double h = h0;
  if (left && right) h = (s1 - s0) / std::max(1.0, std::round((s1 - s0) / h0));
  double anchor = left ? s0 : (right ? s1 : x_min);
  const double k = std::round((anchor - x_min) / h);
  const double lo = anchor - k * h;
  return Grid{lo, lo + cells * h, cells};
}

WindowChoice choose_window(const Profile& profile, double A, double P, int cells) {
  const double x_low = profile.lowest_point();
  if (profile.symmetric_single_zone()) {
    const double b = half_width_for_load(profile, A, P);
    return {x_low - (1.0 + kMargin) * b, x_low + (1.0 + kMargin) * b, "load_size", b};
  }

  // Everything within A P / 2 of the lowest gap may touch; look for such places well beyond the first one, and at
  // separate asperities beyond the scan, whose lowest points are known from the profile's tree.
  const double level = 0.5 * A * P;
  // One scan: the places within the level set the trial's first window; the troughs above it (the only places the
  // scan keeps whose gap exceeds the level) are checked as asperities are.
  std::vector<double> places = low_places(profile, level, /*troughs=*/true), asperities;
  const auto troughs = std::stable_partition(places.begin(), places.end(),
                                             [&](double x) { return profile.gap(x) <= level; });
  asperities.assign(troughs, places.end());
  places.erase(troughs, places.end());
  asperity_minima(profile.spec(), 0.0, 0.0, asperities);
  const auto [lowest, highest] = std::minmax_element(places.begin(), places.end());
  double lo = *lowest, hi = *highest;

  // Trial solves: widen until the contact stays off the trial window's ends and no asperity outside the trial window
  // would be pressed through by the trial's approach.
  double c = 0.5 * (lo + hi), half = std::max(0.5 * (hi - lo), 1e-9);
  for (int attempt = 0; attempt < 40; ++attempt, half *= 2.0) {
    const Grid trial = align_to_support(profile, c - 1.5 * half, c + 1.5 * half, kTrialCells);
    std::vector<double> g0(trial.n);
    for (int i = 0; i < trial.n; ++i) g0[i] = profile.gap(trial.x(i));
    HalfPlaneKernel kernel(trial, A);
    NormalSolver solver(kernel, {.tolerance = 1e-6, .max_iterations = 5000});
    ContactState state;
    if (!solver.solve(g0, P, state).converged()) continue;
    const auto zones = locate_zones(trial, state.p, g0);
    if (zones.empty()) continue;
    const bool touches = (zones.front().first_cell == 0 && zones.front().left.method != EdgeMethod::corner) ||
                         (zones.back().last_cell == trial.n - 1 && zones.back().right.method != EdgeMethod::corner);
    if (touches) continue;
    bool missed = false;
    for (double x : asperities) {
      if (x >= trial.x_min && x <= trial.x_max) continue;
      if (gap_after(profile, kernel, state, x) < 0.0) lo = std::min(lo, x), hi = std::max(hi, x), missed = true;
    }
    if (missed) {  // take the asperity in and redo at the same relative margin
      c = 0.5 * (lo + hi);
      half = 0.5 * std::max(0.5 * (hi - lo), 1e-9);
      continue;
    }
    double xl = zones.front().left.x, xr = zones.back().right.x;
    const double bl = 0.5 * (zones.front().right.x - xl), br = 0.5 * (xr - zones.back().left.x);
    // An asperity inside the trial window that its cells passed over (a contact narrower than a cell, its share of
    // the load taken by a cell nearer to another asperity's lowest point) while the trial's approach presses it
    // through: it touches, and the window takes it in.
    for (double x : asperities) {
      if (x < trial.x_min || x > trial.x_max) continue;
      const bool in_zone = std::any_of(zones.begin(), zones.end(), [&](const Zone& z) {
        return x >= z.left.x - trial.h() && x <= z.right.x + trial.h();
      });
      if (!in_zone && gap_after(profile, kernel, state, x) < 0.0) xl = std::min(xl, x), xr = std::max(xr, x);
    }
    // The margin beyond the outer zones: kMargin of their half-widths, and at least two cells of the trial grid and
    // of the run's own (an outer zone at a wave's crest is narrower than a cell of a coarse run, which would put it
    // in the window's end cell: m ≥ 2 (W + 2 m) / cells, W = xr − xl, gives m ≥ 2 W / (cells − 4)).
    const double run_cells = cells > 8 ? 2.0 * (xr - xl) / (cells - 4) : 0.0;
    const double margin_l = std::max({kMargin * bl, 2.0 * trial.h(), run_cells});
    const double margin_r = std::max({kMargin * br, 2.0 * trial.h(), run_cells});
    return {xl - margin_l, xr + margin_r, "trial_solve", 0.0};
  }
  throw InputError("grid: no window up to 1 km keeps the contact off its ends for this profile and load; give "
                   "grid.window");
}

}  // namespace fretwear
