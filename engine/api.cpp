#include "engine/api.hpp"

#include "engine/simulation.hpp"
#include "engine/version.hpp"

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
  return summary;
}

json not_converged_summary(const Scene& scene, const std::string& message) {
  return not_converged_summary(scene, ConvergenceError(message));
}

}  // namespace fretwear
