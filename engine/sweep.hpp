// `fretwear sweep`: the product of variations of a scene, run on the local cores, one output folder per run, a table
// of every run's summary, and a fretting map over the first two varied keys.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fretwear {

// One --vary: a dotted key path into the scene ("load.Q.ratio") and its values.
struct Variation {
  std::string key;
  std::vector<nlohmann::json> values;
};

// Parses "key=v1,v2,..." (values as JSON numbers, booleans or bare words taken as strings). Throws InputError.
Variation parse_variation(const std::string& text);

struct SweepRun {
  std::vector<nlohmann::json> values;  // one per variation
  std::string name;                    // the run's scene name (its output folder)
  int status = 0;                      // 0 done, 2 invalid, 3 not converged
  std::string message;
  nlohmann::json summary;              // empty unless done
};

struct SweepResult {
  std::vector<Variation> variations;
  std::vector<SweepRun> runs;
  std::filesystem::path dir;  // the sweep's folder (the base scene's output.dir)
};

// Validates every variant before running any (all problems at once, SceneError); then runs them on `jobs` threads,
// each into <dir>/runs/<name>/, and writes <dir>/sweep.csv, <dir>/sweep.json and, with plots, the fretting map.
SweepResult run_sweep(const std::filesystem::path& scene_file, const std::vector<Variation>& variations, int jobs,
                      std::ostream* progress);

}  // namespace fretwear
