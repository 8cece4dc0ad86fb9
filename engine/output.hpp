// Writing a run's results into its folder (engine/folder.hpp): summary.json, the resolved scene, each stage's
// CSV fields and plots, and index.html showing them.
#pragma once

#include <nlohmann/json.hpp>

#include "engine/folder.hpp"
#include "engine/plot.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"

namespace fretwear {

// summary.json, scene.resolved.json, contact.csv, the plots and index.html. Returns the summary written.
nlohmann::json write_results(const Scene& scene, const RunResult& result, OutputFolder& out);

}  // namespace fretwear
