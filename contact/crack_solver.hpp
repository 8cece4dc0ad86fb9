// Stress intensity factors of a straight surface-breaking crack, normal or inclined to the surface, under the stresses
// the uncracked specimen carries along its line, with unilateral frictional contact between its faces.
//
// Geometry. The crack runs from the surface point (x_c, 0) at an angle α to the surface (90° normal to it; below 90°
// it leans toward +x), along t̂ = (cos α, sin α) to the tip at distance l. Its normal is n̂ = (sin α, −cos α) (n̂ = +x
// at 90°). Along the crack, at distance η from the mouth, the uncracked body carries
//     σ_n = n̂·σ·n̂ = σxx sin²α + σyy cos²α − 2σxy sin α cos α       (opens the crack when > 0),
//     τ   = n̂·σ·t̂ = (σxx − σyy) sin α cos α − σxy cos 2α           (σxx and σxy at 90°).
//
// Method: distributed edge dislocations (Bueckner's superposition; Nowell and Hills 1987; Hills, Kelly, Dai and
// Korsunsky 1996 (HKDK), ch. 2–4). A dislocation in the half-plane y > 0 with a traction-free surface y = 0, at z₀,
// with Burgers vector b = b_x + i b_y, has the Muskhelishvili potentials (HKDK 1996, ch. 2; Dundurs and Mura 1964), with
// γ = μ(b_y − i b_x)/(π(κ + 1)),
//     Φ(z) = γ [1/(z − z₀) − 1/(z − z̄₀)] + γ̄ (z̄₀ − z₀)/(z − z̄₀)²,
//     Ψ(z) = −Φ̄(z) − Φ(z) − z Φ′(z),   Φ̄(z) = conj Φ(z̄),
// (the full-plane dislocation γ/(z − z₀) continued analytically across the free surface), so that
//     σxx + σyy = 4 Re Φ,   σyy − σxx + 2iσxy = 2[(z̄ − z) Φ′(z) − Φ(z) − Φ̄(z)],
// which vanishes on y = 0 (z̄ = z) as it must. Two families of dislocations along the crack line, b = −B₁ n̂ ("climb",
// opening) and b = −B₂ t̂ ("glide", sliding), each carry on the line the Cauchy term 2μB/(π(κ + 1)(η − ξ)) on their
// own traction (σ_n for B₁, τ for B₂) plus regular image terms in both. Normalising η = l(1 + t)/2,
// ξ = l(1 + s)/2, B_j = ((κ + 1)/(2μ)) w(s) φ_j(s) with w(s) = √((1 + s)/(1 − s)) (bounded at the mouth s = −1,
// square-root singular at the tip s = +1), the faces are cleared of the uncracked tractions by
//     (1/π) ∫_{−1}^{1} w(s) [k̂_n1(t, s) φ₁(s) + k̂_n2(t, s) φ₂(s)] ds = −σ_n(t),
//     (1/π) ∫_{−1}^{1} w(s) [k̂_t1(t, s) φ₁(s) + k̂_t2(t, s) φ₂(s)] ds = −τ(t),
// k̂_aj(t, s) the traction a on the line at (1 + t) e^{iα} of a unit dislocation j at (1 + s) e^{iα}, in units of
// 2μ/(π(κ + 1)) and lengths of l/2 (crack_kernel below). φ in Pa. At 90° the line is a mirror line of the half-plane:
// k̂_n2 = k̂_t1 = 0 and
//     k̂_n1 = k̂_t2 = 1/(t − s) − 1/(2 + t + s) − 2(1 + s)/(2 + t + s)² + 4(1 + s)²/(2 + t + s)³   (PHYSICS.md),
// which is what the solver uses there (the two modes uncoupled, N×N each). Gauss–Jacobi quadrature for w (Chebyshev
// polynomials of the third kind V_N; HKDK 1996, ch. 3) with
//     s_i = cos θ_i, θ_i = π(2i − 1)/(2N + 1) (zeros of V_N),  t_k = cos(2πk/(2N + 1)) (zeros of W_N),
//     W_i = 2(1 + s_i)/(2N + 1),   i, k = 1..N,
// turns it into 2N equations Σ_i W_i [k̂_n1(t_k, s_i) φ₁(s_i) + k̂_n2(t_k, s_i) φ₂(s_i)] = −σ_n(t_k) (and the same for
// τ) in 2N unknowns (index 0: no closure condition). The matrix depends on N and α only, not on l.
//
// Tip values. Near s = 1, w φ ≈ √2 φ(1)/√(1 − s), and (1/π) ∫ √2/(√(1 − s)(t − s)) ds → √2/√(t − 1) for t → 1+, so
// ahead of the tip (r = η − l = l(t − 1)/2) the traction is ≈ φ(1) √(l/r) and
//     K_I = lim √(2πr) σ_n = √(2πl) φ₁(1),   K_II = lim √(2πr) τ = √(2πl) φ₂(1),
// i.e. K/(σ0 √(πl)) = √2 φ(1)/σ0. φ(1) = Σ_i L_i(1) φ(s_i), the degree N − 1 polynomial through φ(s_i) at s = 1:
//     L_i(1) = (2/(2N + 1)) (−1)^{i+1} cot(θ_i/2) cos(θ_i/2)          (Krenk 1975; HKDK 1996, ch. 3).
// The matrix M is factorised once (N × N at 90°, 2N × 2N otherwise); each length costs one solve for φ, which also
// gives the opening needed to detect overlapping faces.
// Convergence is algebraic: O(N⁻²) at 90° (N = 80 gives 1.12146 for the edge crack in uniform tension, exact
// 1.121522); an inclined crack's mouth is a corner of two wedges (α and π − α) whose density is not a polynomial
// times w either, and converges more slowly the flatter the crack (test_crack_inclined.cpp measures it).
//
// Signs: K_I > 0 opens the crack. K_II = lim √(2πr) τ ahead of the tip with τ = n̂·σ·t̂ as above: for a crack normal
// to the surface that is PHYSICS.md's σxy (x along the surface, y into the specimen). K_II > 0 means the face on the
// n̂ side (the +x side at 90°, the side below the crack when it leans toward +x) slides toward the tip relative to the
// other face.
//
// Face contact. The opening g(η) and the slip h(η) (the n̂-side face's displacement relative to the other
// along t̂) are, with ∫_t^1 w(s) V_j(s) ds = ∫_0^{θ_t} [cos((j + 1)u) + cos(ju)] du, s = cos θ,
//     g = ((κ + 1) l/(4μ)) ∫_t^1 w φ₁ ds,   h = ((κ + 1) l/(4μ)) ∫_t^1 w φ₂ ds,
// computed exactly for the interpolating polynomial of φ at the collocation points t_k (the matrix Q below). Where
// the open crack would have g(t_k) < 0, the faces are put in contact, point by point on the t_k:
//     open:   σ_n + σ_n^disl = 0,  τ + τ^disl = 0,  g ≥ 0;
//     closed: g = 0,  p = −(σ_n + σ_n^disl) ≥ 0, and Coulomb friction with coefficient f on the total shear T:
//             stick: h = 0 while |T| ≤ f p;   slip: T = f p sign(h) (opposing the slip), with h T ≥ 0.
// An active set over the t_k (open / stick / slip ±) is iterated until no point violates its inequalities (closing
// where g < 0 or where K_I < 0 at an open tip; opening where p < 0; slipping where |T| > f p; sticking where the slip
// reverses): every violating point changes in the first 20 passes, then only the worst one per pass. A zone boundary
// falling between two collocation points can leave the discrete problem without an exact solution, and the set
// cycles. Then the passes start again from the set of the linear complementarity problem the contact poses, with
// the faces' pressure p and shear T at the t_k as loads (g = g₀ + G_p p + G_t T, h = h₀ + H_p p + H_t T through
// M⁻¹): the unknowns (p, b⁺, b⁻, s), T = b⁻ − b⁺, complementary to (g, s + h, s − h, f p − b⁺ − b⁻) (Stewart and
// Trinkle 1996, in two dimensions; (p, g) alone without friction), solved by Lemke's pivoting
// (contact/complementarity.hpp). It is posed on the points whose own compliance G_p,kk is positive; an inclined
// crack's last two or three points at the mouth, a corner the density's polynomial does not resolve, have none, and
// the passes settle them. Where friction makes Lemke's path end on a ray, the frictionless problem's contact set is
// the start. If these passes cycle too, the least violating set of the cycles met is kept if its violation (an
// overlap or a tension, in the units of the load) is below 1e-3 of the largest load on the line; otherwise the
// passes start from the complementarity set again, without friction with each closed point sliding the way the
// faces do (first they slip one way: the shear is zero either way), then with the mouth's points held in the state
// it gave them and their inequalities unchecked (they lie within (1 + t_{N−2})/2 < 0.5 % of l of the mouth), and
// ConvergenceError is thrown if that does not settle either. Each phase of the cycle is solved on its own as loaded proportionally from the uncracked, unloaded
// state: under proportional load the contact and stick zones are fixed, so that one solve is the monotonic history's
// end; the unloading and reloading history within the cycle (reversed slip, locked-in shear) is not modelled. With
// f = 0 at 90° the modes stay uncoupled and K_II is that of the open crack.
//
// Reported: K_I_open and K_II_open of the open crack (K_I_open < 0 where the faces would overlap at the tip); K_I of
// the contact solution, 0 where the faces touch at the tip (closed); K_II of the contact solution with friction.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "contact/subsurface_stress.hpp"

