// What the command line and the Python module (python/) share beyond Simulation and write_results: the summary of a
// run that did not converge.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"

namespace fretwear {

// summary.json of a run whose solver did not converge (the command line's exit status 3): the scene, the version,
// "status": "not_converged" and the solver's message.
nlohmann::json not_converged_summary(const Scene& scene, const std::string& message);

}  // namespace fretwear
