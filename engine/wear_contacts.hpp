// The contact as the wear stage sees it: wear::ContactResponse (wear/contact_response.hpp) answered on top of
// contact/, by the analogy route on the worn profile (similar bodies: under force control, and under displacement
// control in partial slip at the Q that reaches δ) or by the incremental route (dissimilar bodies, gross slip, load
// histories, or when the scene asks for it), with what the stage needs besides: the shear at the top of
// the cycle for records, the solves' warm starts for checkpoints, and the solves' counts.
#pragma once

#include <algorithm>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/contact_zones.hpp"
#include "contact/incremental_slip.hpp"
#include "contact/normal_solver.hpp"
#include "contact/reference_datum.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "wear/contact_response.hpp"

namespace fretwear {

// What run_wear needs of a contact besides wear::ContactResponse: the shear at the top of the last cycle solved
// (records), the warm starts of its solves (checkpoints) and its counts.
class WearContact : public wear::ContactResponse {
 public:
  int cells() const final { return model_.grid.n; }
  double cell_width() const final { return model_.grid.h(); }
  // The end-of-step pressure (route-independent for similar bodies: the pressure does not depend on the shear).
  bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) final;
  // The shear traction at the top of the cycle of the last respond() per cell (Pa); the bottom is its reverse.
  virtual const std::vector<double>& shear_top() const = 0;
  // The tangential load at the top of the cycle of the last respond() (N/m).
  virtual double Q_top() const = 0;
  // The warm starts of the solves and the counts below, for checkpoints.
  virtual nlohmann::json save() const = 0;
  virtual void restore(const nlohmann::json& j) = 0;
  // The last contact-implicit solve that did not converge (its termination and residual), for the error message.
  SolveSummary last_unconverged;
  // Solves and their CG iterations, by kind: the cycle (normal and corrective solves, or slip increments) and the
  // contact-implicit steps.
  long cycle_solves = 0, cycle_iterations = 0, implicit_solves = 0, implicit_iterations = 0;

 protected:
  WearContact(const Scene& scene, const Model& model);
  // gap_ = g0 + w, the gap of the worn profile.
  void set_gap(std::span<const double> w);
  // One of the cycle's solves on the worn profile (gap_, or gap_ shifted): counted, and a ConvergenceError naming
  // `what` when it stops short.
  void solve_worn(double P, ContactState& state, const char* what);
  // Throws InputError naming grid.window where the pressure p of the worn profile loads either end cell of the
  // window: the worn contact has grown to the window's end, and would be cut off there (the pressure beyond the
  // window is not modelled).
  void check_window(const std::vector<double>& p) const;
  // The counts, for save() and restore().
  nlohmann::json counts() const;
  void restore_counts(const nlohmann::json& j);
  // Solves on a worn profile: its worn cells sit at zero gap and zero pressure by the hundred near the limit, and
  // enter the contact set only through the proportioning test (contact/normal_solver.hpp).
  static NormalSolverOptions worn_options() {
    NormalSolverOptions o;
    o.proportioning = kWearProportioning;
    return o;
  }
  // The contact-implicit solves give up sooner than the cycle's: a step whose solve does not converge is retried
  // with a smaller jump (wear/implicit_stepper.hpp), which is cheaper than iterating on a badly conditioned one.
  // With proportioning they take tens of iterations, a few hundred at most (4096 cells); the limit grows with the
  // grid.
  static NormalSolverOptions implicit_options(int cells) {
    NormalSolverOptions o = worn_options();
    o.max_iterations = std::max(2000, cells);
    return o;
  }
  const Scene& scene_;
  const Model& model_;
  double P_ref_;                  // the load of the pressure handed to the stepper: load.P, or a history's largest P
  NormalSolver solver_;           // the cycle's solves
  NormalSolver implicit_solver_;  // the contact-implicit steps'
  ContactState implicit_;
  std::vector<double> gap_;
};

