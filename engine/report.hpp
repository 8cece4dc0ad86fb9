// index.html as a report of the run: the warnings first, then a section per stage that ran (a heading, its plots, a
// table of its summary values in engineering units, and the closed forms it can be held to: Hertz, the
// Cattaneo–Mindlin stick zone, the wear limit of paper 002), and the resolved scene last. summary.json stays SI; only
// the page converts. The page is laid out to be read at 1400 px without sideways scrolling (images and long values
// shrink or wrap to the column).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"

namespace fretwear {

// How a summary value is shown: SI value × scale, in `unit` ("" for a pure number, a count or a word).
struct DisplayUnit {
  std::string unit;
  double scale = 1.0;
};
// The unit of a summary value, from its dotted path in summary.json ("contact.p_max" → MPa, ×1e-6).
DisplayUnit display_unit(const std::string& path);

// One section of the report: a stage that ran.
struct ReportSection {
  std::string id;                    // "normal", "tangential", "wear", "stress", "fatigue", "crack", "life"
  std::string heading;
  std::vector<std::string> plots;    // files, each plot once (its SVG, or its PNG where there is none)
  std::vector<std::string> prefixes; // the summary paths its table shows
  std::vector<std::string> exclude;  // summary paths under those prefixes shown elsewhere
};

// The sections of a run, in the order the stages ran; each plot in `plots` lands in the section of its stage.
std::vector<ReportSection> report_sections(const nlohmann::json& summary, const std::vector<std::string>& plots);

// A closed-form comparison: quantity, fretwear's value and the closed form's, both already in `unit`.
struct ClosedFormRow {
  std::string quantity, unit;
  double computed = 0.0, closed_form = 0.0;
  std::string source;  // the closed form's name and where it comes from
};
// The closed forms section `id` can be compared with, where the scene has them (empty otherwise).
std::vector<ClosedFormRow> closed_form_rows(const std::string& id, const Scene& scene, const RunResult& result,
                                            const nlohmann::json& summary);

// The energy a Hertz contact dissipates per ±Q cycle, per unit length (J/m): the area of its fretting loop.
// E = 8 f ∫_c^a p g dx with p = p0 √(1 − x²/a²) and the slip g = (f/(2R)) [x √(x² − c²) − c² arccosh(x/c)]
// (PHYSICS.md, "Partial slip"; Mindlin and Deresiewicz 1953 in the plane). Quadrature in x = c + (a − c)(1 − cos t)/2.
double hertz_dissipated_energy(double f, double p0, double a, double c, double R);

// The whole page.
std::string report_html(const Scene& scene, const RunResult& result, const nlohmann::json& summary,
                        const nlohmann::json& resolved_scene, const std::vector<std::string>& plots,
                        const std::vector<std::string>& tables);

}  // namespace fretwear
