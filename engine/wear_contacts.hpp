// The contact as the wear stage sees it: wear::ContactResponse (wear/contact_response.hpp) answered on top of
// contact/, by the analogy route on the worn profile (similar bodies, force control) or by the incremental route
// (displacement control, or when the scene asks for it), with what the stage needs besides: the shear at the top of
// the cycle for records, the solves' warm starts for checkpoints, and the solves' counts.
#pragma once

#include <algorithm>
#include <memory>
#include <span>
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
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  const std::vector<double>& shear_top() const override { return q_top_; }
  double Q_top() const override { return scene_.Q_max(); }
  // The last corrective pressure (for records).
  const std::vector<double>& corrective_pressure() const { return corrective_.p; }
  // The stick zones of the last cycle, one per run of the corrective contact (several where the contact has
  // several zones); the CycleResponse carries only their span.
  const std::vector<Zone>& stick_zones() const { return stick_zones_; }
  nlohmann::json save() const override;
  void restore(const nlohmann::json& j) override;

 private:
  double tilt_ = 0.0, corrective_load_ = 0.0;
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
class IncrementalContactResponse : public WearContact {
 public:
  // The cycle stage's load (its plan) and datum.
  IncrementalContactResponse(const Scene& scene, const Model& model, const CycleStage& cycle);
  // Another load on the cycle stage's datum (a block of load.blocks; P and f are the scene's).
  IncrementalContactResponse(const Scene& scene, const Model& model, const CycleStage& cycle, const CyclicLoad& load);
  // Throws InputError when the worn contact reaches the end of the window (a sliding contact keeps widening).
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  const std::vector<double>& shear_top() const override { return cycle_.q_top; }
  double Q_top() const override { return cycle_.Q_peak; }
  // The steady cycle of the last respond().
  const CycleResult& last_cycle() const { return cycle_; }
  nlohmann::json save() const override;
  void restore(const nlohmann::json& j) override;

 private:
  IncrementalSlipSolver slip_;
  ReferenceDatum datum_;
  CyclicLoad load_;
  double beta_ = 0.0;  // Dundurs β of the pair (0: similar bodies, uncoupled)
  ContactState normal_;     // under load.P: where the cycle's first loading starts
  ContactState reference_;  // under P_ref_ when it is not load.P (a history): p_ref
  CycleResult cycle_;
};

// The contact the wear stage sees: by the route the cycle stage ran (IncrementalContactResponse, with the cycle
// stage's datum, or AnalogyContactResponse), so that the route, with its `auto` fallback, is decided once. Throws
// what their constructors throw.
std::unique_ptr<WearContact> make_wear_contact(const Scene& scene, const Model& model, const CycleStage& cycle);

}  // namespace fretwear