// The steady-cycle slip and stick zone on a worn profile, by the analogy route (similar bodies, constant P).
//
// The slip s per cycle is 4 f g* (g* the corrective problem's gap) where the contact is loaded and the corrective
// contact open. A cell that carries no pressure would slip 4 f (g* − g) on touching (its surfaces touch, or nearly,
// and travel that relative to each other): CycleResponse::s_touching, filled on every such cell of finite gap
// outside the corrective contact. The wear rate
// c p s is unchanged by it (p = 0), but the contact-implicit step (wear/implicit_stepper.hpp) takes its shift ΔN c s
// from it. Near the limit the worn zones sit at zero gap and zero pressure; a worn cell given
// no slip there would be rigid in the step while its neighbours wear, and the step's Richardson extrapolation and its
// rule for cells that start to wear would leave it standing proud of them by the step's error (about 1e-11 m at 1024
// cells, against a normal solve accurate to 1e-14 m). The next plain normal solve then resolves that roughness
// exactly: the worn zones' pressure alternated between 0 and up to MPa from cell to cell (the stiffness of one
// cell, about 1/(A h), so the noise and Ruiz's F1 grew with the grid), and the cells it loaded were the ones that
// wore next. With the slip kept the worn zones stay level and carry exactly zero
// (tests/verification/test_worn_zones.cpp). The same holds beyond the contact, worn or not: the contact spreads
// outward as its slip zones wear, one cell at a time, and a cell it reaches within a step would otherwise enter with
// no slip lagged, unworn by the step of ΔN and worn by the second half step, a first-order difference that rejected
// the step (two rejections per cell entering on hertz_wear at 4096 cells: 253 of its 592 step attempts). With
// 4 f (g* − g) lagged there every cell outside the stick zone is worn by both solutions alike.
class AnalogyContactResponse : public WearContact {
 public:
  // load: the cyclic load (CyclePlan::load, or cyclic_load()).
  AnalogyContactResponse(const Scene& scene, const Model& model, const CyclicLoad& load);
  // Under displacement control (load.delta > 0, no bulk strain, no history): each response first finds the Q whose
  // steady cycle takes the datum's reference points to ±load.delta on the worn profile, δ_top(Q) = δ with
  // δ_top(Q) = f (δ_P − δ*(Q)) + D(q_top) (contact/displacement_limit.hpp, the datum fixed in the bodies as they wear),
  // by toms748 over corrective solves; then the cycle at that Q. Throws UnsupportedError from respond() where the
  // worn contact's stick limit falls to δ (the bodies slide) and, as under force control, where it slips backwards.
  AnalogyContactResponse(const Scene& scene, const Model& model, const CyclicLoad& load, const ReferenceDatum& datum);
  // Throws InputError when the worn contact reaches the end of the window (check_window).
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  const std::vector<double>& shear_top() const override { return q_top_; }
  // The tangential load at the top of the cycle: the scene's under force control, the last response's under
  // displacement control.
  double Q_top() const override { return Q_; }
  // The last corrective pressure (for records).
  const std::vector<double>& corrective_pressure() const { return corrective_.p; }
  // Where it gives up on reverse slip, its message advises effects.tangential.route "incremental", unless the
  // caller already falls back to that route by itself (IncrementalContactResponse).
  void falls_back() { advise_route_ = false; }
  // The stick zones of the last cycle, one per run of the corrective contact (several where the contact has
  // several zones); the CycleResponse carries only their span.
  const std::vector<Zone>& stick_zones() const { return stick_zones_; }
  nlohmann::json save() const override;
  void restore(const nlohmann::json& j) override;

 private:
  // Under displacement control: Q_ and corrective_load_ from δ_top(Q) = delta_ on the worn gap (gap_).
  void solve_top_displacement();

  double tilt_ = 0.0, corrective_load_ = 0.0, Q_ = 0.0;
  const ReferenceDatum* datum_ = nullptr;  // displacement control: the cycle stage's datum
  double delta_ = 0.0;
  bool advise_route_ = true;
  ContactState normal_, corrective_;
  std::vector<double> q_top_;
  std::vector<Zone> stick_zones_;
};

