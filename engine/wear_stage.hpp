// The wear stage of a scene: the contact seen by wear (the analogy route on the worn profile), the asymptotic state
// computed directly, and the run driven through Boost.Odeint with records.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/contact_zones.hpp"
#include "contact/normal_solver.hpp"
#include "engine/scene.hpp"
#include "wear/contact_response.hpp"
#include "wear/implicit_stepper.hpp"
#include "wear/reference_steppers.hpp"

namespace fretwear {

struct Model;
struct NormalResult;

using Interval = std::pair<double, double>;

// The asymptotic state of paper 002 (PHYSICS.md, "Wear"): complete contact over the initial stick zone on the
// original profile; the worn depth is the overlap it leaves outside.
struct WearAsymptote {
  std::vector<double> p;       // pressure (Pa), zero outside the stick zone
  std::vector<double> w;       // worn depth, both bodies (m)
  double worn_area = 0.0;      // ∫ w dx (m²)
  double max_depth = 0.0;      // m
  double x_max_depth = 0.0;    // m
  Interval extent{0.0, 0.0};   // where w > 0 (outer ends, m)
};

// One record of the run.
struct WearRecord {
  double cycles = 0.0;
  double worn_area = 0.0, max_depth = 0.0, p_max = 0.0;
  std::optional<Interval> stick_zone;
  Interval contact{0.0, 0.0};
  double fraction = 0.0;  // worn area over the asymptote's
  std::vector<double> w, p, s;  // per cell
  std::vector<double> q;        // shear traction at the top of the cycle per cell (Pa); the bottom is −q
};

struct WearStage {
  std::vector<WearRecord> records;
  WearAsymptote asymptote;
  double rate_coefficient = 0.0;    // c in dw/dN = c p s (1/Pa)
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
  std::uint64_t scene_hash = 0;                       // scene_hash(scene), stored in the checkpoint
  std::optional<nlohmann::json> resume;               // a checkpoint read by read_checkpoint(), to continue from
};

// Checkpoints (docs/SCENES.md, "Long runs"): everything a wear run carries from one step to the next — the wear
// depth, the cycle, the next ΔN, the record index, the records so far, the stepper's and the contact solver's warm
// starts and counts — so that a resumed run takes exactly the steps the uninterrupted one takes. CBOR (RFC 8949),
// vectors as raw little-endian doubles; written to a temporary file, fsync'ed and renamed over the previous one.
inline constexpr int kCheckpointFormat = 1;
// <output.dir>.checkpoint: beside the output folder, which is replaced only when a run completes.
std::filesystem::path checkpoint_path(const Scene& scene);
// FNV-1a (64 bit) of the resolved scene's JSON: two scenes that resolve alike share a checkpoint.
std::uint64_t scene_hash(const Scene& scene);
// The checkpoint at `path` for this scene, or nothing when there is none. Throws InputError when the file is not a
// fretwear checkpoint, has another format or fretwear version, or belongs to another scene.
std::optional<nlohmann::json> read_checkpoint(const std::filesystem::path& path, const Scene& scene);
// Writes j atomically (temporary file, fsync, rename, fsync of the folder).
void write_checkpoint(const std::filesystem::path& path, const nlohmann::json& j);

// The steady-cycle slip and stick zone on a worn profile, by the analogy route (similar bodies, constant P).
class AnalogyContactResponse : public wear::ContactResponse {
 public:
  AnalogyContactResponse(const Scene& scene, const Model& model);
  int cells() const override;
  double cell_width() const override;
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) override;
  // The last contact-implicit solve that did not converge (its termination and residual), for the error message.
  SolveSummary last_unconverged;
  // The last normal and corrective pressures (for records).
  const std::vector<double>& corrective_pressure() const { return corrective_.p; }
  // The stick zones of the last cycle, one per run of the corrective contact (several where the contact has
  // several zones); the CycleResponse carries only their span.
  const std::vector<Zone>& stick_zones() const { return stick_zones_; }
  // The warm starts of the solves and the counts below, for checkpoints.
  nlohmann::json save() const;
  void restore(const nlohmann::json& j);
  // Solves and their CG iterations, by kind: the cycle (normal and corrective) and the contact-implicit steps.
  long cycle_solves = 0, cycle_iterations = 0, implicit_solves = 0, implicit_iterations = 0;

 private:
  const Scene& scene_;
  const Model& model_;
  NormalSolver solver_;
  // The contact-implicit solves give up sooner than the cycle's: a step whose solve does not converge is retried
  // with a smaller jump (wear/implicit_stepper.hpp), which is cheaper than iterating on a badly conditioned one.
  // Converging solves take tens to about 1500 iterations at 4096 cells; the limit grows with the grid.
  static NormalSolverOptions implicit_options(int cells) {
    NormalSolverOptions o;
    o.max_iterations = std::max(2000, cells);
    return o;
  }
  NormalSolver implicit_solver_;
  double tilt_ = 0.0, corrective_load_ = 0.0;
  ContactState normal_, corrective_, implicit_;
  std::vector<double> gap_;
  std::vector<Zone> stick_zones_;
};

WearAsymptote wear_asymptote(const Scene& scene, const Model& model, const NormalResult& normal);

// The explicit stepper's cap on ΔN as a share of the forward-Euler limit 1.5 Δx/(E* c s_max). Dormand–Prince's
// stability region reaches about 3.3 along the negative real axis where Euler's reaches 2, so this leaves dopri5 a
// margin of about 1.5 for the limit's drift as the profile wears and for the estimate's own approximation.
inline constexpr double kExplicitCapFraction = 0.9;

// Runs the wear of a scene with the stepper it names (effects.wear.stepper): "implicit" (the default), "explicit"
// (Dormand–Prince capped below the stability limit; small problems) or "cycle_by_cycle" (every cycle worn, the
// reference on short runs; throws UnsupportedError when one cycle exceeds the stability limit). The normal solution
// and the first cycle have been computed on the same model. `control` reports progress, writes checkpoints, continues
// from one and stops on request (then WearStage::interrupted).
WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal,
                   const WearControl& control = {});

}  // namespace fretwear
