// Stress intensity factors of a straight surface-breaking crack normal to the surface (x = x_c, 0 ≤ y ≤ l) under
// the stresses the uncracked specimen carries along its line: σxx opens it (mode I), σxy shears it (mode II).
//
// Method: distributed edge dislocations (Bueckner's superposition; Nowell and Hills 1987; Hills, Kelly, Dai and
// Korsunsky 1996 (HKDK), ch. 3–4; paper 000 eq 19). With depths η (field) and ξ (dislocation) along the crack, the
// dislocation density B(ξ) clears the crack faces of the uncracked body's traction σ(η):
//     σ(η) + (2μ / (π(κ + 1))) ∫_0^l B(ξ) k(η, ξ) dξ = 0,   0 < η < l,
//     k(η, ξ) = 1/(η − ξ) − 1/(η + ξ) − 2ξ/(η + ξ)² + 4ξ²/(η + ξ)³           (PHYSICS.md, "Cracks"),
// the same kernel for mode I (climb, σ = σxx) and mode II (glide, σ = σxy): the crack line is a mirror line of the
// half-plane, so the two modes are uncoupled. Normalising η = l(1 + t)/2, ξ = l(1 + s)/2 and
// B = ((κ + 1)/(2μ)) w(s) φ(s) with w(s) = √((1 + s)/(1 − s)) (bounded at the mouth s = −1, square-root singular
// at the tip s = +1) gives
//     (1/π) ∫_{−1}^{1} w(s) φ(s) k̂(t, s) ds = −σ(t),
//     k̂(t, s) = 1/(t − s) − 1/(2 + t + s) − 2(1 + s)/(2 + t + s)² + 4(1 + s)²/(2 + t + s)³,
// φ in Pa. Gauss–Jacobi quadrature for w (Chebyshev polynomials of the third kind V_N; HKDK 1996, ch. 3) with
//     s_i = cos θ_i, θ_i = π(2i − 1)/(2N + 1) (zeros of V_N),  t_k = cos(2πk/(2N + 1)) (zeros of W_N),
//     W_i = 2(1 + s_i)/(2N + 1),   i, k = 1..N,
// turns it into N equations Σ_i W_i k̂(t_k, s_i) φ(s_i) = −σ(t_k) in N unknowns (index 0: no closure condition).
//
// Tip value. Near s = 1, w φ ≈ √2 φ(1)/√(1 − s), and (1/π) ∫ √2/(√(1 − s)(t − s)) ds → √2/√(t − 1) for t → 1+, so
// ahead of the tip (r = η − l = l(t − 1)/2) σ ≈ √2 φ(1)/√(t − 1) = φ(1) √(l/r) and
//     K = lim √(2πr) σ = √(2πl) φ(1),   i.e.  K/(σ0 √(πl)) = √2 φ(1)/σ0.
// φ(1) is the value at s = 1 of the degree N − 1 polynomial through φ(s_i): with the Lagrange basis on the zeros
// of V_N(cos θ) = cos((N + ½)θ)/cos(θ/2), V_N(1) = 1 and V_N′(s_i) = (N + ½)(−1)^{i+1}/(sin θ_i cos(θ_i/2)), so
//     L_i(1) = 1/((1 − s_i) V_N′(s_i)) = (2/(2N + 1)) (−1)^{i+1} cot(θ_i/2) cos(θ_i/2)
//            = (2/(2N + 1)) cot(θ_i/2) sin(N θ_i)                      (Krenk 1975; HKDK 1996, ch. 3),
//     φ(1) = Σ_i L_i(1) φ(s_i).
// The matrix depends on N only, so it is factorised once and the tip functional z = −M⁻ᵀ L(1) is kept: then
// K = √(2πl) z · σ(t_k) for any load and length, one dot product per length and mode. Convergence is O(N⁻²) (the
// density is not the smooth multiple of w the quadrature assumes at the mouth): N = 80 gives 1.12146 for the edge
// crack in uniform tension, whose exact value is 1.121522.
//
// Signs: K_I > 0 opens the crack; K_II = lim √(2πr) σxy ahead of the tip, with x along the surface and y into the
// specimen (PHYSICS.md), i.e. the sign of the shear stress the uncracked body carries there.
//
// Closure: where K_I of the open crack is negative its faces would overlap at the tip; the crack is then reported
// closed, K_I = 0, with the open value beside it. K_II is exact for frictionless faces whether open or closed (the
// modes are uncoupled); face friction, which would reduce it, is not modelled. An open-crack K_I > 0 with overlap
// near the mouth only is not detected.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "contact/subsurface_stress.hpp"

namespace fretwear {

struct CrackSolverOptions {
  int n_quadrature = 60;  // N Gauss–Jacobi nodes; error in K ≈ 0.34/N² relative (1e-4 at 60); in [2, 1000]
  // Depths at which the crack-line stress is tabulated per crack position, y_j = l_max (j/M)², j = 0..M; ≥ 8.
  int table_points = 256;

  // Empty when valid; otherwise names the field, its value and the constraint.
  std::string validate() const;
};

// The SIFs of one crack depth.
struct CrackSif {
  double l = 0.0;         // crack depth (m)
  double K_I = 0.0;       // Pa√m: the open value, or 0 where the faces would overlap at the tip
  double K_I_open = 0.0;  // Pa√m: the open crack's value, negative where its faces would overlap
  double K_II = 0.0;      // Pa√m, sign of σxy ahead of the tip; frictionless faces
  bool closed = false;    // K_I_open < 0
};

struct CrackResult {
  double x_c = 0.0;             // crack position on the surface (m)
  std::vector<CrackSif> sifs;   // one per requested length, in the order given
  double seconds = 0.0;         // wall time (tabulation and SIFs)
};

class CrackSolver {
 public:
  using Load = std::function<double(double eta)>;  // a crack-line stress (Pa) at depth η (m)

  // Factorises the N×N system. Throws InputError if the options are invalid.
  explicit CrackSolver(CrackSolverOptions options = {});

  // SIFs of a crack of depth l (m) with normal traction σ_n(η) (σxx, tension > 0) and shear σxy(η) on its line.
  CrackSif sif(double l, const Load& normal, const Load& shear) const;

  // SIFs at x = x_c below the tractions for each depth in lengths (m, > 0): the crack-line stress is tabulated
  // once (StressLine, to the largest length) and every length reads it at its collocation points.
  CrackResult solve(const SurfaceTractions& t, double x_c, std::span<const double> lengths) const;

  // The normalised density φ(s_i) (Pa) of a crack of depth l under the crack-line load σ(η): for inspection.
  std::vector<double> density(double l, const Load& load) const;

  const std::vector<double>& nodes() const { return s_; }        // s_i
  const std::vector<double>& collocation() const { return t_; }  // t_k
  const std::vector<double>& tip_weights() const { return L1_; } // L_i(1)
  const CrackSolverOptions& options() const { return options_; }

 private:
  CrackSif from_loads(double l, std::span<const double> normal, std::span<const double> shear) const;
  CrackSolverOptions options_;
  std::vector<double> s_, t_, L1_, z_;  // nodes, collocation points, tip extrapolation, tip functional
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;  // M_ki = W_i k̂(t_k, s_i)
};

}  // namespace fretwear
