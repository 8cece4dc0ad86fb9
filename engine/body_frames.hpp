// Each body's wear in its own frame, in gross slip (docs/METHODS.md, "Each body in its own frame").
//
// In gross slip the pad slides over the specimen by ±U each cycle, so a point of the specimen meets the whole
// stroke of pad points while a point of the pad meets the whole stroke of specimen points. The state is therefore
// two profiles, z = [w_pad; w_spec]: w_pad(x) at the pad's points x (the grid), w_spec(X) at the specimen's points X
// (the same grid: at mid-stroke X = x). With the pad displaced by u relative to the specimen the gap at pad point x is
//     g_u(x) = g0(x) + w_pad(x) + w_spec(x + u),
// and its pressure p_u(x) is the normal solution under P for that gap. For similar bodies the shear does not move
// it. For dissimilar ones (Dundurs β ≠ 0) the sliding shear q = σ f p (σ = ±1, the direction the pad slides) moves
// the pressure through the coupling of contact/coupling_kernel.hpp, g = g0 + K p − A β S q − δ: each position has a
// pressure p_u^σ for each direction, the normal solution for the gap g_u − σ A β f S p_u^σ (the frictional sliding
// contact of dissimilar bodies, Hills, Nowell and Sackfield 1993, §2.5 with q = ±f p), leaning toward one end of the
// contact when the pad slides one way and toward the other on the way back. The pad passes every position once
// each way, so the means below are over both directions, ⟨p_u⟩ = ½ (p_u^+ + p_u^−).
// Over a cycle the relative position runs over [−U, U] twice each way, uniformly in distance, so with the slip
// travelled s(x) per cycle (4U plus the elastic part, the cycle's response at mid-stroke) Archard's law gives
//     dw_pad/dN (x) = c_pad s(x) ⟨p_u(x)⟩,      dw_spec/dN (X) = c_spec ⟨(p_u s)(X − u)⟩,
// ⟨·⟩ the mean over u ∈ [−U, U]. The mean is taken by the trapezoid rule on positions u_k = k U / M, k = −M … M,
// M = min(kFrameIntervals, max(1, round(U / Δx))), about a cell apart while the stroke spans few cells. Each position
// stands for its share of the stroke, halfway to its neighbours: the specimen is read as its mean over the points the
// pad passes in that share, and each position's wear deposited evenly over them, the transpose
// (BodyFrames::share_cells), so that Σ h dw_spec = Σ h c_spec ⟨p s⟩ exactly and the composite of reading and deposit is
// positive semidefinite. Measured on the gross-slip example (docs/PERFORMANCE.md, "Each body's frame in gross slip"):
// against all 21 whole-cell positions at 512 cells, every cycle worn, 9 positions gave each body's depth to 2e-4 and
// 5e-4 and 17 positions to 1e-4; but the pressure, at 9 positions, rippled by about 5 % at the positions' spacing
// (each position's pressure has its edge where that position's share of the specimen's scar ends, and the pad sums
// them), much less at 17, hence 17 (twice the time).
//
// For β ≠ 0 each p_u^σ is found by sweeps, the coupling term from the last pressure, which contract by about f |β|
// (pressures(): to kFrameSweepTolerance), and within the step below as part of its passes (the coupling term at
// the iterate, so that the mixing converges both at once). s is then the slip travelled, not the energy's equivalent
// (IncrementalContactResponse::give_slip_travelled), since the pressures that weigh it are these.
//
// The step (backward Euler in the pressures, with the slip s lagged at the step's start as the shared profile's
// contact-implicit step lags it, wear/implicit_stepper.hpp): the end-of-step pressures p_k solve
//     p_k = normal solution for the gap  g0 + w_pad + S_k w_spec + ΔN [R_pad(p) + S_k R_spec(p)],
// R_pad, R_spec the rates above and S_k the reading of the specimen at position k. Every position's gap carries
// every position's wear, so the system couples them. It is solved by the passes
//     p_k^{j+1} = normal solution for  g0 + w_pad + S_k w_spec + ΔN [R_pad(x^j) + S_k R_spec(x^j) − D x_k^j] + D p_k^{j+1},
// D = (c_pad + c_spec) s ΔN the normal solver's diagonal shift (the wear position k's own pressure would deposit were
// all positions alike, implicit within each solve, so that the contact's own stiffness never limits the step), from
// x^0 the pressures at the step's start (the full step: the half step's, extrapolated), with Anderson's mixing of the
// passes (x^{j+1} = p^{j+1} − ΔG γ, γ the least-squares fit of the residual p^{j+1} − x^j by the last kFrameMemory
// differences of residuals ΔF, ΔG those of the passes' results; Eigen's column-pivoting QR), until a pass changes the
// pressure by less than kFramePassTolerance of its largest value; a step whose passes do not get there in
// kFramePasses is retried with a quarter of the jump. Measured on examples/gross_slip_displacement_wear.json: one pass
// (each position's own wear implicit, the rest lagged) is stable but its steps shrink with the grid (400 / 664 / 1097
// at 256 / 512 / 1024 cells): a cell-wide alternation of w_pad against w_spec is invisible to positions an even number
// of cells apart and doubled for the odd ones, and the lag leaves that coupling explicit. Four unmixed passes left
// every other cell of the newest 20 at each contact edge open at 1024 cells, with the profiles' error (1e-9 m) under
// the tolerance; unmixed passes do not converge at large jumps (thirty stayed above 1e-7 beyond about 30 cycles at
// 256 cells); mixed, about eight reach 1e-3.
//
// Error control as the shared profile's (wear/implicit_stepper.hpp): Richardson extrapolation over one step of ΔN
// and two of ΔN/2 (s refreshed at the half step), err = max_i |two − one| / (τ max_i z) over both profiles,
// ΔN ← ΔN 0.9/√err, wear never decreasing.
#pragma once

