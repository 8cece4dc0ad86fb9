#include "engine/output.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>


namespace fretwear {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void flatten(const json& j, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& rows) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, rows);
  } else {
    rows.emplace_back(prefix, j.is_number_float() ? fmt::format("{:.6g}", j.get<double>()) : j.dump());
  }
}

std::string index_html(const Scene& scene, const json& summary, const std::vector<std::string>& plots,
                       const std::vector<std::string>& tables) {
  std::vector<std::pair<std::string, std::string>> rows;
  flatten(summary, "", rows);
  std::string s = fmt::format(R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>fretwear: {0}</title>
<style>body{{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}}
table{{border-collapse:collapse}}td{{border-bottom:1px solid #ddd;padding:2px 10px;font-family:monospace}}</style>
</head><body><h1>{0}</h1>
<p>fretwear {1}. Files: <a href="summary.json">summary.json</a>, <a href="scene.resolved.json">scene.resolved.json</a>)",
                              scene.name, summary.value("version", ""));
  for (const auto& t : tables) s += fmt::format(",\n<a href=\"{0}\">{0}</a>", t);
  s += ".</p>\n";
  // Each plot once: its SVG, or its PNG where there is no SVG (the colour maps).
  auto has = [&plots](const std::string& name) { return std::find(plots.begin(), plots.end(), name) != plots.end(); };
  for (const auto& plot : plots) {
    const bool svg = plot.ends_with(".svg");
    const bool png_alone = plot.ends_with(".png") && !has(plot.substr(0, plot.size() - 4) + ".svg");
    if (svg || png_alone) s += fmt::format("<p><img src=\"{0}\" alt=\"{0}\" width=\"900\"></p>\n", plot);
  }
  s += "<h2>Summary</h2><table>\n";
  for (const auto& [k, v] : rows) s += fmt::format("<tr><td>{}</td><td>{}</td></tr>\n", k, v);
  s += "</table></body></html>\n";
  return s;
}

}  // namespace

json write_results(const Scene& scene, const RunResult& result, OutputFolder& out) {
  json summary = make_summary(scene, result);
  Scene resolved = scene;  // the window as it was used, so that the resolved scene reproduces the run exactly
  resolved.window = std::pair(result.normal.grid.x_min, result.normal.grid.x_max);
  if (result.cycle) resolved.reference_depth = result.cycle->reference_depth;  // the datum as it was used
  out.write_json("scene.resolved.json", resolved.to_json());
  Written written;
  // The coupled pressure is drawn for dissimilar bodies (a history's p_top, at β = 0, is the stages' only).
  const bool coupled = result.cycle && result.cycle->plan.dissimilar();
  write_normal(scene, result.normal, coupled ? result.cycle->p_top : std::vector<double>{}, out, written);
  for (const StageOutputs& stage : stage_outputs())
    if (stage.ran(result)) stage.write(scene, result, out, written);
  summary["plots"] = written.plots;
  out.write_json("summary.json", summary);
  out.write("index.html", index_html(scene, summary, written.plots, written.tables));
  return summary;
}

}  // namespace fretwear
