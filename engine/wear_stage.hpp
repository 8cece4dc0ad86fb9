// The wear stage of a scene: the wear of the contact over the cycles asked for, driven through Boost.Odeint with the
// stepper the scene names and recorded at the record times, and paper 002's asymptotic state where it applies. The
// contact it wears is engine/wear_contacts.hpp's, its checkpoints engine/checkpoint.hpp's, the asymptote's physics
// contact/wear_limit.hpp's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "contact/displacement_limit.hpp"
#include "contact/wear_limit.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "engine/stop.hpp"

namespace fretwear {

using Interval = std::pair<double, double>;

// The asymptotic state of paper 002 (PHYSICS.md, "Wear"; contact/wear_limit.hpp): complete contact over the initial
// stick zone on the original profile; the worn depth is the overlap it leaves outside. It assumes a stick zone that
// stays where it started, which holds under force control (Q between fixed limits). Under displacement control below
// the stick limit Q falls as the slip zones wear (contact/displacement_limit.hpp), so the first cycle's stick zone
// never slips either, and the asymptote is the complete contact over it, fully stuck under Q = δ/C (`Q_max`, C the
// stuck compliance by the datum); `note` says so, and that the stick zone may grow a little over points that have
// worn, which leaves the run slightly below this worn area. In gross slip there is no stick zone and wear never
// stops; there, and where the limit is not established (a history, blocks, dissimilar bodies, reverse slip, a bulk
// stress under displacement control), the state is not computed and `unavailable` says why (w and p are then empty).
//
// The run on the grid tends to a limit of its own: a cell wears or not as a whole, so the stick zones it never wears
// are the runs of cells the first cycle's corrective contact loads, whose ends are cell boundaries, while the direct
// limit puts its corners on the located edges. `cells_worn_area` is the limit over those cells (the same solve with
// the zones' ends moved to their cell boundaries), which the run reaches to the stepper's tolerance: the grid's share
// of the run's distance from the asymptote. The worn area is sensitive to the stick zone's ends (Hertz at Q/fP = 0.5,
// 1024 cells: an edge moved by a third of a cell moves it by 1 %), and this error is first order in h with a sign set
// by where the edges fall in their cells. make_model() puts cell boundaries on the first zone's ends, which leaves
// only the others' (engine/setup.hpp).
struct WearAsymptote : WearLimit {
  std::string unavailable;  // empty when computed; otherwise the reason it is not
  double cells_worn_area = 0.0;  // the limit over the run's stick cells, m² (0 without stick zones)
  // Under displacement control: Q at the limit (N/m), the stuck compliance C of its complete contact (m²/N), and how
  // the limit was found; unset or empty under force control.
  std::optional<double> Q_max, stuck_compliance;
  std::string note;
};

// The stick zones of the limit on the model's grid, located to sub-cell accuracy, one per run of the corrective
// contact: the first cycle's (AnalogyContactResponse; under displacement control the analogy's cycle that reaches
// load.delta, with the limit's Q in `displacement`), or why the limit is not computed (`unavailable`: gross slip,
// reverse slip, a history, blocks, dissimilar bodies, a bulk stress under displacement control).
struct InitialStick {
  std::vector<Zone> zones;
  std::string unavailable;
  std::optional<DisplacementLimit> displacement;  // under displacement control
};
InitialStick initial_stick_zones(const Scene& scene, const Model& model);

// One record of the run.
struct WearRecord {
  double cycles = 0.0;
  double worn_area = 0.0, max_depth = 0.0, p_max = 0.0;
  double Q_max = 0.0;  // the tangential load at the top of the cycle (N/m): the scene's under force control, the one
                       // the prescribed δ gives on the worn profile under displacement control
  std::optional<Interval> stick_zone;    // the stick zones' hull
  std::vector<Interval> stick_zones;     // every stick zone, left to right (one: the hull; none: empty)
  Interval contact{0.0, 0.0};   // the outer ends of the loaded contact
  Interval touching{0.0, 0.0};  // ... and of where the bodies touch, worn flats without load included
  double fraction = 0.0;  // worn area over the asymptote's (0 without one)
  std::vector<double> w, p, s;  // per cell; w is the gap's wear (at mid-stroke where the bodies' frames differ)
  // Each body's wear in its own frame (engine/body_frames.hpp; gross slip): the pad's at its points x, the
  // specimen's at its points X (X = x at mid-stroke), w = w_pad + w_specimen. Empty where both bodies share w,
  // split by pad_fraction.
  std::vector<double> w_pad, w_specimen;
  std::vector<double> q;        // shear traction at the top of the cycle per cell (Pa); the bottom is −q
  int block = -1;               // the block of load.blocks whose load it is under (from 0); -1 without blocks
};

// A body's scar ends where its wear falls below this share of its depth (WearStage::Scar).
inline constexpr double kScarEdge = 0.01;

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
  // Gross slip: each body's wear in its own frame (engine/body_frames.hpp), at this many positions over the stroke;
  // 0 where the bodies share one profile; and the sliding directions solved at each (2 for dissimilar bodies, whose
  // shear moves the pressure one way and the other, else 1). The fixed point's passes, over the steps' Euler
  // solutions.
  int frame_positions = 0, frame_directions = 0;
  long frame_iterations = 0;
  // Dissimilar bodies (β ≠ 0) by the incremental route: the run's cycle responses, those that solved the coupled
  // cycle (and of them, those that marched half of it and mirrored the rest) and those that took the lagged
  // correction (engine/wear_contacts.hpp). Absent for similar bodies and for load.blocks.
  struct Coupling {
    long responses = 0, coupled = 0, mirrored = 0, lagged = 0;
  };
  std::optional<Coupling> coupling;
  // Each body's scar at the last record (its own frame's where frame_positions > 0, else its share of w): the
  // deepest point, the area, and where its wear exceeds kScarEdge of that depth (m).
  struct Scar {
    double max_depth = 0.0, worn_area = 0.0;
    Interval extent{0.0, 0.0};
  };
  Scar pad, specimen;
  int unconverged_steps = 0;  // implicit steps rejected because a contact-implicit solve did not converge
  // Under a load history: cycle responses whose march reached IncrementalSlipOptions::steady_cycles_max cycles
  // without one ending where it began or repeating the one before it.
  long unsteady_history_responses = 0;
  double mean_iterations_cycle = 0.0, mean_iterations_implicit = 0.0;  // CG iterations per warm-started solve
  bool interrupted = false;               // stopped on request before the last cycle (records hold what was done)
  double cycles_reached = 0.0;            // where the run stopped (the last cycle when it completed)
  std::optional<double> resumed_from;     // the cycle of the checkpoint the run continued from
  std::string checkpoint_failure;         // why the last checkpoint could not be written; empty when it was
  // Under displacement control, with an asymptote: the limit of the last record's stick zones were they to stand
  // still (settled_worn_area(), contact/displacement_limit.hpp), and its Q, δ over their stuck compliance; what the
  // run tends to once its stick zone has settled, which growth over worn points leaves below the asymptote.
  struct Settled {
    double worn_area = 0.0;  // m²
    double Q_max = 0.0;      // N/m
  };
  std::optional<Settled> settled;
};

