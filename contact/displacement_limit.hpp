// The fretting wear limit under displacement control, below the stick limit: the reference points of the datum
// (contact/reference_datum.hpp) cycle ±δ, similar bodies, a constant P, no bulk stress.
//
// The first cycle. For similar bodies the steady cycle at a tangential load Q is Ciavarella–Jäger's (paper 002's
// analogy, PHYSICS.md "Partial slip"): q_top = f (p − p*), p the pressure under P and p* the corrective pressure of
// the same profile under P − Q/f, whose contact is the stick zone. Inside it K p = δ_P − g0 and K p* = δ* − g0
// (δ_P, δ* the two solves' approaches), so the rigid shift at the top of the cycle is λ = f (δ_P − δ*) and the
// datum gives
//     δ_top(Q) = f (δ_P − δ*(Q)) + D(q_top),
// which rises from 0 at Q = 0 to the stick limit δ_s = f (δ_P − min g0) + D(f p) at Q = fP (the corrective contact
// shrinks onto the first point of the profile to touch). The first cycle's Q0 solves δ_top(Q0) = δ (Boost.Math's
// toms748); δ ≥ δ_s slides (gross slip: no stick zone, and the wear never stops).
//
// The limit. Wear needs pressure and slip, so at the limit the slip zones carry neither pressure nor shear and the
// contact is the stick zone Z alone, a complete contact fully stuck all through the cycle: its shear solves
// K q = λ on Z (one rigid shift for every zone), whatever the profile there, so δ = C(Z) Q with C the stuck
// compliance of that complete contact,
//     C(Z) = λ₁ + D(q₁),   q₁ the stuck shear under a unit Q,
// measured by the datum (on Z = [−c, c] the flat-punch shear Q/(π√(c² − x²)), and C is hertz_stuck_compliance with
// a → c). Before the limit the slip zones carry shear of the sign of Q, farther out than Z, where the log kernel has
// fallen: by reciprocity (∫ q₁ K q = ∫ q K q₁) the same Q over Z alone moves the pad further, so C(Z0) exceeds the
// first cycle's δ/Q0 (to within the datum's O((a/d)²) variation over the contact), and as the slip zones wear Q
// falls from Q0 toward δ/C(Z0). A falling Q cannot shrink the stick zone, so Z0 never slips, and a complete contact
// over Z0 on the original profile, under P and fully stuck under δ/C(Z0), is a state at which the wear stops:
// displacement_limit() gives it (paper 002's limit at Q0, with Q = δ/C(Z0)). Were δ/C(Z0) above Q0, the stick zone
// would shrink instead, and the limit would be the analogy's zone Z(Q*) at the Q* with C(Z(Q*)) Q* = δ (`shrinks`).
//
// What this leaves out (docs/METHODS.md, "Wear under displacement control"): as Q falls the stick zone also grows,
// early in the run, over points beside it that slipped a little and wore a little before the falling Q closed the
// corrective gap there; the run then settles on a zone between Z0 and Z(Q*), path-dependent, and below the worn area
// over Z0 (Hertz: by 3.5 % at δ = 0.41 δ_s, about 11 % at 0.82 δ_s).
#pragma once

#include <span>
#include <vector>

#include "contact/contact_zones.hpp"
#include "contact/elastic_pair.hpp"
#include "contact/grid.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "contact/reference_datum.hpp"

