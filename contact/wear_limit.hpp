// The state fretting wear tends to under a tangential load between fixed limits (Ciavarella and Hills 1999, "Some
// observations on oscillating tangential forces and wear in general plane contacts", Eur. J. Mech. A/Solids 18,
// §3.2 "Steady state limit"; paper 002, PHYSICS.md "Wear").
//
// Wear needs pressure and slip, so it never enters the stick zones S of the first cycle, and under a fixed Q range
// they stay where they started. Wear stops when the slip zones carry no pressure: the limit is a complete contact
// over S on the original profile g0 under the load P,
//     g0(x) + (K p)(x) − δ = 0  for x in S,   p = 0 outside S,   ∫ p dx = P,
// with K the half-plane influence operator of the composite compliance A = 2/E* (contact/half_plane_kernel.hpp).
// The worn depth (both bodies together) is the overlap that state leaves outside S,
//     w(x) = max(0, −(g0(x) + (K p)(x) − δ)),   W = ∫ w dx,
// which reaches past the original contact (Hertz: x_e > a). Any number of stick zones is allowed (two asperities:
// §2 of the paper).
//
// Discretisation: one NormalSolver solve with the gap set to +∞ outside S, on a grid of the caller's cell count whose
// cell boundaries fall on the first stick zone's edges, so that the complete contact's corners there are exact, as
// for a sharp punch (whole cells of the caller's grid would misplace them by up to h/2); other zones' corners are
// placed to within half a cell. p and w are then interpolated linearly onto the caller's grid (the grids differ by
// less than a cell).
//
// The pressure is square-root singular at every end of a stick zone the complete contact reaches (Hertz:
// p = P[1 + (c² − 2x²)/a²] / (π√(c² − x²)), K_N = P(1 − c²/a²)/√(πc)); its edge intensities are fitted on the aligned
// grid, where those ends are cell boundaries (contact/edge_intensity.hpp, over kEdgeFitFraction of each zone's length).
//
// The caller supplies the stick zones (e.g. from the analogy route's first cycle, contact/contact_zones.hpp) and
// decides whether the limit applies: it assumes stick zones that do not move, which holds under force control.
#pragma once

#include <utility>
#include <vector>

#include "contact/contact_zones.hpp"
#include "contact/edge_intensity.hpp"
#include "contact/grid.hpp"
#include "contact/profile.hpp"

namespace fretwear {

struct WearLimit {
  std::vector<double> p;                  // pressure on the caller's grid (Pa), zero outside the stick zones
  std::vector<double> w;                  // worn depth on the caller's grid, both bodies together (m)
  double worn_area = 0.0;                 // W = ∫ w dx (m²)
  double max_depth = 0.0;                 // m
  double x_max_depth = 0.0;               // where w is deepest (m)
  std::pair<double, double> extent{0.0, 0.0};  // where w > 0, outer ends (m)
  // K_N at the ends of each stick zone, left to right (Pa·m^0.5); an end is empty where the complete contact does not
  // reach it (the pressure falls to zero inside the zone) or the zone is too short to fit.
  std::vector<EdgeIntensities> edge_intensities;
};

// The limit for the profile on `grid` (its cell count and window), the composite compliance A (1/Pa), the normal
// load P (N/m) and the stick zones of the first cycle, left to right. No stick zone: p and w zero. Throws
// ConvergenceError when the complete-contact solve does not converge.
WearLimit wear_limit(const Profile& profile, double A, const Grid& grid, double P,
                     const std::vector<Zone>& stick_zones);

}  // namespace fretwear
