// Cyclic partial slip by load increments: the incremental route of ARCHITECTURE.md, first for similar bodies
// (Dundurs β = 0, so the pressure p of the normal solve under the constant P is fixed; dissimilar bodies, whose
// pressure moves with the shear, are at the end of this comment) under force control, with the
// tangential load Q(t) cycling 0 → +Q → −Q → +Q … and a bulk tension in phase, ε(t) = ε Q(t)/Q.
//
// For similar bodies a shear traction q on the cells changes the relative tangential surface displacement by K q,
// with the same influence matrix K and compliance A as the normal problem (HalfPlaneKernel; PHYSICS.md,
// "Conventions": at β = 0 the normal and tangential problems are uncoupled). The bulk strain adds ε x (Nowell and
// Hills 1987, as PHYSICS.md, "Bulk tension", states it: in the stick zone (1/π) ∫ q/(x − ξ) dξ = ε/A). With s = K q + ε x − (a rigid shift), stick cells keep s fixed and a slipping cell
// moves by Δw = −Δs at |q| = f p with q Δw ≥ 0 (Coulomb). This sign reproduces Cattaneo–Mindlin and the analogy route
// (tangential_solver.hpp): under a proportional load both solve the same discrete problem.
//
// One increment, from (q_prev, ε_prev) to (Q, ε): with b = K q_prev − (ε − ε_prev) x, solve the convex quadratic
// program
//     min ½ qᵀ K q − qᵀ b   subject to   −f p_i ≤ q_i ≤ f p_i,   h Σ q_i = Q,
// on the contact cells (p_i > 0; q = 0 elsewhere). K is symmetric positive definite (the window as datum), so the
// solution is unique, and its KKT conditions with multiplier λ for the load are the contact laws: with
// Δs_i = (K (q − q_prev))_i + (ε − ε_prev) x_i − λ,
//     −f p_i < q_i < f p_i  ⇒  Δs_i = 0   (stick: the increment is a rigid shift),
//     q_i = +f p_i          ⇒  Δs_i ≤ 0   (forward slip, Δw = −Δs_i ≥ 0),
//     q_i = −f p_i          ⇒  Δs_i ≥ 0   (backward slip).
//
// Method: constrained conjugate gradients with two-sided bounds, after Polonsky and Keer (1999, Wear 231, §2):
// CG on the free cells with the mean residual removed (this is λ and keeps h Σ q = Q), cells at a bound whose
// residual points inward added to the working set with a restart, and after each step the Euclidean projection
// onto {box, h Σ q = Q} over the working set (a uniform shift μ and a clamp; μ = 0 unless a cell hit a bound, as
// the direction sums to zero). Preconditioner, as NormalSolver's: z = Π_W C⁻¹ Π_W g with C the 2n circulant that
// embeds K; it falls back to plain CG if it stalls. Warm-started from the previous increment.
//
// Stopping criterion: the largest KKT violation relative to the increment's slip scale,
//     r = max( max_free |Δs_i|, max_{q = +fp} max(Δs_i, 0), max_{q = −fp} max(−Δs_i, 0) ) / d,
//     d = A |Q − Q_prev| + |ε − ε_prev| ℓ   (ℓ: the half-width of the loaded cells' span),
// with λ the mean of Δs + λ over the free cells; the load is balanced to round-off at every iterate. Relative to d
// the errors of the increments do not add up with their number: a cycle's slip is accurate to about r A Q.
//
// Cycle bookkeeping: per cell the slip w accumulates Δw (zero on the cells that stick in the increment); the slip
// range is max w − min w over the cycle, the slip travelled Σ |Δw|, the energy density Σ q Δw (q at the end of the
// increment, at ±f p where Δw ≠ 0, so every term is f p |Δw| ≥ 0; a bound cell whose Δw has the wrong sign by less
// than the tolerance is counted as sticking).
//
// The fretting loop: given a ReferenceDatum the solver records, at the end of every increment, δ = λ + D(q, p) −
// D(0, p) − ε x_c (contact/reference_datum.hpp), λ the rigid shift summed over the increments (the multiplier above).
//
// Displacement control (CyclicLoad::delta > 0; needs the datum): δ cycles 0 → +δ → −δ → +δ and the bulk strain follows
// it. Prescribing δ instead of Q replaces the load constraint by δ = λ + D(q, p) − …, whose weights are not uniform
// over the cells, so the KKT system is no longer that of a symmetric program; instead each increment solves the
// force-controlled program above for the Q whose δ(Q) is the target. From a given state δ(Q) is continuous and
// increasing (its slope is the tangential compliance, positive for any d > 0), so a bracket grown from the secant
// guess Q_prev + Δδ/(last compliance) and the Illinois false position find it, warm-started from evaluation to
// evaluation (three to six solves an increment), to |δ(Q) − target| ≤ 10 · tolerance · |Δδ|. The bracket ends at
// Q = ±f P, where every cell is at ±f p and λ is the smallest shift that keeps them there (the stick limit): if δ
// still falls short there, the bodies slide rigidly by the rest, which is added to the slip of every contact cell,
// and the cycle is in gross slip with CycleResult::sliding_amplitude = (rigid sliding per cycle)/4.
//
// A load history (CyclicLoad::history, force control): the cycle runs through the points [t, P, Q, ε] (the last
// repeats the first) and is repeated; increments end at every point, and each segment is split into
// ⌈m Δt/T⌉ ≥ 1 equal steps (m = increments_per_cycle, T the period); the first loading goes from Q = 0, ε = 0 under
// the contact's P to the first point in m/4 steps. For β = 0 the pressure at an increment is the normal solution at
// its P (one constrained-CG solve per distinct P, warm-started from the nearest P solved): the bounds ±f p change,
// cells that separate drop their traction (the drop is part of the increment's Δq), and q at a cell above its new
// bound is clamped by the projection, after which the KKT signs say whether it slips. |Q| ≥ f P at any increment is
// gross slip, reported without fields as under force control. The phases: top and bottom at the largest and the
// smallest Q, "unloaded" and "reloaded" where Q first crosses their mean after the top and after the bottom.
//
// Dissimilar bodies (Dundurs β ≠ 0; NormalCoupling, force control under constant P): the normal and tangential
// problems are coupled (contact/coupling_kernel.hpp derives it): on the grid
//     g = g0 + K p − A β S q − δ,        s = K q + A β S p + ε x − λ,
// S the exact step-kernel matrix of piecewise-constant tractions. The pressure then moves over the cycle. Each
// increment is a block Gauss–Seidel iteration between the two problems, from the previous increment's (p, q):
//     sweep k:  p_k = the normal solution (load P) for the gap g0 − A β S q_{k−1}, warm-started from p_{k−1};
//               q_k = the tangential increment above with bounds ±f p_k and the pressure's coupling slip added,
//                     Δs = K (q − q_prev) + A β S (p_k − p_prev) + Δε x − λ, warm-started from q_{k−1};
// cells that leave the contact drop their traction, as under a load history. It stops when one sweep changes
// neither traction by more than coupling_tolerance · max p_k:
//     max( max_i |p_k − p_{k−1}|, max_i |q_k − q_{k−1}| ) ≤ coupling_tolerance · max_i p_k,
// and throws ConvergenceError naming the increment after max_coupling_sweeps. One sweep contracts the error by about
// f |β| (measured 0.05 at f |β| = 0.055, docs/PERFORMANCE.md): the change is carried by the slipping cells' bounds
// ±f p, which move with the pressure, more than by the elastic coupling alone (β², each half entering once). So a
// few sweeps suffice for f |β| up to a few tenths; Hertz, steel on aluminium (β = −0.11), settles at f = 8 and does
// not at f = 9 (f |β| = 0.99), and the error then says so past kSweepsSlowBeyond. The change of the first
// sweeps is the increment's own (its load step moves q, and the new q moves p): with predict_increments (the default)
// the first normal solve is given q_0 + r Δq_last and warm-started from p_0 + r Δp_last, the last increment's changes
// scaled by r = ΔQ/ΔQ_last, when that increment had the same P and the same strain per unit Q and loaded in the same
// direction (within a half cycle the increments are equal steps along one path), and the first sweep's pressure change
// is measured from that p. The stopping criterion is unchanged. Within it the sweeps stop where the inner solves stop
// moving (a sweep whose input moved by less than their tolerances is a fixed point), so two starts give answers that
// differ by what those tolerances let through: 4e-7 in a cycle's energy, 2e-6 p0 in the traction
// (tests/verification/test_coupled_increments.cpp), for 8 % fewer sweeps and 10 % fewer CG iterations. Anderson
// acceleration of the sweeps (Walker and Ni 2011) was tried and did not shorten them: the sweeps' change is carried by
// the cells at the stick zone's edges, which switch between stick and slip from sweep to sweep. The cycle starts from
// the given contact with q = 0, as if P had been applied without friction (with friction, loading P alone on dissimilar
// bodies builds a shear with a central stick zone, Spence 1975, which is not modelled here); the first cycle after that
// first loading is then not yet the steady one (tests/verification/test_cycle_dissimilar.cpp: 0.1 % in energy for steel
// on titanium), the second is. Only the last cycle is reported, and the march before it only has to leave the state at
// its top: settling_increments > 0 marches the first loading in a quarter of them and the cycles before the last in
// that many (under a load history each segment in its share of them, one at least). The top state after a full
// reversal hardly remembers that march: with 4 (the first loading in one increment, the first cycle in four) the
// reported cycle's energy moved by 1e-8 to 1e-7 and its traction by 1e-6 p0 at 512 and 1024 cells, for steel on
// titanium and on aluminium, Q/fP = 0.5 and 0.85, and under a history with P out of phase with Q by 2e-8 and 7e-7 p0
// (tests/verification/test_coupled_increments.cpp), what the inner tolerances let through above. The wear stage's
// coupled responses take 4 (engine/wear_contacts.hpp); the cycle stage marches every cycle in full. Under displacement
// control with β ≠ 0 each evaluation of the δ search above is such a coupled increment to its Q, from the increment's
// start (traction and pressure), so δ(Q) keeps its meaning and the search is unchanged; past the stick limit the bodies
// slide as for β = 0. Under a load history with β ≠ 0 each increment is a coupled increment under its own P (the normal
// half of a sweep solves for that load), and the pressure at the history's top and bottom is reported as under a
// constant P (for β = 0 too, where it is the normal solution at the P of those points), with the bulk strain there.
//
// Half a cycle, mirrored (mirror_half_cycle; β ≠ 0 without bulk strain, solve() only). The equations above are
// unchanged by x → −x with q → −q, Q → −Q (S is odd, K even) when the gap is even, and the cells pair as
// i ↔ n − 1 − i on a window centred at x = 0; under displacement control δ → −δ too, when the datum's reference
// points lie on x = 0 (D, the shear's share and the pressure's alike, is then odd under the mirror, and the even
// pressure under P alone adds nothing to it), and the reloading half slides as the unloading half did (the sliding
// amplitude from twice the unloading's sliding). A steady cycle whose bottom is its top so mirrored then reloads as
// it unloaded, mirrored, and dissipates e(x) + e(−x) per cycle, e the unloading half's; its slip travelled
// likewise, and its slip range from the unloading's extremes (w over the reloading is W(x) − w_u(−x, t), W the slip at
// the bottom). So the last cycle marches its unloading half only: 20 of the 40 increments. The marched cycle is
// that but for the slip the first loading leaves locked in at the stick zone's edges, which no later cycle undoes:
// its bottom and its top mirrored differ by about 2e-3 p0 at those cells (6e-3 p0 at Q/fP = 0.85), and its energy
// density is even only to 1.5e-5 of its peak. The mirrored cycle's energy is within 5e-7 of the marched one's and its
// density within 1.4e-5 of the peak (tests/verification/test_coupled_mirror.cpp: aluminium at Q/fP = 0.5 and 0.85,
// titanium), far below what the increments themselves leave (2.7e-3 of the density, in the L1 norm, at 40
// increments; docs/METHODS.md). Its top, q_top and p_top, is the steady top the unloading started from, as the full
// march reaches it; q_reloaded is q_unloaded mirrored; the loop's reloading points are the unloading's with Q and δ
// reversed; increment_energy, increment_Q and increment_shift hold the marched increments only, and
// IncrementalResult::mirrored says so. A worn gap is even only as far as the solves that wore it are (its pressure is
// even to their tolerance): the gap is taken as even where its odd part is within 1e-6 of its largest value, and
// otherwise the whole cycle is marched.
#pragma once