#include <functional>
#include <span>
#include <utility>
#include <vector>

#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>
#include <boost/numeric/odeint/stepper/stepper_categories.hpp>
#include <nlohmann/json.hpp>

#include "contact/coupling_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "engine/setup.hpp"
#include "wear/contact_response.hpp"

namespace fretwear {

inline constexpr int kFrameIntervals = 8;                 // M's cap: 17 positions over the stroke
inline constexpr int kFramePasses = 40;                   // passes of the step's coupling between positions
inline constexpr double kFramePassTolerance = 1e-3;       // converged when one changes p by less (relative to max p)
inline constexpr int kFrameMemory = 6;                    // Anderson's mixing: the differences it fits
inline constexpr double kFrameSweepTolerance = 1e-10;     // β ≠ 0: a position's sweeps stop when p changes less
inline constexpr int kFrameSweeps = 60;                   // (relative to max p), in at most this many

// The gap's wear at mid-stroke, w_pad + w_spec, of z = [w_pad; w_spec] (2n values).
std::vector<double> mid_stroke(std::span<const double> z);

// The stroke seen by the frames: positions u_k (in cells, fractional) and their trapezoid weights (sum 1).
struct FramePositions {
  std::vector<double> shift;   // u_k / Δx
  std::vector<double> weight;  // ν_k
  // The share of the stroke each stands for, [a_k, b_k] / Δx: halfway to its neighbours, [−U, U] in all (ν_k is its
  // length over 2U).
  std::vector<std::pair<double, double>> share;
};
FramePositions frame_positions(double U, double h);

// The two bodies' wear in their own frames: pressures at every position (and each sliding direction, for β ≠ 0),
// rates, and the implicit step. The cycle's response at mid-stroke (the slip s and the sliding amplitude U) comes
// from `respond`, called with the gap's wear at mid-stroke w_pad + w_spec. The pressures are indexed by state
// m = k D + d: position k, direction d of D (1 for similar bodies; 2 for β ≠ 0, σ = +1 then −1).
class BodyFrames {
 public:
  // respond(w, out) answers the steady cycle on the profile worn by w (the wear stage's contact); U(out) its
  // sliding amplitude (m).
  using Respond = std::function<void(std::span<const double>, wear::CycleResponse&)>;
  using Amplitude = std::function<double()>;
  // f: the friction coefficient, which sets the sliding shear ±f p (used where the pair's β ≠ 0).
  BodyFrames(const Model& model, double P, double f, double c_pad, double c_specimen, Respond respond,
             Amplitude amplitude);

  // The cycle at mid-stroke on z (out), and the positions and slip the step lags from it; returns its sliding
  // amplitude U (m). lag() sets them again from a response and its U.
  double respond(std::span<const double> z, wear::CycleResponse& out);
  void lag(const wear::CycleResponse& r, double U);
  // The pressures p_m on z at the states of the last respond() (warm-started from p), and dz/dN from them.
  void pressures(std::span<const double> z, std::vector<std::vector<double>>& p);
  void rates(const std::vector<std::vector<double>>& p, std::vector<double>& dz) const;
  // One backward-Euler step of ΔN from z at the positions and slip of the last respond(); p: the start's pressures
  // on entry (warm start), the end's on return. False when a normal solve did not converge.
  bool euler(std::span<const double> z, double dN, std::vector<std::vector<double>>& p, std::vector<double>& out);

  const FramePositions& positions() const { return positions_; }
  int directions() const { return directions_; }  // D: 1, or 2 where the shear moves the pressure (β ≠ 0)
  std::size_t states() const { return positions_.shift.size() * std::size_t(directions_); }
  long solves() const { return solves_; }
  long cg_iterations() const { return cg_iterations_; }  // over the solves
  long iterations() const { return iterations_; }  // passes over the positions, over all steps
  void count(long solves, long iterations, long cg_iterations) {
    solves_ = solves, iterations_ = iterations, cg_iterations_ = cg_iterations;
  }
  SolveSummary last_unconverged;