namespace fretwear {

// The stuck compliance C(Z) = δ/Q (m²/N) of a complete contact over the zones Z of the grid's window, fully stuck,
// for similar bodies of the pair, measured by reference points at depth d (m) below x_c (m). Solved on a grid of
// the same cell count aligned to the first zone's ends (as wear_limit() does), so that the corners there are cell
// boundaries. Throws ConvergenceError when the solve stops short, InputError without a zone.
double stuck_compliance(const Grid& grid, const ElasticPair& pair, double x_c, double d, const std::vector<Zone>& zones);

// The top of the analogy's steady cycle at one Q.
struct AnalogyTop {
  double Q = 0.0;                 // N/m
  double delta = 0.0;             // δ_top, m
  std::vector<Zone> stick_zones;  // the corrective contact's zones, left to right
};

// δ_top of the analogy's cycle (header) from its two solves on one gap: the normal contact under P and the corrective
// one under P − Q/f, f (δ_P − δ*) + D(q_top) with q_top = f (p − p*) (m). q: scratch, resized to the grid.
double analogy_delta_top(const ReferenceDatum& datum, double f, const ContactState& normal,
                         const ContactState& corrective, std::vector<double>& q);
// The stick limit δ_s = f (δ_P − min g) + D(f p) of the normal contact under P on the gap g (header; m).
double analogy_stick_limit(const ReferenceDatum& datum, double f, const ContactState& normal, std::span<const double> g,
                           std::vector<double>& q);

// δ_top(Q) on the unworn profile and its inverse (header). Similar bodies, no bulk stress; the grid, kernel, g0 and
// datum must outlive it.
class AnalogyDisplacement {
 public:
  // Solves the normal contact under P (N/m); f the friction coefficient. Throws ConvergenceError when it stops short.
  AnalogyDisplacement(const Grid& grid, const HalfPlaneKernel& kernel, std::span<const double> g0, double P, double f,
                      const ReferenceDatum& datum);
  // The cycle's top at Q in (0, fP). Throws ConvergenceError when the corrective solve stops short.
  AnalogyTop at(double Q) const;
  // δ_s, the displacement at which the contact starts to slide (m).
  double stick_limit() const { return stick_limit_; }
  double load() const { return P_; }        // P, N/m
  double friction() const { return f_; }    // f
  // The Q0 with δ_top(Q0) = delta, 0 < delta < stick_limit(), to a relative 2⁻⁴⁰ (toms748); its top.
  AnalogyTop at_displacement(double delta) const;

 private:
  const Grid& grid_;
  std::span<const double> g0_;
  double P_, f_;
  const ReferenceDatum& datum_;
  NormalSolver solver_;
  ContactState normal_;
  double stick_limit_ = 0.0;
};

// The limit of a worn state whose stick zones Z stand still from now on: their cells no longer wear, so it is the
// complete contact over Z on the worn profile g0 + w under P (cells whose centres lie in Z), and its worn depth is w
// inside Z and the overlap that contact leaves outside. Returns its worn area (m²). Z's ends should be cell
// boundaries, as a run's stick zones are. Throws ConvergenceError when the solve stops short.
double settled_worn_area(const Grid& grid, const HalfPlaneKernel& kernel, std::span<const double> g0,
                         std::span<const double> w, double P, const std::vector<Zone>& zones);

// The limit under displacement control (header).
struct DisplacementLimit {
  double Q_initial = 0.0;         // Q0, the first cycle's (N/m)
  double Q = 0.0;                 // at the limit, δ / C(Z) (N/m)
  double compliance = 0.0;        // C(Z), m²/N
  double initial_compliance = 0.0;  // the first cycle's δ / Q0, m²/N
  std::vector<Zone> stick_zones;  // Z: the first cycle's (Z0), or Z(Q*) where the stick zone shrinks
  bool shrinks = false;           // δ/C(Z0) > Q0: the stick zone shrinks to Z(Q*)
};

// The limit for the reference points' amplitude delta (m), 0 < delta < analogy.stick_limit(), with the first cycle
// at Q_initial (analogy.at_displacement(delta).Q; a test may give another to reach the shrinking branch). The shrunk
// zone's Q* is found by toms748 on (Q_initial, min(δ/C(Z0), fP)).
DisplacementLimit displacement_limit(const AnalogyDisplacement& analogy, const Grid& grid, const ElasticPair& pair,
                                     double x_c, double d, double delta, double Q_initial);

}  // namespace fretwear