// The steady cycle on a worn profile by the incremental route (contact/incremental_slip.hpp): under the scene's
// control, force or displacement (load.control, load.delta), through the onset of gross slip, or through a load
// history (load.history, each repetition one wear cycle), for similar or dissimilar bodies. respond(w) solves the
// normal contact of g0 + w under P (warm-started from the last), then marches the first loading and the cycles on
// the worn gap g0 + w (solve_history's normal solves at each P of the history, and the coupled normal solves of
// β ≠ 0, take that gap); the last cycle is the steady one. The reference points of δ are those of the cycle stage
// (centre of the unworn contact, reference_depth below), fixed in the bodies as they wear. The marching itself
// starts from rest each time (it is fast and has no warm start); the normal and contact-implicit solves are
// warm-started, and save()/restore() carry those starts.
//
// The slip s handed to the stepper, whose rate is dw/dN = c p s with p the pressure under the constant P
// (wear/contact_response.hpp; c = k for Archard, α f for the energy law, wear/wear_law.hpp):
//  - β = 0 and no history (the pressure is that of P all through the cycle): s is the slip travelled per cycle,
//    Σ |Δw| over the increments (in gross slip, 4 times the sliding amplitude plus the elastic part, over the whole
//    contact; no stick zone).
//  - a history (P moves through the cycle), or β ≠ 0 (the shear moves the pressure): "c p s" with one p is
//    ambiguous, and the wear is summed over the increments instead. Archard's law wears a cell by k p_j |Δw_j| in
//    increment j, and where it slips |q_j| = f p_j, so over a cycle Δw = (k/f) Σ q_j Δw_j = (k/f) e, e the energy
//    density per cycle (CycleResult::energy_density); the energy law gives α e. Both are c e / f. With p_ref the
//    pressure under P on the worn profile (the one the stepper holds, and its contact-implicit step solves for),
//        s = e / (f p_ref)   where p_ref > 0,   s = 0 elsewhere,
//    so that c p_ref s = c e / f exactly. For an in-phase cycle under a constant P, e = f p Σ |Δw| cell by cell (a
//    slipping cell sits at its bound), and s is the slip travelled again, to round-off: the history reduces to the
//    force-controlled wear (tests/verification/test_wear_loads.cpp). The contact-implicit step scales the rate with
//    the end-of-step pressure at this s, i.e. takes the energy per cycle proportional to the pressure under P.
//    Under a history p_ref is the pressure under the history's largest P (P_ref_; load.P when that is larger),
//    whose contact covers every cell that touches during the cycle, so no energy is left out; CycleResponse::p and
//    the records' pressure are that pressure, and the contact-implicit step solves under that load. β ≠ 0 without
//    a history: p_ref is the uncoupled pressure under P, on whose contact the coupled cycle dissipates.
//    Where p_ref is small against the pressure the cell carries while it slips in the cycle (e = f p̄ Σ|Δw|, p̄ that
//    pressure's slip-weighted mean), e / (f p_ref) = (p̄/p_ref) Σ|Δw| grows without bound: at the edges of the worn
//    zones near the limit, where the coupled cycle still loads cells that the pressure under P has left. The ratio
//    of two small pressures there swings from step to step, and the stepper's error estimate with it (a dissimilar
//    Hertz run at 512 cells cut its jump to 1e-307 cycles). So s is capped at kEnergySlipCap = 2 times the slip
//    travelled: exact (c p_ref s = c e / f) wherever p_ref ≥ p̄/2, and below that the wear rate is c p_ref · 2Σ|Δw|,
//    less than the energy's, falling to zero with p_ref. Such cells wear as the uncoupled pressure under P says;
//    the limit the run tends to is then that of the pressure under P (PERFORMANCE.md, "Dissimilar bodies").
//  - off the contact (p_ref = 0, material there): the slip on touching, CycleResponse::s_touching, that the
//    contact-implicit step takes for the cells it loads (AnalogyContactResponse says why): in partial slip what the
//    marched cycle moved the surfaces there relative to each other (CycleResult::slip_if_touching), in gross slip
//    the contact's s continued over the gaps (the bodies slide past every x alike).
//
// The coupled cycle (β ≠ 0: force or displacement control, or a load history) settles in kSettlingIncrements = 4
// per cycle: the first loading in one increment and the first cycle in four (a history's segments in their shares of
// four, one each at least), then the scene's steady cycle (45
// increments of about five block Gauss–Seidel sweeps at 40 per cycle, against 90 marching all at 40): only the
// steady cycle is reported, and the state at its start hardly remembers the march to it (contact/incremental_slip.hpp,
// settling_increments, and tests/verification/test_coupled_increments.cpp: 1e-8 of the energy, 1e-6 p0; under a
// history with P out of phase, 2e-8 and 7e-7 p0). Under a constant P, on an even
// worn gap (Hertz, any symmetric profile, worn by symmetric cycles) it marches only the unloading half of the steady
// cycle and takes the reloading half as its mirror image (mirror_half_cycle, contact/incremental_slip.hpp): 25
// increments instead of 45, the energy within 5e-7 of the full march's (under displacement control, where each
// increment is a δ search, 2.3e-7: tests/verification/test_coupled_mirror.cpp).
//
// The lagged coupling (β ≠ 0 under a constant P, Coupling::lagged, the default; under displacement control in partial
// slip without bulk strain; under a load history). The analogy's uncoupled cycle on the same worn profile
// (AnalogyContactResponse: a normal and a corrective solve; under displacement control a dozen corrective solves
// more, for the Q that reaches δ) costs a few hundredths of a coupled cycle; under a history there is no analogy, and
// the uncoupled cycle is the marched one of β = 0 through the same history (an IncrementalContactResponse of its
// own: one tangential solve an increment where the coupled cycle takes some five sweeps of a normal and a tangential
// solve, and the first loading and first run through the history in full), about a tenth. So a response may be
//     s(w) = max(0, s_u(w) + Δs(w_r))   on the contact of p(w) (zero off it),   Δs(w_r) = s_c(w_r) − s_u(w_r),
// s_u the uncoupled slip, s_c the coupled one (the energy's equivalent above) and w_r the profile of the last
// coupled response (the refresh); the shear at the top of the cycle is corrected alike, and so is Q under
// displacement control (Q_u(w) + Q_c(w_r) − Q_u(w_r)), and off the contact the slip on touching (the coupled cycle's
// slip_if_touching less the analogy's at w_r); the stick zones are the refresh's. Its error is measured, as the stepper measures the worn profile, in the wear it adds: with the rates
// r = p s, the relative error of the lagged rate of the worn area (h c Σ_i p_i s_i)
//     ε = Σ_i p_i |max(0, s_u,i + Δs_i(w_r)) − s_c,i(w)| / Σ_i p_i s_c,i(w)
// is taken proportional to how far the uncoupled rate has moved since the refresh,
//     ε ≈ γ · drift,   drift = Σ_i |r_u,i(w) − r_u,i(w_r)| / Σ_i r_u,i(w_r),
// and over the wear since the refresh (the worn area A(w) − A(w_r)) it adds at most ε (A(w) − A(w_r)) to the worn
// area. A response is lagged while
//     γ · drift · |A(w) − A(w_r)|  ≤  kLagSafety · τ · A(w),   τ = effects.wear.tolerance, kLagSafety = 1/2,
// i.e. while the lag has added less than half what one accepted step may err by (the stepper holds each step's error to
// τ max w; here the worn area's share), aiming to add at most half of the stepper's own error (measured against a run
// coupled at every response at τ/10: it adds once or twice the stepper's own, about 1e-3 of the worn area, since γ ·
// drift misses part of the edge cells' error; docs/PERFORMANCE.md, "Dissimilar bodies"); and in full otherwise, at
// the first call, when the uncoupled cycle's stick zones move, and when its contact reaches the window's ends (the
// coupled response raises the error). Each refresh measures ε for the correction it replaces and sets γ = ε /
// drift from it, a quarter of the last γ at least (at the first, with no ε yet, γ = ρ = Σ_i p_i |Δs_i| / Σ_i p_i s_c,i,
// the correction's share of the rate: the correction taken to move with the rate it corrects), so a correction that
// moved more than γ said makes the next refresh come sooner. The drift and ε are in the worn area's norm, not cell by
// cell: at the contact's edges the correction jumps as the worn contact spreads there one cell at a time (about 1 % of
// the peak rate per accepted step at 256 cells, the coupled and the uncoupled cycle loading the new edge cell
// differently), a maximum-norm bound would couple every response, and those jumps change sign from step to step. Near
// the limit, where the worn area hardly grows, nearly every response is lagged. docs/PERFORMANCE.md ("Dissimilar
// bodies") has the run against every response coupled at 256 to 1024 cells;
// tests/verification/test_wear_lagged_coupling.cpp holds a run to it, under force and under displacement control
// and under a history. Under displacement control Q, and with it the uncoupled stick zone's edges within their cells,
// moves at every response, and under a history the marched stick zone's edges move with the pressure the worn slip
// zones leave it: there the stick zones count as moved when an edge crosses into another cell. Where the analogy cannot
// follow the worn contact (it slides, or slips backwards at its leading edge) every later response is coupled.
//
// Similar bodies under displacement control in partial slip (route "auto", no bulk strain): every response is the
// analogy's at the Q whose cycle reaches δ (AnalogyContactResponse's displacement mode, on this datum), which for
// β = 0 is the marched cycle's to the solves' tolerances (tests/verification/test_wear_displacement_analogy.cpp: Q
// 4e-9, the slip 2.3e-7 of its largest) at a sixth of its cost or less; where the worn contact slides or slips
// backwards, every later response is marched, and analogy_gave_up() says why.
class IncrementalContactResponse : public WearContact {
 public:
  // How a β ≠ 0 response takes in the coupling (above); β = 0 always solves its own cycle.
  enum class Coupling { every_response, lagged };
  // The cycle stage's load (its plan) and datum.
  IncrementalContactResponse(const Scene& scene, const Model& model, const CycleStage& cycle,
                             Coupling coupling = Coupling::lagged);
  // Another load on the cycle stage's datum (a block of load.blocks; P and f are the scene's).
  IncrementalContactResponse(const Scene& scene, const Model& model, const CycleStage& cycle, const CyclicLoad& load,
                             Coupling coupling = Coupling::lagged);
  // Throws InputError when the worn contact reaches the end of the window (check_window; a sliding contact keeps
  // widening).
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  const std::vector<double>& shear_top() const override { return q_top_; }
  double Q_top() const override { return Q_top_; }
  // The steady cycle of the last coupled response (the refresh, under Coupling::lagged).
  const CycleResult& last_cycle() const { return cycle_; }
  // Responses that solved the coupled cycle, those of them that marched half of it and mirrored the rest
  // (mirror_half_cycle, contact/incremental_slip.hpp), and those that took the lagged correction.
  long coupled_responses() const { return coupled_responses_; }
  long mirrored_responses() const { return mirrored_responses_; }
  // Responses to a load history whose march did not reach a cycle that repeats the one before it.
  long unsteady_responses() const { return unsteady_responses_; }
  long lagged_responses() const { return lagged_responses_; }
  // Similar bodies under displacement control: responses answered by the analogy (header). Why the analogy (this
  // one's, or the lag's) stopped answering where it did: empty while it answers every one.
  long analogy_responses() const { return analogy_responses_; }
  const std::string& analogy_gave_up() const { return analogy_gave_up_; }
  // Dundurs β of the pair: the cycle is coupled where it is not 0.
  double beta() const { return beta_; }
  // Have the responses give as s the slip travelled per cycle where β ≠ 0 too, not the energy's equivalent
  // e / (f p_ref): for a caller that weighs the slip by pressures of its own (the bodies' frames in gross slip,
  // engine/body_frames.hpp, which solve the coupled pressure at each position of the stroke).
  void give_slip_travelled() { slip_travelled_ = true; }
  nlohmann::json save() const override;
  void restore(const nlohmann::json& j) override;

