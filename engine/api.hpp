// What the command line and the Python module (python/) share beyond Simulation and write_results: the summary (and
// the tables) of a run that did not converge.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "engine/folder.hpp"
#include "engine/scene.hpp"
#include "engine/warnings.hpp"

namespace fretwear {

// summary.json of a run whose solver did not converge (the command line's exit status 3): the scene, the version,
// "status": "not_converged", the solver's message and `failed_stage`, the stage whose solve it was (null when
// `error` does not say: it is not a StageNotConverged of Simulation::run()). When that stage came after the normal
// contact, also what a completed run's summary (make_summary) gives for the normal contact and for each stage that
// completed before it, in the same keys (contact, grid, solver, cycle, wear, stress, ...; effects_run and timings
// list those stages). `warnings`: those found before solving (`before`, the preflight's), then those of the stages
// that completed.
nlohmann::json not_converged_summary(const Scene& scene, const ConvergenceError& error,
                                     const std::vector<Warning>& before = {});

// Writes that summary to `out` as summary.json (returned too) and, where the wear stage failed part way, the tables
// of its records before the failure (wear_history.csv, profiles.csv and, for several stick zones,
// wear_stick_zones.csv; no plots). The caller commits `out`.
nlohmann::json write_not_converged(const Scene& scene, const ConvergenceError& error, const std::vector<Warning>& before,
                                   OutputFolder& out);

// The same from the solver's message alone: `failed_stage` null, no stage's results, no warnings.
nlohmann::json not_converged_summary(const Scene& scene, const std::string& message);

}  // namespace fretwear
