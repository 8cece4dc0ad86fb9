// The wear stage of a scene: the contact seen by wear (the analogy route on the worn profile, or the incremental
// route under displacement control), the asymptotic state computed directly, and the run driven through
// Boost.Odeint with records.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/contact_zones.hpp"
#include "contact/incremental_slip.hpp"
#include "contact/normal_solver.hpp"
#include "contact/reference_datum.hpp"
#include "contact/wear_limit.hpp"
#include "engine/scene.hpp"
#include "wear/contact_response.hpp"
#include "wear/implicit_stepper.hpp"
#include "wear/reference_steppers.hpp"

namespace fretwear {

struct Model;
struct NormalResult;

using Interval = std::pair<double, double>;

// The asymptotic state of paper 002 (PHYSICS.md, "Wear"; contact/wear_limit.hpp): complete contact over the initial
// stick zone on the original profile; the worn depth is the overlap it leaves outside. It assumes a stick zone that
// stays where it started, which holds under force control (Q between fixed limits); under displacement control Q_max
// changes as the contact wears and the stick zone moves with it (in partial slip the wear still stops, at a limit this
// does not compute; in gross slip there is no stick zone and wear never stops), so the state is not computed there and
// `unavailable` says why (w and p are then empty).
struct WearAsymptote : WearLimit {
  std::string unavailable;  // empty when computed; otherwise the reason it is not
};

// One record of the run.
struct WearRecord {
  double cycles = 0.0;
  double worn_area = 0.0, max_depth = 0.0, p_max = 0.0;
  double Q_max = 0.0;  // the tangential load at the top of the cycle (N/m): the scene's under force control, the one
                       // the prescribed δ gives on the worn profile under displacement control
  std::optional<Interval> stick_zone;
  Interval contact{0.0, 0.0};
  double fraction = 0.0;  // worn area over the asymptote's (0 without one)
  std::vector<double> w, p, s;  // per cell
  std::vector<double> q;        // shear traction at the top of the cycle per cell (Pa); the bottom is −q
};

struct WearStage {
  std::vector<WearRecord> records;
  WearAsymptote asymptote;
  double rate_coefficient = 0.0;    // c in dw/dN = c p s (1/Pa)
  std::string route;                // the cycle's route on the worn profile: "analogy" or "incremental"
  double stability_limit = 0.0;     // the explicit jump limit 1.5 Δx/(E* c s_max) at the start (cycles)
  double explicit_step_cap = 0.0;   // stepper "explicit": the cap on ΔN, kExplicitCapFraction · stability_limit
                                    // (cycles); 0 for the other steppers
  double explicit_max_step = 0.0;   // stepper "explicit": the longest accepted step (cycles), ≤ the cap
  int steps = 0, rejected_steps = 0, implicit_solves = 0, responses = 0;
  int unconverged_steps = 0;  // implicit steps rejected because a contact-implicit solve did not converge
  double mean_iterations_cycle = 0.0, mean_iterations_implicit = 0.0;  // CG iterations per warm-started solve
  bool interrupted = false;               // stopped on request before the last cycle (records hold what was done)
  double cycles_reached = 0.0;            // where the run stopped (the last cycle when it completed)
  std::optional<double> resumed_from;     // the cycle of the checkpoint the run continued from
};

// Steering a wear run from outside it: progress, checkpoints and a stop request. wear/ knows none of this; the
// engine's driver calls these at step boundaries (after every accepted step and after every record).
struct WearProgress {
  double cycles = 0.0, total = 0.0;  // done and asked for
  double dN = 0.0;                   // the next step's size (cycles)
  double fraction = 0.0;             // worn area over the asymptote's
  int steps = 0;                     // accepted steps so far
};

struct WearControl {
  std::function<void(const WearProgress&)> progress;  // may be empty
  std::function<bool()> stop_requested;               // true: stop at this boundary (a checkpoint is written)
  std::filesystem::path checkpoint;                   // where checkpoints go; empty: none
  double checkpoint_interval = 60.0;                  // seconds between checkpoints between records (0: every step)
  std::uint64_t scene_hash = 0;                       // scene_hash(scene) (engine/checkpoint.hpp), stored in it
  std::optional<nlohmann::json> resume;               // a checkpoint read by read_checkpoint(), to continue from
};

// What run_wear needs of a contact besides wear::ContactResponse: the shear at the top of the last cycle solved
// (records), the warm starts of its solves (checkpoints) and its counts.
class WearContact : public wear::ContactResponse {
 public:
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
  // The end-of-step pressure of wear::ContactResponse::implicit_pressure, with `solver` (route-independent for
  // similar bodies: the pressure does not depend on the shear).
  bool solve_implicit(const NormalSolver& solver, const Model& model, double P, std::span<const double> w,
                      std::span<const double> d, std::vector<double>& p);
  ContactState implicit_;
  std::vector<double> gap_;
};

// The steady-cycle slip and stick zone on a worn profile, by the analogy route (similar bodies, constant P).
class AnalogyContactResponse : public WearContact {
 public:
  AnalogyContactResponse(const Scene& scene, const Model& model);
  int cells() const override;
  double cell_width() const override;
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) override;
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
  const Scene& scene_;
  const Model& model_;
  NormalSolver solver_;
  NormalSolver implicit_solver_;
  double tilt_ = 0.0, corrective_load_ = 0.0;
  ContactState normal_, corrective_;
  std::vector<double> q_top_;
  std::vector<Zone> stick_zones_;
};