#include <complex>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "contact/reference_datum.hpp"
#include "contact/tangential_solver.hpp"

namespace fretwear {

// f |β| from which a coupled increment that did not settle names it as the reason (above).
inline constexpr double kSweepsSlowBeyond = 0.5;

struct IncrementalSlipOptions {
  int increments_per_cycle = 40;  // load steps over +Q → −Q → +Q (the first loading 0 → Q takes a quarter of
                                  // them); a multiple of 4 and ≥ 4, so that Q = 0 and ±Q are increment ends
  int cycles = 1;                 // steady cycles after the first loading; ≥ 1
  // solve_history() only: after those, cycles until the last one ends in the traction it began from, or repeats the
  // one before it at the same increments (the traction at the top and the bottom of both), within 1e-6 of the
  // largest top traction, at most this many cycles in all; 0: exactly `cycles`. A history reaches its steady cycle
  // only after several cycles where the first slips and the later ones do not (shakedown); IncrementalResult::repeated
  // says whether it did.
  int steady_cycles_max = 10;
  // Increments of the cycles before the last one (the first loading takes a quarter of them): 0 for
  // increments_per_cycle; else a multiple of 4 (see above: only the last cycle is reported).
  int settling_increments = 0;
  double tolerance = 1e-8;        // on the residual r above; in (0, 1e-2]
  int max_iterations = 20000;     // CG iterations per increment before giving up; ≥ 1
  // none: plain constrained CG; symbol: Π_W C⁻¹ Π_W on the working set (see above).
  NormalSolverOptions::Preconditioner preconditioner = NormalSolverOptions::Preconditioner::symbol;
  // β ≠ 0 only: the block Gauss–Seidel stop, max |Δp|, |Δq| between sweeps ≤ coupling_tolerance · max p (see above);
  // in (0, 1e-2].
  double coupling_tolerance = 1e-8;
  int max_coupling_sweeps = 100;  // sweeps per increment before giving up; ≥ 1
  // β ≠ 0 only: start each increment's sweeps from the last increment's change scaled to this one (see above).
  bool predict_increments = true;
  // β ≠ 0 without bulk strain, on a mirror-symmetric contact (see above; under displacement control with the datum
  // on x = 0): the last cycle's reloading half taken as the mirror image of its unloading half, solve() only.
  bool mirror_half_cycle = false;
  NormalSolverOptions normal;     // for the normal solves of the coupled increments
  // Called after each increment with the number marched so far (the first loading's and every cycle's); may throw to
  // end the march (a stop asked for). Empty: not called.
  std::function<void(int)> after_increment;