 private:
  // The gap of position k on z, plus extra (empty: none).
  void gap_at(std::span<const double> z, std::size_t k, std::span<const double> extra, std::vector<double>& g) const;
  // The specimen's cells j that pad cell i passes in position k's share of the stroke, with the share of the
  // passage over each (summing to 1): visit(j, weight).
  template <class Visit>
  void share_cells(std::size_t k, int i, Visit visit) const;
  // S_k v: the specimen's v read at the pad's cells, position k; and its transpose, added to out.
  void read(std::span<const double> v, std::size_t k, std::vector<double>& out) const;
  void deposit(std::span<const double> v, std::size_t k, std::span<double> out) const;
  // State m's position and the sign σ of its sliding shear σ f p (0 where D = 1).
  std::size_t position(std::size_t m) const { return m / std::size_t(directions_); }
  double sign(std::size_t m) const { return directions_ == 1 ? 0.0 : (m % 2 == 0 ? 1.0 : -1.0); }
  // out += the gap the sliding shear of state m adds on its pressure p: −σ A β f S p.
  void add_coupling(std::size_t m, std::span<const double> p, std::vector<double>& out) const;

  const Model& model_;
  int n_;
  double P_, c_pad_, c_spec_;
  double coupling_;  // A β f (m/Pa per unit of S)
  int directions_;
  CouplingKernel coupling_kernel_;
  Respond respond_;
  Amplitude amplitude_;
  NormalSolver solver_;
  FramePositions positions_;
  std::vector<double> s_;  // the slip lagged: the last response's slip_if_touching
  mutable std::vector<double> deposit_;  // rates()' scratch: one position's specimen wear before its deposit
  mutable std::vector<double> coupled_;  // add_coupling()'s scratch: the sliding shear's gap
  long solves_ = 0, iterations_ = 0, cg_iterations_ = 0;
};

struct FramesStepperStats {
  int accepted = 0, rejected = 0, unconverged = 0, responses = 0;
  double last_error = 0.0;
};

// The controlled stepper on z (Boost.Odeint's controlled-stepper interface, as wear::ImplicitWearStepper).
class FramesWearStepper {
 public:
  using state_type = std::vector<double>;
  using deriv_type = std::vector<double>;
  using value_type = double;
  using time_type = double;
  using order_type = unsigned short;
  using stepper_category = boost::numeric::odeint::controlled_stepper_tag;

  explicit FramesWearStepper(double tolerance) : tolerance_(tolerance) {}
  static constexpr order_type order() { return 2; }

  boost::numeric::odeint::controlled_step_result try_step(std::reference_wrapper<BodyFrames> system,
                                                          state_type& z, time_type& N, time_type& dN);

  const FramesStepperStats& stats() const { return stats_; }
  nlohmann::json save() const;
  // Throws InputError when a warm start does not hold `cells` values (engine/checkpoint.hpp, cell_vector).
  void restore(const nlohmann::json& j, std::size_t cells);

 private:
  double tolerance_;
  FramesStepperStats stats_;
  std::vector<std::vector<double>> p_start_;  // the pressures at the last accepted state (warm starts)
  // The response at the state of the last try and its U: a rejected step retried from the same state reuses them.
  state_type responded_;
  wear::CycleResponse response_;
  double amplitude_ = 0.0;
};

// dz/dN at z for the explicit stepper (effects.wear.stepper "explicit", wear/reference_steppers.hpp's
// ExplicitWearStepper): the cycle at mid-stroke, every state's pressure on z (warm-started from the last
// evaluation's), and the rates. Its save/restore carry what a resumed run needs to repeat the uninterrupted one:
// the count, the last rate (Dormand–Prince's first-same-as-last derivative) and the pressures it warm-starts from.
class FramesRateSystem {
 public:
  explicit FramesRateSystem(BodyFrames& frames) : frames_(&frames) {}
  void operator()(const std::vector<double>& z, std::vector<double>& dz, double N);
  long evaluations() const { return evaluations_; }
  const std::vector<double>& last_rate() const { return rate_; }
  nlohmann::json save() const;
  // Throws InputError when a pressure does not hold `cells` values or the rate state_size (cell_vector).
  void restore(const nlohmann::json& j, std::size_t cells, std::size_t state_size);

 private:
  BodyFrames* frames_;
  std::vector<std::vector<double>> p_;
  std::vector<double> rate_;
  long evaluations_ = 0;
};

// One cycle at a time, every position: the reference of the step above (effects.wear.stepper "cycle_by_cycle").
class FramesCycleByCycle {
 public:
  using state_type = std::vector<double>;
  using stepper_category = boost::numeric::odeint::controlled_stepper_tag;
  boost::numeric::odeint::controlled_step_result try_step(std::reference_wrapper<BodyFrames> system,
                                                          state_type& z, double& N, double& dN);
  long responses = 0;

 private:
  std::vector<std::vector<double>> p_;
};

}  // namespace fretwear