namespace fretwear {

struct CrackSolverOptions {
  int n_quadrature = 60;  // N Gauss–Jacobi nodes; error in K ≈ 0.34/N² relative at 90° (1e-4 at 60); in [2, 1000]
  // Active-set passes of the face-contact solve before giving up (ConvergenceError); ≥ 1.
  int max_contact_iterations = 500;

  // Empty when valid; otherwise names the field, its value and the constraint.
  std::string validate() const;
};

// The crack itself: its inclination and its faces.
struct CrackSpec {
  // Angle to the surface (degrees): 90 normal to it, below 90 leaning toward +x. In [kMinAngle, 180 − kMinAngle]:
  // a flatter crack runs so close to the surface that its images nearly touch it and the quadrature converges too
  // slowly (edge crack in tension: at 15° N = 60 is 5 % off, N = 240 0.2 %; at 10° the open crack's density
  // oscillates into spurious overlaps up to N = 120).
  double angle_deg = 90.0;
  double face_friction = 0.0;  // Coulomb coefficient between the faces where they touch; ≥ 0
  static constexpr double kMinAngle = 15.0;

  // Empty when valid; otherwise names the field, its value and the constraint.
  std::string validate() const;
};

// The SIFs of one crack length.
struct CrackSif {
  double l = 0.0;          // crack length from the mouth to the tip (m)
  double K_I = 0.0;        // Pa√m: the contact solution's, 0 where the faces touch at the tip
  double K_I_open = 0.0;   // Pa√m: the open crack's value, negative where its faces would overlap at the tip
  double K_II = 0.0;       // Pa√m, sign of τ ahead of the tip (header); faces in contact with friction
  double K_II_open = 0.0;  // Pa√m: the open crack's value (faces free to overlap)
  bool closed = false;     // the faces touch at the tip: K_I = 0
  double closed_fraction = 0.0;  // share of the collocation points where the faces touch
  int contact_iterations = 0;    // active-set passes (0: the open crack did not overlap)
  // With face friction, where the passes from the open crack's overlaps cycled and the contact then settled from
  // another start (the complementarity problem's solution, a cycle's set): K_II of the least violating set of those
  // cycles, the solution the passes came near; NaN otherwise. A frictional contact solved for one state alone can
  // have more than one solution, and the other start may land on another than the one the passes approach (the
  // one finer and coarser grids settle on directly): K_II then differs from this.
  double K_II_nearly = std::numeric_limits<double>::quiet_NaN();
};

// The state of the faces at each collocation point, for inspection and tests.
struct CrackFaces {
  enum class State { open, stick, slip };
  std::vector<double> eta;       // distance from the mouth (m), from the tip toward the mouth
  std::vector<double> opening;   // 2μ/(κ + 1) × opening g (Pa·m): ≥ 0 where open, 0 where closed
  std::vector<double> slip;      // 2μ/(κ + 1) × slip h (Pa·m)
  std::vector<double> pressure;  // contact pressure p (Pa), 0 where open
  std::vector<double> shear;     // shear T carried across the faces (Pa), 0 where open
  std::vector<State> state;
  CrackSif sif;
};

struct CrackResult {
  double x_c = 0.0;             // crack mouth on the surface (m)
  std::vector<CrackSif> sifs;   // one per requested length, in the order given
  double seconds = 0.0;         // wall time (tabulation and SIFs)
};

// The kernel k̂_aj(t, s) of the header (Cauchy term included): k[a][j], a = 0 for σ_n, 1 for τ; j = 0 for the
// opening family, 1 for the sliding family. Exposed for tests.
using CrackKernel = std::array<std::array<double, 2>, 2>;
CrackKernel crack_kernel(double angle_deg, double t, double s);

class CrackSolver {
 public:
  using Load = std::function<double(double eta)>;  // a crack-line traction (Pa) at distance η (m) from the mouth