  // Empty when valid; otherwise names the field, its value and the constraint.
  std::string validate() const;
};

// One increment's data: the traction bounds and the load step.
struct SlipIncrement {
  double Q = 0.0;              // tangential load at the end of the increment (N/m)
  double Q_prev = 0.0;         // at its start (N/m)
  double bulk_strain = 0.0;    // ε at the end of the increment
  double bulk_strain_prev = 0.0;
};

// What one increment leaves: the traction and, per cell, the slip increment Δw (m; zero on stick cells and off
// the contact).
struct IncrementState {
  std::vector<double> q;      // shear traction per cell (Pa)
  std::vector<double> u;      // K q per cell (m), carried to the next increment
  std::vector<double> dw;     // slip increment per cell (m)
  // The slip increment a cell would make were it touching without load (m): dw on the contact; off it, where q = 0
  // and nothing holds the surfaces together, the change of their relative tangential displacement, −(Δs − λ).
  std::vector<double> dw_touching;
  double shift = 0.0;         // λ of the increment: the rigid shift of the pad relative to the specimen (m)
};

// The coupling of dissimilar bodies (see the header): Dundurs β and the initial gap for the normal solves.
struct NormalCoupling {
  double beta = 0.0;              // Dundurs β, body 1 the pad, body 2 the specimen (elastic_pair.hpp)
  std::span<const double> g0;     // initial gap per cell (m; +∞ where the pad has no material)
};

struct IncrementalResult {
  std::vector<CycleResult> cycles;  // one per steady cycle, top to top; CycleResult::solves holds its increments
  SolveSummary worst;               // the increment with the largest residual over the whole run
  int n_increments = 0;
  int n_iterations = 0;             // CG iterations over every increment
  // β ≠ 0: block Gauss–Seidel sweeps over every increment, the most any increment took. The pressure of the last
  // cycle at its top and bottom (Pa per cell) for β ≠ 0 and for a load history at any β (whose P varies); empty
  // for solve() with β = 0, where the pressure is the contact's.
  int n_coupling_sweeps = 0;
  int max_coupling_sweeps = 0;
  std::vector<double> p_top, p_bottom;
  // A load history: the bulk strain ε at the top and the bottom of its last cycle (0 for solve(), where it is ±ε).
  double bulk_strain_top = 0.0, bulk_strain_bottom = 0.0;
  // The last cycle's reloading half was the mirror image of its unloading half (mirror_half_cycle, on a symmetric
  // contact): increment_energy, increment_Q and increment_shift then hold the marched increments only.
  bool mirrored = false;
  // solve_history() with steady_cycles_max > 0: the last cycle ended where it began, or repeated the one before it
  // (false: the cap came first, and the last cycle may not be the steady one).
  bool repeated = true;
  int cycles_marched = 0;  // cycles after the first loading
  std::vector<double> increment_energy;  // h Σ q Δw of every increment, the first loading's included (J/m)
  // Q at the end of every increment (N/m) and its rigid shift λ (m; the multiplier of the load, work-conjugate to Q:
  // over a closed cycle ∮ Q dλ is the energy dissipated, when the elastic operator is symmetric).
  std::vector<double> increment_Q, increment_shift;
};

class IncrementalSlipSolver {
 public:
  // The kernel must outlive the solver. Throws InputError if the options are invalid.
  IncrementalSlipSolver(const HalfPlaneKernel& kernel, IncrementalSlipOptions options = {});

