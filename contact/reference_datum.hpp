// The displacement datum of SCENES.md: in 2D a half-plane's displacement is defined only up to a rigid motion (the
// log kernel), so fretwear measures the relative tangential displacement δ of the two bodies between reference
// points at depth d below the contact centre x_c, one in each body: (x_c, +d) in the specimen, (x_c, −d) in the pad.
// δ > 0 when the pad's point has moved in +x relative to the specimen's, the direction of the force Q > 0 the pad
// exerts on the specimen, so that Q and δ have the same sign on the fretting loop.
//
// Line loads on the half-plane y > 0 (y into the body), a force F in +x and P in +y (compressive) per unit length
// applied at the origin. The stresses are the radial fields of Flamant (Johnson 1985, §2.2, eqs 2.15 and 2.20):
//     σ_xx = −(2/π)(F x³ + P x² y)/r⁴,  σ_yy = −(2/π)(F x y² + P y³)/r⁴,  σ_xy = −(2/π)(F x² y + P x y²)/r⁴.
// Their displacements, with the body's shear modulus μ and κ (3 − 4ν plane strain, (3 − ν)/(1 + ν) plane stress),
// no rotation at infinity (the rotation of these fields decays like 1/r) and the translation fixed so that the
// surface displacement is HalfPlaneKernel's, −(F/π)(κ + 1)/(4μ) ln(|x|/L) (Johnson eq 2.21a; the same L):
//     u_x = −F/(4πμ) [(κ + 1) ln(r/L) + 2 y²/r²] + P/(4πμ) [2 x y/r² − (κ − 1) atan(x/y)],
//     u_y = −F/(4πμ) [(κ − 1) φ − 2 x y/r²] + (normal-load terms, used only to check Hooke's law in the tests),
// φ = atan2(y, x). These are Johnson's eqs 2.19 and 2.21 (Barber, Elasticity, 3rd ed. 2010, §12.5 and §12.6) written
// in Cartesian form; tests/unit/test_reference_datum.cpp checks that they satisfy Hooke's law with the stresses
// above and that the surface limit is the kernel's.
//
// A shear traction q (on the specimen; −q on the pad) and a pressure p over cells of width h: integrated exactly over
// each cell (s = x_c − ξ runs over the cell, r² = s² + d²),
//     ∫ ln(r/L) ds = s ln(r/L) − s + d atan(s/d),  ∫ d²/r² ds = d atan(s/d),
//     ∫ s d/r² ds = (d/2) ln r²,                  ∫ atan(s/d) ds = s atan(s/d) − (d/2) ln r².
// The pad is the mirror image (y → −y) of a half-plane loaded by −q in x and by the same compressive p, so
//     D = u_x,pad(x_c, −d) − u_x,spec(x_c, d) = h Σ_j (g_j q_j + e_j p_j),
//     g_j = Σ_bodies (1/(4πμ)) [(κ + 1) I_ln + 2 I_d] / h,
//     e_j = (1/(4πμ_pad)) [2 I_xy − (κ_pad − 1) I_atan] / h − (the same for the specimen),
// and e = 0 for similar bodies. The rigid shift λ of the pad relative to the specimen in the incremental solver
// (incremental_slip.hpp: the stick condition K q + ε x − λ = const) then gives
//     δ = λ + D(q, p) − D(0, p₀) − ε x_c,
// ε the specimen's bulk strain (its displacement ε x, measured from the reference point), p₀ the pressure under P
// alone: δ = 0 in the unloaded state. The datum length L cancels between λ and D.
//
// Fully stuck Hertz contact (q = Q/(π√(a² − x²)), similar bodies, x_c = 0): λ = −(A Q/π) ln(a/(2L)) and
//     δ/Q = (A/π) ln[(d + √(d² + a²))/a] + (1/(π μ)) d/√(d² + a²),
// the tangential compliance the fretting loop shows at the start of unloading.
//
// Energy: in the half-plane model the rigid shift λ is work-conjugate to Q (∮ Q dλ is exactly the energy the cycle
// dissipates); δ differs from λ by D(q), whose weights vary over the contact by O((a/d)²), so the loop's area equals
// the dissipated energy only to O((a/d)²) (1.4e-3 relative for Hertz at d = 10a; tests/verification).
#pragma once

#include <span>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/grid.hpp"

namespace fretwear {

struct LineLoadDisplacement {
  double ux = 0.0, uy = 0.0;  // m
};

// The displacement at (x, y), y > 0, of a half-plane (shear modulus mu, Pa; kappa) under the line loads F (+x) and
// P (+y, compressive) in N/m at the origin, with the datum length L (m); uy only for F (P = 0 gives the whole uy).
LineLoadDisplacement line_load_displacement(double x, double y, double F, double P, double mu, double kappa, double L);

class ReferenceDatum {
 public:
  // The reference points at depth d (m, > 0) below x_c (m), for the kernel's datum length L = grid.width().
  ReferenceDatum(const Grid& grid, const ElasticPair& pair, double x_c, double d);

  // D(q, p) above (m); q and p per cell (Pa), p may be empty (no pressure term).
  double relative_displacement(std::span<const double> q, std::span<const double> p) const;
  // g_j and e_j above (m/Pa per unit of h Σ), one per cell.
  const std::vector<double>& shear_weights() const { return g_; }
  const std::vector<double>& pressure_weights() const { return e_; }
  double x_c() const { return x_c_; }
  double depth() const { return d_; }

 private:
  double x_c_, d_, h_;
  std::vector<double> g_, e_;
};

// The closed-form fully stuck compliance δ/Q of a Hertz contact of half-width a (m) centred on the reference
// points at depth d (m), similar bodies of shear modulus mu (Pa), composite compliance A (1/Pa): the formula above.
double hertz_stuck_compliance(double A, double mu, double a, double d);

}  // namespace fretwear
