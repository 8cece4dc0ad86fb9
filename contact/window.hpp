// The default window of the grid: it covers the expected contact with a margin of half the outer zones' half-widths
// on each side (SCENES.md, "Grid"), and puts the pad's corners (a sharp punch, a table's ends) on cell boundaries.
//
// - Symmetric single-zone profiles: the load–size integral gives the half-width b exactly; the window is
//   x_low ± 1.5 b.
// - Anything else: every x with g0(x) ≤ A P / 2 (in 2D the approach scales like A P: for a wedge this is the exact
//   half-width, for Hertz 1.25 a) may touch; a coarse trial solve over that set, widened until the contact stays off
//   the trial window's ends, gives the zones, and the window is their extent plus the margin. The separate asperities
//   of an envelope are found however far apart they are: each one's lowest point is a candidate, taken in when its
//   gap is within A P / 2 or when the trial solution would press it through (beyond the trial window, or within it
//   where its cells, wider than the contacts, passed over it).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contact/grid.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "contact/profile.hpp"

namespace fretwear {

// The chosen window's margin beyond the outer zones, as a share of their half-widths, each side.
inline constexpr double kWindowMargin = 0.5;

struct WindowChoice {
  double x_min = 0.0, x_max = 0.0;  // m
  std::string method;               // "load_size", "trial_solve" or "given"
  double expected_half_width = 0.0; // the load–size half-width when method is load_size (m), else 0
};

// Throws InputError when the load cannot be placed (a trial contact keeps reaching the ends of a 1 km window).
WindowChoice choose_window(const Profile& profile, double A, double P, int cells);

// Where a solution on a window leaves the pad pressed through beyond it: the place outside the kernel's grid with
// the most negative gap g0 + K p − δ (m) that the solution (state: p on the grid and the approach δ) leaves there,
// among the places where the profile may touch (within A P / 2 of its lowest gap, 100 level-set widths around it)
// and the lowest point of every asperity of an envelope, however far and high. In 2D the surface outside the loaded
// cells approaches more than at their outer edges (the log kernel), so an asperity as low as the contact's edges
// beyond the window is pressed through. None for a lone waviness (periodic), whose window picks one of equal troughs,
// and none below 1e-9 A P (round-off).
struct PressedOutside {
  double x = 0.0;    // m
  double gap = 0.0;  // m, < 0
};
std::optional<PressedOutside> pressed_outside(const Profile& profile, const HalfPlaneKernel& kernel,
                                              const ContactState& state, double P);

// The lowest point of every asperity of an envelope (recursively, in global x), however far apart; empty for any
// other profile.
std::vector<double> asperity_lowest_points(const Profile& profile);

// Shifts and stretches [x_min, x_max] by less than a cell so that the finite ends of the profile's support fall on
// cell boundaries of an n-cell grid.
Grid align_to_support(const Profile& profile, double x_min, double x_max, int cells);

}  // namespace fretwear
