// One scene, run: the setup resolved once (engine/setup.hpp: the model, the plan of the load cycle, the effects), then
// each stage the scene asks for, in order: normal, cycle, wear, stress (with its fatigue measures), crack, life.
// Simulation::run() reads like the method; each stage lives in an engine/*_stage.* module, the physics in contact/
// and wear/. stage_outputs() lists what each stage adds to summary.json and to the output folder, which
// make_summary() and write_results() (engine/output.hpp) loop over: a new effect adds its line there.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "engine/crack_stage.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/fatigue_stage.hpp"
#include "engine/folder.hpp"
#include "engine/life_stage.hpp"
#include "engine/normal_stage.hpp"
#include "engine/preflight.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "engine/stress_stage.hpp"
#include "engine/warnings.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

struct Timings {
  double total = 0.0, normal = 0.0;   // wall seconds
  std::optional<double> tangential;   // present when the stage ran
  std::optional<double> wear;
  std::optional<double> stress, crack, life;
};

struct RunResult {
  NormalResult normal;
  std::optional<CycleStage> cycle;
  std::optional<WearStage> wear;
  std::vector<StressMap> stress_maps;      // at the top and bottom of every state (initial, then each record)
  std::vector<SifSet> sifs;                // at the top and bottom of every state (initial, then each record)
  double crack_x = 0.0;                    // where the crack is (m)
  std::optional<QuadratureCheck> crack_quadrature;  // the last state's SIFs against half the points
  std::optional<FatigueStage> fatigue;     // SWT and Ruiz of every state, with the stress maps of a cycle
  std::optional<LifeStage> life;           // initiation and growth over the states the run went through
  Timings timings;
  std::vector<Warning> warnings;  // what the results cannot be trusted for (engine/warnings.hpp)
};

// A solve that did not converge in one stage of Simulation::run(): the solver's message (what()), the stage, and
// what the stages before it gave. A ConvergenceError, so that a caller wanting the message alone catches that.
class StageNotConverged : public ConvergenceError {
 public:
  StageNotConverged(const std::string& message, std::string stage, std::shared_ptr<const RunResult> partial)
      : ConvergenceError(message), stage_(std::move(stage)), partial_(std::move(partial)) {}
  // Its name in summary.json (effects_run, timings): "normal", "tangential", "wear", "stress", "crack" or "life".
  const std::string& stage() const { return stage_; }
  // The normal contact and the stages that completed before stage(), with their timings (total: up to the failure)
  // and their warnings (result_warnings); null when the normal stage failed.
  const RunResult* partial() const { return partial_.get(); }

 private:
  std::string stage_;
  std::shared_ptr<const RunResult> partial_;  // shared: an exception is copied as it is thrown
};

class Simulation {
 public:
  explicit Simulation(Scene scene) : scene_(std::move(scene)) {}
  // control (optional) steers the wear stage: progress, checkpoints, resume, stop. A wear stage stopped on request
  // (WearStage::interrupted) ends the run there: stress and crack, which use the last record, are not computed.
  // A solve that does not converge throws StageNotConverged, holding what the stages before it gave.
  // solved (optional): what the checks before solving solved for this scene (Preflight::solved), taken instead of
  // solving it again, with its wall times as the stages'.
  RunResult run(const WearControl* control = nullptr, const SolvedStages* solved = nullptr) const;
  const Scene& scene() const { return scene_; }

 private:
  Scene scene_;
};

// What a stage that ran adds to the summary and to the output folder.
struct StageOutputs {
  const char* effect;                       // its name in summary.json's effects_run and timings; null for none
  std::optional<double> Timings::*seconds;  // its wall time (with effect)
  bool (*ran)(const RunResult&);
  void (*summarise)(const Scene&, const RunResult&, nlohmann::json& summary);  // its part of summary.json
  void (*write)(const Scene&, const RunResult&, OutputFolder&, Written&);       // its CSVs and plots
};

// The stages after the normal one (whose part is the summary's top level and contact.csv), in the order they run.
const std::vector<StageOutputs>& stage_outputs();

// The singular edges of the state a run's stress maps show (engine/stress_stage.hpp).
SingularEdges singular_edges_of(const RunResult& result);

// summary.json (SCENES.md's contract).
nlohmann::json make_summary(const Scene& scene, const RunResult& result);

}  // namespace fretwear