// Steering a wear run from outside it: progress, checkpoints and a stop request. wear/ knows none of this; the
// engine's driver calls these at step boundaries (after every accepted step and after every record).
struct WearProgress {
  double cycles = 0.0, total = 0.0;  // done and asked for
  double dN = 0.0;                   // the next step's size (cycles)
  double fraction = 0.0;             // worn area over the asymptote's
  int steps = 0;                     // accepted steps so far
  int block = -1, blocks = 0;        // under load.blocks: the block the run stands in (from 0), and how many
};

struct WearControl {
  std::function<void(const WearProgress&)> progress;  // may be empty
  // Asked at every boundary, with where the run stands: true stops the run there (a checkpoint is written). May be
  // empty.
  std::function<bool(const WearProgress&)> stop_requested;
  // Asked between the stages, and within the stress, crack and life stages between their parts (a map's columns, a
  // record's cracks, initiation and growth): true ends the run there with StopRequested (engine/stop.hpp).
  StopCheck stop_now;
  std::filesystem::path checkpoint;                   // where checkpoints go; empty: none
  double checkpoint_interval = 60.0;                  // seconds between checkpoints between records (0: every step)
  std::uint64_t scene_hash = 0;                       // scene_hash(scene), stored in the checkpoint
  std::optional<nlohmann::json> resume;               // a checkpoint read by read_checkpoint(), to continue from
};