  // The cycles of `load` on the normal solution `contact` (its p is fixed: β = 0, constant P). Q_max ≥ f P returns one
  // cycle in the gross_slip regime with no fields, as the analogy route does. With a datum (it must outlive the
  // call) each cycle carries its fretting loop. Throws ConvergenceError naming the cycle, the increment, Q and the
  // residual if an increment does not converge.
  // With a coupling whose β ≠ 0 the pressure is solved with the shear at every increment (the coupling's g0 must
  // outlive the call); ConvergenceError also when the sweeps do not settle.
  IncrementalResult solve(const ContactState& contact, const CyclicLoad& load, const ReferenceDatum* datum = nullptr,
                          const NormalCoupling* coupling = nullptr) const;
  // A load history (load.history non-empty; see the header): g0 is the initial gap per cell, for the normal solves
  // at each distinct P(t), warm-started; `contact` is the normal solution under load.P, where the first loading starts.
  // With a coupling whose β ≠ 0, the pressure under each increment's P is solved with the shear, as in solve().
  IncrementalResult solve_history(const ContactState& contact, const CyclicLoad& load, std::span<const double> g0,
                                  const ReferenceDatum* datum = nullptr, const NormalCoupling* coupling = nullptr) const;

  // One increment from `state` (q and u = K q of the previous increment, or empty for q = 0). p: the pressure per
  // cell (Pa); f the friction coefficient. Needs Σ f p h ≥ |Q|.
  SolveSummary solve_increment(std::span<const double> p, double f, const SlipIncrement& inc,
                               IncrementState& state) const;

