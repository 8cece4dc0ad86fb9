// Stresses inside the specimen from the contact tractions on a uniform grid, plus a remote bulk stress.
//
// Conventions (PHYSICS.md): x along the surface, y into the specimen (y ≥ 0), p > 0 in compression, q the traction
// the pad exerts on the specimen in +x. The surface's outward normal is −y, so the traction (q, p) it carries gives
// the free-surface limits
//     σyy → −p,   σxy → −q   as y → 0+,
// and a tension σ_bulk > 0 adds σxx = σ_bulk everywhere.
//
// Each cell carries constant p_i, q_i on [ξ_i, ξ_{i+1}]. Integrating Flamant's line-load stresses (Johnson 1985,
// §2.2 normal and §2.3 tangential force) over a strip gives the uniform strip loads of Johnson (1985) §2.6, which
// we write with X = x − ξ, r² = X² + y², θ = atan2(X, y) ∈ [−π/2, π/2] as a function of one end of the strip:
//     normal p:      F_xx = −(1/π)[θ − Xy/r²],   F_yy = −(1/π)[θ + Xy/r²],   F_xy = −(1/π) X²/r²,
//     tangential q:  G_xx = −(1/π)[ln r² + y²/r²], G_yy = −(1/π) X²/r²,      G_xy = −(1/π)[θ − Xy/r²],
// so that a strip [ξ1, ξ2] carrying p gives σ = p [F(x − ξ1) − F(x − ξ2)] (likewise q with G). Summed over the
// cells by parts, the field is a sum over the cell boundaries ξ_b of the jumps Δp_b = p_b − p_{b−1},
// Δq_b = q_b − q_{b−1} (p_{−1} = p_n = 0):
//     σ(x, y) = Σ_b [Δp_b F(x − ξ_b, y) + Δq_b G(x − ξ_b, y)] + σ_bulk e_x ⊗ e_x.
// Boundaries with no jump (outside the contact) cost nothing; Σ_b Δq_b = 0, so the length unit inside ln r² cancels.
//
// On the surface (y = 0) the limit from inside is returned. Exactly on a cell boundary at y = 0, θ takes the mean of
// its one-sided values (so σyy is the mean of the two pressures) and the term Δq_b ln r², logarithmically singular
// there (the piecewise-constant q jumps), is omitted: keep surface points off the boundaries where q jumps.
#pragma once

#include <span>
#include <vector>

#include "contact/grid.hpp"

namespace fretwear {

// In-plane stress components (Pa).
struct Stress {
  double xx = 0.0, yy = 0.0, xy = 0.0;
};

// The loads on the specimen's surface: a view, the spans must outlive it.
struct SurfaceTractions {
  Grid grid;
  std::span<const double> p;  // pressure per cell (Pa), > 0 in compression
  std::span<const double> q;  // shear traction per cell on the specimen, +x (Pa); empty = none
  double sigma_bulk = 0.0;    // remote σxx in the specimen (Pa), > 0 in tension
};

// σ at (x, y), y ≥ 0 (m). O(number of jumps).
Stress stress_at(const SurfaceTractions& t, double x, double y);

// σ at one x for every depth y_j ≥ 0: the jumps are gathered once and each boundary is visited once per depth.
std::vector<Stress> stress_along_depth(const SurfaceTractions& t, double x, std::span<const double> y);

// σ at the points (x + r cos α, r sin α) of the straight line from the surface point (x, 0) at angle_deg α to the
// surface (in (0, 180); below 90 it leans toward +x), for every distance r ≥ 0 along it: the jumps gathered once.
// At 90° these are stress_along_depth's depths, bit for bit.
std::vector<Stress> stress_along_line(const SurfaceTractions& t, double x, double angle_deg, std::span<const double> r);

// Principal in-plane stresses σ1 ≥ σ2 (Pa) and the angle (rad) from x to σ1's direction:
//     σ1,2 = (σxx + σyy)/2 ± √(((σxx − σyy)/2)² + σxy²),   tan 2α = 2σxy / (σxx − σyy).
struct Principal {
  double s1 = 0.0, s2 = 0.0, angle = 0.0;
};
Principal principal(const Stress& s);

// Von Mises equivalent stress (Pa) in plane strain, σzz = ν(σxx + σyy):
//     σ_vm = √( ½[(σxx − σyy)² + (σyy − σzz)² + (σzz − σxx)²] + 3σxy² ).
double von_mises(const Stress& s, double nu);

}  // namespace fretwear