// The asymptote of the scene on `model`: wear_limit() over the stick zones of initial_stick_zones(), or the reason it
// is not computed. Throws
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
  double seconds_per_response = 0.0;  // wall time of a warm-started cycle response, the least of a few (s)
  double stability_limit = 0.0;       // 1.5 Δx/(E* c s_max) (cycles); 0 when nothing slips
  double responses = 0.0;             // cycle responses the run will take (at least)
  double area_rate = 0.0;             // the worn area per cycle at the first cycle, c ∫ p s dx (m²/cycle)
  double seconds() const { return responses * seconds_per_response; }
};
// timed = false: the rates alone, without timing the responses (seconds_per_response stays infinite).
WearEstimate estimate_wear(const Scene& scene, const Model& model, const CycleStage& cycle, bool timed = true);
// Why the stepper "cycle_by_cycle" cannot run at this explicit stability limit (cycles): a jump of one cycle past it
// is unstable. Empty when it can (or nothing slips: limit 0).
std::string cycle_by_cycle_problem(double stability_limit);

// Whether the run tracks each body's wear in its own frame (engine/body_frames.hpp): gross slip (the sliding
// amplitude over half a cell) with the specimen wearing (pad_fraction < 1), similar or dissimilar bodies (for β ≠ 0
// each position's pressure is solved for each sliding direction), under any stepper. Elsewhere both bodies share
// one profile in the pad's frame, split by pad_fraction: in partial slip, or a stroke under half a cell, the two
// frames differ by less than a cell. This is the scene's own load's rule; under load.blocks each block's cycle
// decides for that block (false here, where the cycle stage solved the first block's alone).
bool bodies_in_own_frames(const Scene& scene, const Model& model, const CycleStage& cycle);

// Runs the wear of a scene with the stepper it names (effects.wear.stepper): "implicit" (the default), "explicit"
// (Dormand–Prince capped below the stability limit; small problems) or "cycle_by_cycle" (every cycle worn, the
// reference on short runs; throws UnsupportedError when one cycle exceeds the stability limit). The normal solution
// and the cycle stage have been computed on the same model; the wear stage runs the cycle by the route the cycle stage
// ran. `control` reports progress, writes checkpoints, continues from one and stops on request (then
// WearStage::interrupted).
// A solve that does not converge part way throws WearNotConverged once a record has been taken (before that, the
// solver's ConvergenceError).
WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal, const CycleStage& cycle,
                   const WearControl& control = {});

// A wear run whose solve did not converge after its first record: the solver's message (with the cycle the run had
// reached) and the stage as far as it got: the records taken before the failure, cycles_reached the last accepted
// step's cycle, the counts so far and each body's scar at the last record; no settled limit (under displacement
// control that is a solve of its own).
class WearNotConverged : public ConvergenceError {
 public:
  WearNotConverged(const std::string& message, std::shared_ptr<const WearStage> partial)
      : ConvergenceError(message), partial_(std::move(partial)) {}
  const WearStage& partial() const { return *partial_; }

 private:
  std::shared_ptr<const WearStage> partial_;  // shared: an exception is copied as it is thrown
};

// Its part of summary.json: "wear" (the law, the worn area and depth at the last record, the stick zone at the first
// and the last, the asymptote or why there is none, where the run got to, the integrator's counts).
nlohmann::json summarise_wear(const Scene& scene, const WearStage& wear);

// wear_history.csv, profiles.csv and, with plots, wear.gp (the worn profile and the pressure at each record, the stick
// zone and the worn area against cycles).
void write_wear(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, const WearStage& wear,
                OutputFolder& out,
                Written& written);

}  // namespace fretwear
