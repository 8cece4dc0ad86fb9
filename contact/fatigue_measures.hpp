// Multiaxial fatigue measures for comparing fretting designs: Smith–Watson–Topper on critical planes, and Ruiz's
// parameters along the surface.
//
// Smith–Watson–Topper on critical planes (Smith, Watson and Topper 1970, J. Materials 5, 767, who correlate life
// with σ_max ε_a; taken plane by plane for fretting by Szolwinski and Farris 1996, Wear 198, 93). The in-plane
// stresses σxx, σyy, σxy are given at K ≥ 2 instants of the cycle (fretwear: its top and its bottom). A plane
// through the point is named by the angle θ ∈ [0, π) of its unit normal n = (cos θ, sin θ) from +x toward +y (y into
// the specimen): θ = 0 is a plane normal to the surface (a crack growing straight down), θ = π/2 a plane parallel to
// it. Only planes containing the z axis (normal to the plane of the analysis) are scanned. On a plane
//     σ_n(θ) = σxx cos²θ + σyy sin²θ + 2 σxy sin θ cos θ,
// and Hooke's law, ε = [(1 + ν) σ − ν tr(σ) I]/E, gives the normal strain
//     ε_n(θ) = [(1 + ν) σ_n(θ) − ν tr σ]/E,   tr σ = σxx + σyy + σzz,
// with σzz = ν(σxx + σyy) in plane strain (so tr σ = (1 + ν)(σxx + σyy)) and σzz = 0 in plane stress. Over the
// instants k,
//     SWT(θ) = max_k σ_n,k(θ) · [max_k ε_n,k(θ) − min_k ε_n,k(θ)] / 2        (Pa, i.e. J/m³),
// and the critical plane is the θ that maximises it: SWT_max = SWT(θ_crit). SWT < 0 on every plane means no plane
// through the point is ever in tension. A uniaxial σxx cycling between σ_min and σ_max in plane strain gives
// SWT = σ_max (σ_max − σ_min)/(2E′), E′ = E/(1 − ν²), on θ = 0.
//
// Ruiz parameters (Ruiz, Boddington and Chen 1984, Exp. Mech. 24, 208; Ruiz and Chen 1986, "Life assessment of
// dovetail joints between blades and discs in aero-engines", IMechE Fatigue of Engineering Materials and
// Structures, C141/86; applied to partial slip by Nowell and Hills 1990, Wear 136, 329), point by point along the
// surface:
//     F1 = τ δ            (Pa·m = J/m²: the frictional work, a measure of surface damage),
//     F2 = σ_T τ δ        (Pa²·m: crack initiation),
// with τ = |q| the shear traction at the top of the cycle, δ the slip amplitude (half the peak-to-peak slip range)
// and σ_T = max(σxx, 0) the surface tangential stress at the top of the cycle where tensile. Where the surface
// sticks δ = 0 and both vanish; where it is compressed F2 vanishes.
#pragma once

#include <span>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/subsurface_stress.hpp"

namespace fretwear {

// Normal stress σ_n(θ) on the plane whose normal is at θ (rad) from +x toward +y (Pa).
double normal_stress(const Stress& s, double theta);

// Normal strain ε_n(θ) on that plane by Hooke's law, σzz from the plane state (header).
double normal_strain(const Stress& s, double theta, const Material& m, PlaneState plane);

// SWT(θ) = max_k σ_n,k · Δε_n/2 over the instants `states` (Pa).
double swt_on_plane(std::span<const Stress> states, double theta, const Material& m, PlaneState plane);

struct SwtOptions {
  int n_scan = 180;                // planes scanned over [0, π): a step of π/n_scan (1°)
  double theta_tolerance = 1e-7;   // rad: the golden-section refinement around the best scanned plane stops here
};

struct SwtResult {
  double swt = 0.0;          // SWT on the critical plane (Pa = J/m³)
  double theta = 0.0;        // the critical plane's normal, from +x toward +y, in [0, π) (rad)
  double sigma_n_max = 0.0;  // the largest normal stress on it over the cycle (Pa)
  double delta_eps_n = 0.0;  // its normal strain range over the cycle
};

// The critical plane: SWT(θ) at n_scan planes, then a golden-section search over the two scan steps around the
// best, keeping the better of the two. Needs at least two states.
SwtResult swt_critical_plane(std::span<const Stress> states, const Material& m, PlaneState plane,
                             const SwtOptions& options = {});

// Ruiz's F1 and F2 at points x along the surface (header); all spans of one size.
struct RuizProfile {
  std::vector<double> x;        // m
  std::vector<double> sigma_t;  // σxx at the surface, top of the cycle (Pa), signed (F2 uses its tensile part)
  std::vector<double> tau;      // |q| at the top of the cycle (Pa)
  std::vector<double> delta;    // slip amplitude (m)
  std::vector<double> F1;       // τ δ (Pa·m = J/m²)
  std::vector<double> F2;       // max(σ_T, 0) τ δ (Pa²·m)
  // The peaks and where; peaks within 1e-6 relative of each other are ties, won by the smallest x (the trailing side
  // of a cycle that is symmetric in x).
  double F1_max = 0.0, F1_max_x = 0.0;  // J/m², m
  double F2_max = 0.0, F2_max_x = 0.0;  // Pa²·m, m
};

// σ_t: surface σxx at the top of the cycle; q: shear traction at the top; delta: slip amplitude.
RuizProfile ruiz(std::span<const double> x, std::span<const double> sigma_t, std::span<const double> q,
                 std::span<const double> delta);

// Ruiz at the cell centres of the grid: σxx from the tractions at the top of the cycle (stress_at at y = 0, cell
// centres being off the boundaries where q jumps), τ = |q_top|, δ = slip_range/2 (slip_range peak to peak, m).
RuizProfile ruiz_along_surface(const SurfaceTractions& top, std::span<const double> slip_range);

}  // namespace fretwear