  const IncrementalSlipOptions& options() const { return options_; }

  // The increments solve_history() marches at most under `options` through `history`: its first loading and every
  // cycle it may march before one repeats the one before (steady_cycles_max), each split as the march splits it.
  static int history_increments_at_most(const IncrementalSlipOptions& options,
                                        const std::vector<HistoryPoint>& history);

 private:
  class Run;           // what solve() and solve_history() carry from increment to increment (incremental_slip.cpp)
  class AmplitudeRun;  // solve(): Q, or δ, cycling 0 → +X → −X → +X under constant P
  class HistoryRun;    // solve_history(): the points of a load history

  // solve_increment with the bounds given and the previous increment's K q in u_prev (state.q: the start).
  SolveSummary solve_bounded(std::span<const double> lo, std::span<const double> hi, const SlipIncrement& inc,
                             std::span<const double> u_prev, IncrementState& state) const;
  SolveSummary iterate(std::span<const double> lo, std::span<const double> hi, const SlipIncrement& inc,
                       std::span<const double> u_prev, IncrementState& state, bool use_preconditioner) const;
  const HalfPlaneKernel& kernel_;
  IncrementalSlipOptions options_;
  bool preconditioned_ = false;  // the options ask for the kernel's inverse spectrum, and C is positive definite
};

}  // namespace fretwear