  // Factorises the system. Throws InputError if the options or the crack are invalid.
  explicit CrackSolver(CrackSolverOptions options = {}, CrackSpec crack = {});

  // SIFs of a crack of length l (m) with normal traction σ_n(η) (tension > 0) and shear τ(η) on its line.
  CrackSif sif(double l, const Load& normal, const Load& shear) const;

  // The same, with the state of the faces at the collocation points.
  CrackFaces faces(double l, const Load& normal, const Load& shear) const;

  // SIFs at x = x_c below the tractions for each length in lengths (m, > 0): the stress along the crack line is
  // evaluated at each length's collocation points (stress_along_line), so a length's SIFs are the same whatever
  // other lengths are listed with it.
  CrackResult solve(const SurfaceTractions& t, double x_c, std::span<const double> lengths) const;

  // The open crack's normalised opening density φ₁(s_i) (Pa) of a crack of length l under the normal load σ_n(η)
  // alone: for inspection.
  std::vector<double> density(double l, const Load& load) const;

  const std::vector<double>& nodes() const { return s_; }        // s_i
  const std::vector<double>& collocation() const { return t_; }  // t_k
  const std::vector<double>& tip_weights() const { return L1_; } // L_i(1)
  const CrackSolverOptions& options() const { return options_; }
  const CrackSpec& crack() const { return crack_; }

 private:
  CrackFaces from_loads(double l, std::span<const double> normal, std::span<const double> shear, bool detail) const;
  Eigen::VectorXd open_density(const Eigen::VectorXd& rhs) const;  // φ = M⁻¹ rhs, (φ₁, φ₂)
  CrackSolverOptions options_;
  CrackSpec crack_;
  bool uncoupled_ = true;  // α = 90°
  std::vector<double> s_, t_, L1_;         // nodes, collocation points, tip extrapolation
  Eigen::MatrixXd M_;                      // 2N × 2N: rows (σ_n, τ) at t_k, columns (φ₁, φ₂) at s_i
  Eigen::MatrixXd Q_;                      // N × N: ∫_{t_k}^1 w φ ds = Σ_i Q_ki φ(s_i)
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;  // of M's N×N block at 90°, of M otherwise
};

}  // namespace fretwear
