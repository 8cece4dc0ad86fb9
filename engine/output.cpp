#include "engine/output.hpp"

#include "engine/report.hpp"

namespace fretwear {
using nlohmann::json;

json write_results(const Scene& scene, const RunResult& result, OutputFolder& out) {
  json summary = make_summary(scene, result);
  Scene resolved = scene;  // the window as it was used, so that the resolved scene reproduces the run exactly
  resolved.window = std::pair(result.normal.grid.x_min, result.normal.grid.x_max);
  if (result.cycle) resolved.reference_depth = result.cycle->reference_depth;  // the datum as it was used
  const json resolved_json = resolved.to_json();
  out.write_json("scene.resolved.json", resolved_json);
  Written written;
  // The coupled pressure is drawn for dissimilar bodies (a history's p_top, at β = 0, is the stages' only).
  const bool coupled = result.cycle && result.cycle->plan.dissimilar();
  write_normal(scene, result.normal, coupled ? result.cycle->p_top : std::vector<double>{}, out, written);
  for (const StageOutputs& stage : stage_outputs())
    if (stage.ran(result)) stage.write(scene, result, out, written);
  summary["plots"] = written.plots;
  out.write_json("summary.json", summary);
  out.write("index.html", report_html(scene, result, summary, resolved_json, written.plots, written.tables));
  return summary;
}

}  // namespace fretwear