 private:
  // The analogy's response on w into r, counted; false (and no analogy from now on, analogy_gave_up() saying why)
  // where it cannot follow the worn contact.
  bool respond_by_analogy(std::span<const double> w, wear::CycleResponse& r);
  // The cycle solved on w (every response but the lagged ones).
  void respond_coupled(std::span<const double> w, wear::CycleResponse& out);
  // The lagged response from uncoupled_ (the analogy's on w) and the last correction.
  void respond_lagged(wear::CycleResponse& out);
  // After a coupled response `out` on w (the profile of uncoupled_): ε, γ and the new correction.
  void refresh(std::span<const double> w, const wear::CycleResponse& out);
  // Whether the response on w may take the lagged correction (header).
  bool lag_allowed(std::span<const double> w) const;
  double worn_area(std::span<const double> w) const;  // h Σ w (m²)
  // The uncoupled wear rate's drift since the refresh, and whether its stick zones are the refresh's.
  double drift() const;
  bool same_stick_zones() const;

  IncrementalSlipSolver slip_;
  ReferenceDatum datum_;
  CyclicLoad load_;
  double beta_ = 0.0;  // Dundurs β of the pair (0: similar bodies, uncoupled)
  bool slip_travelled_ = false;  // give_slip_travelled()
  ContactState normal_;     // under load.P: where the cycle's first loading starts
  ContactState reference_;  // under P_ref_ when it is not load.P (a history): p_ref
  CycleResult cycle_;
  std::vector<double> q_top_;  // the shear at the top of the cycle of the last response (Pa)
  long coupled_responses_ = 0, mirrored_responses_ = 0, lagged_responses_ = 0, analogy_responses_ = 0;
  long unsteady_responses_ = 0;
  double Q_top_ = 0.0;            // the tangential load at the top of the last response's cycle (N/m)
  std::string analogy_gave_up_;
  // The lagged coupling's uncoupled cycle (null: every response coupled): the analogy's, or under a load history
  // the marched one of β = 0.
  std::unique_ptr<WearContact> analogy_;
  wear::CycleResponse uncoupled_;      // the analogy's response on the current w (its p warm-starts the next)
  wear::CycleResponse uncoupled_ref_;  // ... and on w_r
  wear::CycleResponse coupled_ref_;    // the coupled response on w_r (its stick zones)
  std::vector<double> slip_correction_, shear_correction_;  // Δs(w_r) (m) and q_top's (Pa)
  // Off the contact: the coupled cycle's slip on touching less the uncoupled one's at w_r (m; CycleResponse::s_touching)
  std::vector<double> touching_correction_;
  double gain_ = -1.0;                 // γ: ε per unit drift; negative before the first refresh
  double area_ref_ = 0.0;              // the worn area of w_r (m²)
  double Q_correction_ = 0.0;          // Q_top's (N/m): the coupled cycle's Q less the analogy's on w_r
  double tolerance_ = 0.0;             // τ: the stepper's tolerance
};

// The contact the wear stage sees: by the route the cycle stage ran (IncrementalContactResponse, with the cycle
// stage's datum, or AnalogyContactResponse), so that the route, with its `auto` fallback, is decided once. Throws
// what their constructors throw.
std::unique_ptr<WearContact> make_wear_contact(const Scene& scene, const Model& model, const CycleStage& cycle);

}  // namespace fretwear