// The steady cycle on a worn profile by the incremental route (contact/incremental_slip.hpp): similar bodies under
// the scene's control, force or displacement (load.control, load.delta), through the onset of gross slip. respond(w)
// solves the normal contact of g0 + w under P (warm-started from the last), then marches the first loading and one
// cycle; the second of those is the steady cycle, whose slip travelled per cell is s (in gross slip, 4 times the
// sliding amplitude plus the elastic part, over the whole contact; no stick zone). The reference points of δ are
// those of the cycle stage (centre of the unworn contact, reference_depth below), fixed in the bodies as they wear.
// The marching itself starts from rest each time (it is fast and has no warm start); the normal and contact-implicit
// solves are warm-started, and save()/restore() carry those starts.
class IncrementalContactResponse : public WearContact {
 public:
  // reference_x, reference_depth: the datum (m), as CycleStage has them.
  IncrementalContactResponse(const Scene& scene, const Model& model, double reference_x, double reference_depth);
  int cells() const override;
  double cell_width() const override;
  // Throws InputError when the worn contact reaches the end of the window (a sliding contact keeps widening).
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) override;
  const std::vector<double>& shear_top() const override { return cycle_.q_top; }
  double Q_top() const override { return cycle_.Q_peak; }
  // The steady cycle of the last respond().
  const CycleResult& last_cycle() const { return cycle_; }
  nlohmann::json save() const override;
  void restore(const nlohmann::json& j) override;

 private:
  const Scene& scene_;
  const Model& model_;
  NormalSolver solver_;
  NormalSolver implicit_solver_;
  IncrementalSlipSolver slip_;
  ReferenceDatum datum_;
  CyclicLoad load_;
  ContactState normal_;
  CycleResult cycle_;
};

// Whether the wear stage runs the cycle by the incremental route: under displacement control, or when the scene
// asks for that route.
bool wear_uses_incremental(const Scene& scene);

// The asymptote of the scene on `model`: wear_limit() over the stick zones of the first cycle by the analogy route,
// or the reason it does not apply (displacement control; reverse slip, which the analogy cannot follow). Throws
// ConvergenceError when its solve does not converge.
WearAsymptote wear_asymptote(const Scene& scene, const Model& model, const NormalResult& normal);

// The explicit stepper's cap on ΔN as a share of the forward-Euler limit 1.5 Δx/(E* c s_max). Dormand–Prince's
// stability region reaches about 3.3 along the negative real axis where Euler's reaches 2, so this leaves dopri5 a
// margin of about 1.5 for the limit's drift as the profile wears and for the estimate's own approximation.
inline constexpr double kExplicitCapFraction = 0.9;

// What a wear run costs before it starts, from its first cycle: the explicit stability limit and the responses (one
// steady cycle each) the stepper will take. The implicit stepper takes a few hundred whatever the cycle count and is
// not estimated (responses 0). Throws what run_wear would throw at its first cycle.
struct WearEstimate {
  double seconds_per_response = 0.0;  // wall time of one warm-started cycle response (s)
  double stability_limit = 0.0;       // 1.5 Δx/(E* c s_max) (cycles); 0 when nothing slips
  double responses = 0.0;             // cycle responses the run will take (at least)
  double seconds() const { return responses * seconds_per_response; }
};
WearEstimate estimate_wear(const Scene& scene, const Model& model, const NormalResult& normal);
// Why the stepper "cycle_by_cycle" cannot run at this explicit stability limit (cycles): a jump of one cycle past it
// is unstable. Empty when it can (or nothing slips: limit 0).
std::string cycle_by_cycle_problem(double stability_limit);

// Runs the wear of a scene with the stepper it names (effects.wear.stepper): "implicit" (the default), "explicit"
// (Dormand–Prince capped below the stability limit; small problems) or "cycle_by_cycle" (every cycle worn, the
// reference on short runs; throws UnsupportedError when one cycle exceeds the stability limit). The normal solution
// and the first cycle have been computed on the same model. `control` reports progress, writes checkpoints, continues
// from one and stops on request (then WearStage::interrupted).
WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal,
                   const WearControl& control = {});

}  // namespace fretwear
