// Load-controlled normal contact of two elastic half-planes on a uniform grid.
//
// Find p ≥ 0 on the cells and a rigid approach δ such that, with g_i = g0_i + (K p)_i − δ,
//     g_i ≥ 0,   p_i g_i = 0,   h Σ p_i = P,
// where K is HalfPlaneKernel's influence matrix and g0 the initial gap (+∞ where the pad has no material: those
// cells never carry load). This is the discrete form of PHYSICS.md's normal-contact equation.
//
// Method: constrained conjugate gradients (Polonsky and Keer 1999, Wear 231, §2 and fig. 1): CG on the current
// contact set with the mean gap removed (this balances δ), projection onto p ≥ 0, re-entry of overlapping cells with
// a restart, and scaling to the load. Warm-started from the caller's p when it has the grid's size; a cold start is
// uniform on the cells with g0 ≤ min g0 + A P / 2 (those that may touch, as choose_window reckons them).
//
// Cost: one Toeplitz product K t per iteration. The elastic displacement u = K p is carried along,
//     u ← u − τ K t + K c,   c = the change that projection and re-entry make to p − τ t,
// with K c summed column by column while c has few nonzeros and replaced by a full product K p otherwise; K p is
// recomputed before convergence is declared, so the residual is never that of a drifted u.
//
// Preconditioner (optional): z = Π_a C⁻¹ Π_a g, with C the 2n circulant that embeds K (its spectrum is the discrete
// form of the kernel's symbol A/|ξ|, so C⁻¹ acts like |ξ|/A, the Hilbert transform of d/dx) and Π_a the restriction to the
// contact set with the mean removed (C is positive definite for the half-plane kernel with the window as datum; the
// solver falls back to none if it is not). Overlapping cells then enter through a preconditioned steepest-descent
// step on the contact set enlarged by them, not at −τ g, which overshoots on fine grids. Each iteration costs two
// products; the default is chosen by measurement (docs/PERFORMANCE.md). Zhao, Vollebregt and Oosterlee (2014)
// deflate such a preconditioner where it stalls; up to n = 65536 on Hertz it does not, and none is used here.
//
// Stopping criterion (ARCHITECTURE.md): the relative complementarity residual
//     r = max( h Σ_i p_i |g_i| / (P g_max),  max_{p_i = 0} (−g_i) / g_max ) ≤ tolerance,
// with g_max the largest finite gap on the grid, or A P if larger (a complete contact has no open gap); the load is
// balanced to round-off at every iterate.
#pragma once

#include <complex>
#include <span>
#include <string>
#include <vector>

#include "contact/half_plane_kernel.hpp"

namespace fretwear {

struct NormalSolverOptions {
  enum class Preconditioner { none, symbol };

  double tolerance = 1e-8;     // on the residual r above; in (0, 1e-2]
  int max_iterations = 20000;  // CG iterations before giving up; ≥ 1
  // none: plain constrained CG; symbol: Π_a C⁻¹ Π_a on the contact set (see above). symbol is 5–7× faster on
  // Hertz from n = 1024 to 65536 (docs/PERFORMANCE.md).
  Preconditioner preconditioner = Preconditioner::symbol;
  // Carry u = K p from one iteration to the next (one product per iteration) instead of recomputing it (two).
  bool incremental_gap = true;
  // Cold start on the cells with g0 ≤ min g0 + A P / 2 instead of on every admissible cell.
  bool cold_start_near = true;
  // Γ of the proportioning test (Dostál and Schöberl 2005, MPRGP): overlapping cells (p = 0, g < 0) enter the
  // contact set only when Σ g² over them exceeds Γ² Σ g² over the contact set; until then CG goes on, conjugate,
  // on the set it has. 0 (the default) lets them in at every iteration, Polonsky and Keer's re-entry. In [0, 1e3).
  // A worn profile near its limit has hundreds of cells at zero gap and zero pressure that would otherwise enter
  // and leave at every iteration: the wear stage uses kWearProportioning there (docs/PERFORMANCE.md, "Where the
  // 4096-cell time went", for what it buys and why plain solves keep 0).
  double proportioning = 0.0;

  // Empty when valid; otherwise names the field, its value and the constraint.
  std::string validate() const;
};

// Γ for solves on worn profiles: measured best of 0.1, 0.3, 1 and 3 on the 4096-cell Hertz wear run.
inline constexpr double kWearProportioning = 0.3;

std::string to_string(NormalSolverOptions::Preconditioner p);

enum class Termination { not_run, converged, max_iterations, non_finite, no_admissible_cell };
std::string to_string(Termination t);

struct SolveSummary {
  Termination termination = Termination::not_run;  // until a solve has run
  int iterations = 0;
  double residual = 0.0;  // r above, at the last iterate
  double seconds = 0.0;   // wall time of the solve
  bool converged() const { return termination == Termination::converged; }
  // One line: termination, iterations, residual, time.
  std::string brief() const;
};

struct ContactState {
  std::vector<double> p;    // pressure per cell (Pa), ≥ 0
  std::vector<double> gap;  // g0 + K p − δ per cell (m), ≥ 0; +∞ where the pad has no material
  double approach = 0.0;    // δ relative to HalfPlaneKernel's datum (m); not a physical output in 2D
};

class NormalSolver {
 public:
  // The kernel must outlive the solver. Throws InputError if the options are invalid.
  NormalSolver(const HalfPlaneKernel& kernel, NormalSolverOptions options = {});

  // Solves for load P (N/m) and initial gap g0 (one value per cell). state.p is used as the starting guess when it
  // has one value per cell and carries load; it is overwritten with the solution.
  SolveSummary solve(std::span<const double> g0, double P, ContactState& state) const;
  // The same with the operator K + diag(shift), shift ≥ 0 per cell (m/Pa): the contact-implicit wear step of
  // ARCHITECTURE.md, where shift = ΔN · (wear coefficient) · (slip per cycle) and the returned gap includes the
  // step's wear. K + diag(shift) is symmetric positive definite on the load-balanced subspace, like K. The
  // preconditioner is then a block one: the symbol where K dominates, Jacobi 1/(K_00 + shift_i) where the shift
  // does; the displacement (K + diag(shift)) p is carried as above.
  SolveSummary solve(std::span<const double> g0, double P, ContactState& state, std::span<const double> shift) const;

  const NormalSolverOptions& options() const { return options_; }

 private:
  // One constrained-CG run; with the preconditioner it also stops when it stalls (solve() then falls back), and
  // without it when plain_stall > 0 iterations have not halved its best residual.
  SolveSummary iterate(std::span<const double> g0, double P, ContactState& state, std::span<const double> shift,
                       bool use_preconditioner, int plain_stall = 0) const;
  const HalfPlaneKernel& kernel_;
  NormalSolverOptions options_;
  bool preconditioned_ = false;  // the options ask for the kernel's inverse spectrum, and C is positive definite
};

}  // namespace fretwear
