#include "engine/api.hpp"

#include <algorithm>

#include "engine/simulation.hpp"
#include "engine/version.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
using nlohmann::json;

json not_converged_summary(const Scene& scene, const ConvergenceError& error, const std::vector<Warning>& before) {
  const auto* failed = dynamic_cast<const StageNotConverged*>(&error);
  const RunResult* partial = failed ? failed->partial() : nullptr;
  json summary = partial ? make_summary(scene, *partial)
                         : json{{"scene", scene.name}, {"version", kVersion}, {"effects_run", json::array()}};
  json warnings = json::array();
  for (const Warning& w : before) warnings.push_back({{"code", w.code}, {"message", w.message}});
  for (const json& w : summary.value("warnings", json::array())) warnings.push_back(w);
  summary["warnings"] = std::move(warnings);
  summary["status"] = "not_converged";
  summary["message"] = error.what();
  summary["failed_stage"] = failed ? json(failed->stage()) : json(nullptr);
  if (failed) {  // effects_run: the stages that completed (a wear stage that failed part way has its section)
    json& run = summary["effects_run"];
    run.erase(std::remove(run.begin(), run.end(), json(failed->stage())), run.end());
  }
  return summary;
}

json write_not_converged(const Scene& scene, const ConvergenceError& error, const std::vector<Warning>& before,
                         OutputFolder& out) {
  json summary = not_converged_summary(scene, error, before);
  out.write_json("summary.json", summary);
  const auto* failed = dynamic_cast<const StageNotConverged*>(&error);
  const RunResult* partial = failed ? failed->partial() : nullptr;
  if (partial && partial->wear && failed->stage() == "wear") {  // its records up to the failure, as tables
    Scene tables_only = scene;
    tables_only.plots = false;
    Written written;
    write_wear(tables_only, partial->normal, *partial->cycle, *partial->wear, out, written);
  }
  return summary;
}

json not_converged_summary(const Scene& scene, const std::string& message) {
  return not_converged_summary(scene, ConvergenceError(message));
}

}  // namespace fretwear
