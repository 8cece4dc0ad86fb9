#include "engine/report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "contact/closed_form.hpp"

namespace fretwear {
namespace {

using nlohmann::json;

bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }
bool ends_with(const std::string& s, const std::string& p) {
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}
bool one_of(const std::string& s, std::initializer_list<const char*> names) {
  return std::any_of(names.begin(), names.end(), [&s](const char* n) { return s == n; });
}

std::string escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

const DisplayUnit kMm{"mm", 1e3}, kUm{"µm", 1e6}, kMPa{"MPa", 1e-6}, kGPa{"GPa", 1e-9}, kSif{"MPa·√m", 1e-6},
    kForce{"N/mm", 1e-3}, kNone{"", 1.0};

// A number as the page shows it: 4 significant digits, integers as they are, exponents as 1e7 and 2.5e-5.
std::string shown(double v) {
  if (std::isinf(v)) return v > 0 ? "∞" : "−∞";
  if (v == std::round(v) && std::abs(v) < 1e7) return fmt::format("{:.0f}", v);
  std::string s = fmt::format("{:.4g}", v);
  const std::size_t e = s.find('e');
  if (e != std::string::npos) s = s.substr(0, e + 1) + std::to_string(std::stoi(s.substr(e + 1)));
  return s;
}

// A summary value in its display unit: numbers scaled, arrays of them element by element, words as they are.
std::string value_text(const json& v, double scale) {
  if (v.is_null()) return "—";
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_number_integer() || v.is_number_unsigned()) return fmt::format("{}", v.get<long long>());
  if (v.is_number()) return shown(v.get<double>() * scale);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + value_text(v[i], scale);
    return s + "]";
  }
  return v.dump();
}

void flatten(const json& j, const std::string& prefix, std::vector<std::pair<std::string, const json*>>& rows) {
  if (j.is_object() && !j.empty()) {
    for (const auto& item : j.items()) flatten(item.value(), prefix.empty() ? item.key() : prefix + "." + item.key(), rows);
  } else if (j.is_array() && !j.empty() && j.front().is_object()) {  // e.g. wear.blocks: one row per element's value
    for (std::size_t i = 0; i < j.size(); ++i) flatten(j[i], fmt::format("{}[{}]", prefix, i), rows);
  } else {
    rows.emplace_back(prefix, &j);
  }
}

std::string table_html(const json& summary, const ReportSection& section) {
  std::vector<std::pair<std::string, const json*>> all, rows;
  flatten(summary, "", all);
  for (const auto& row : all) {
    const std::string& path = row.first;  // a plain name: lambdas may not capture structured bindings (clang 14)
    auto under = [&path](const std::string& p) { return path == p || starts_with(path, p + "."); };
    const bool in = std::any_of(section.prefixes.begin(), section.prefixes.end(), under);
    const bool out = std::any_of(section.exclude.begin(), section.exclude.end(), under);
    if (in && !out) rows.push_back(row);
  }
  if (rows.empty()) return "";
  std::string s = "<table class=\"values\"><thead><tr><th>quantity</th><th>value</th><th>unit</th></tr></thead>"
                  "<tbody>\n";
  for (const auto& [path, v] : rows) {
    const DisplayUnit u = display_unit(path);
    s += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td></tr>\n", escape(path), escape(value_text(*v, u.scale)),
                     escape(u.unit));
  }
  return s + "</tbody></table>\n";
}

std::string closed_form_html(const std::vector<ClosedFormRow>& rows) {
  if (rows.empty()) return "";
  std::string s = "<h3>Against the closed forms</h3>\n<table class=\"values\"><thead><tr><th>quantity</th>"
                  "<th>fretwear</th><th>closed form</th><th>unit</th><th>difference</th><th>closed form of</th></tr>"
                  "</thead><tbody>\n";
  for (const auto& r : rows) {
    const double d = r.closed_form != 0.0 ? (r.computed - r.closed_form) / std::abs(r.closed_form) : 0.0;
    s += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                     escape(r.quantity), shown(r.computed), shown(r.closed_form), escape(r.unit),
                     r.closed_form != 0.0 ? fmt::format("{:+.2e}", d) : "—", escape(r.source));
  }
  return s + "</tbody></table>\n";
}

// Which stage drew a plot, from its file name (the stages' write functions name them).
std::string plot_stage(const std::string& plot) {
  static const std::pair<const char*, const char*> owners[] = {
      {"pressure", "normal"},  {"traction", "tangential"}, {"slip", "tangential"}, {"loop", "tangential"},
      {"wear_", "wear"},       {"stress_", "stress"},       {"swt_", "fatigue"},    {"ruiz", "fatigue"},
      {"sif_", "crack"},       {"crack_growth", "life"},    {"life_", "life"}};
  for (const auto& [prefix, stage] : owners)
    if (starts_with(plot, prefix)) return stage;
  return "other";
}

// The worn area at paper 002's limit for Hertz under force control, no bulk stress (PHYSICS.md, "Wear"):
// W = [a²(x_e arccosh(x_e/c) − √(x_e² − c²)) − (x_e² − c²)^{3/2}/3]/R, with a² arccosh(x_e/c) = x_e √(x_e² − c²).
double hertz_worn_area_limit(double a, double c, double R) {
  auto residual = [a, c](double x) { return a * a * std::acosh(x / c) - x * std::sqrt(x * x - c * c); };
  double lo = c * (1.0 + 1e-12), hi = 2.0 * a;  // residual > 0 just past c, < 0 far out
  while (residual(hi) > 0.0) hi *= 2.0;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) (residual(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double xe = 0.5 * (lo + hi), r = std::sqrt(xe * xe - c * c);
  return (a * a * (xe * std::acosh(xe / c) - r) - r * r * r / 3.0) / R;
}

}  // namespace

double hertz_dissipated_energy(double f, double p0, double a, double c, double R) {
  constexpr int kPoints = 4000;  // the integrand is smooth in t: the sum converges far below the solver's accuracy
  const double pi = std::acos(-1.0);
  double sum = 0.0;
  for (int k = 0; k < kPoints; ++k) {
    const double t = (k + 0.5) * pi / kPoints, x = c + 0.5 * (a - c) * (1.0 - std::cos(t));
    const double dx = 0.5 * (a - c) * std::sin(t) * pi / kPoints;
    const double p = p0 * std::sqrt(std::max(0.0, 1.0 - x * x / (a * a)));
    const double g = f / (2.0 * R) * (x * std::sqrt(std::max(0.0, x * x - c * c)) - c * c * std::acosh(std::max(1.0, x / c)));
    sum += p * g * dx;
  }
  return 8.0 * f * sum;
}

namespace {

const char* kStyle = R"(<style>
body{font-family:sans-serif;max-width:1200px;margin:1.5em auto;padding:0 1em;color:#222;line-height:1.4}
h1{margin-bottom:0.2em} h2{border-bottom:2px solid #ccc;padding-bottom:0.2em;margin-top:2em}
img{max-width:100%;height:auto;display:block;margin:0.8em 0}
table.values{border-collapse:collapse;width:100%;table-layout:auto;margin:0.5em 0}
table.values th{text-align:left;border-bottom:2px solid #999;padding:2px 10px}
table.values td{border-bottom:1px solid #ddd;padding:2px 10px;font-family:monospace;overflow-wrap:anywhere}
.warnings{background:#fff4e0;border:1px solid #e0a040;padding:0.5em 1em}
.nowarnings{color:#3a7d3a}
pre{white-space:pre-wrap;overflow-wrap:anywhere;background:#f6f6f6;padding:1em;font-size:90%}
nav a{margin-right:1em}
</style>
)";

}  // namespace

DisplayUnit display_unit(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::string leaf = dot == std::string::npos ? path : path.substr(dot + 1);
  const std::string key = leaf.substr(0, leaf.find('['));
  if (starts_with(path, "timings.") || one_of(key, {"seconds", "fatigue_seconds"})) return {"s", 1.0};
  if (ends_with(key, "_deg")) return {"°", 1.0};
  if (starts_with(key, "K_")) return kSif;
  if (one_of(key, {"edge_intensity", "edge_intensities"})) return kSif;  // p √(2π r) at a square-root edge
  if (one_of(key, {"load", "Q_max", "Q_max_initial", "Q_max_final", "Q_max_end"})) return kForce;
  if (key == "E_star") return kGPa;
  if (key == "A") return {"1/GPa", 1e9};
  if (one_of(key, {"coefficient", "coefficient_pad", "coefficient_specimen", "rate_coefficient"})) return {"1/Pa", 1.0};
  if (one_of(key, {"p_max", "p_max_top", "p_max_bottom", "bulk_stress", "von_mises_max", "surface_sxx_trailing_peak",
                   "swt_sigma_n_max"}))
    return kMPa;
  if (one_of(key, {"swt_max", "swt"})) return {"MPa (MJ/m³)", 1e-6};
  if (key == "ruiz_F1_max") return {"J/m²", 1.0};
  if (key == "ruiz_F2_max") return {"MPa·J/m²", 1e-6};
  if (key == "dissipated_energy") return {"J/m", 1.0};
  if (one_of(key, {"worn_area", "worn_area_end"})) return {"µm²", 1e12};
  // Small lengths: slips, displacements, wear depths, crack lengths, the cell size.
  if (one_of(key, {"slip_max", "delta_max", "delta", "sliding_amplitude", "max_depth", "max_depth_end", "h",
                   "lengths", "a_initial", "a_final", "final_length", "critical_distance"}))
    return kUm;
  // Positions and widths along the surface, and depths below it.
  if (one_of(key, {"extent", "zones", "half_width", "load_size_half_width", "x_p_max", "stick_zone", "stick_zones",
                   "stick_zone_unloaded", "stick_zone_initial", "stick_zone_final", "contact_final", "touching_final",
                   "reference_depth", "reference_x", "window", "x", "y", "depth", "x_max_depth",
                   "von_mises_max_at"}) ||
      ends_with(key, "_x") || ends_with(key, "_y"))
    return kMm;
  if (one_of(key, {"cycles", "cycles_target", "cycles_reached", "cycles_max", "total_cycles", "state_cycles",
                   "cycles_start", "cycles_end", "resumed_from", "explicit_stability_limit", "explicit_step_cap",
                   "explicit_max_step", "at_cycles"}))
    return {"cycles", 1.0};
  return kNone;  // ratios, counts, words, and the solvers' own measures (residuals, relative errors)
}

std::vector<ReportSection> report_sections(const json& summary, const std::vector<std::string>& plots) {
  struct Kind {
    const char* id;
    const char* heading;
    std::vector<std::string> prefixes, exclude;
  };
  static const std::vector<Kind> kinds = {
      {"normal", "Normal contact", {"contact", "materials", "grid", "solver"}, {}},
      {"tangential", "Load cycle (partial slip)", {"cycle"}, {}},
      {"wear", "Wear", {"wear"}, {}},
      {"stress", "Stresses under the surface", {"stress"},
       {"stress.swt_max", "stress.swt_max_singular", "stress.swt_max_x", "stress.swt_max_y", "stress.swt_delta_eps_n",
        "stress.swt_sigma_n_max", "stress.swt_theta_deg", "stress.ruiz_F1_max", "stress.ruiz_F1_max_x",
        "stress.ruiz_F2_max", "stress.ruiz_F2_max_x", "stress.fatigue_seconds"}},
      {"fatigue", "Fatigue measures (Smith–Watson–Topper, Ruiz)",
       {"stress.swt_max", "stress.swt_max_singular", "stress.swt_max_x", "stress.swt_max_y", "stress.swt_delta_eps_n",
        "stress.swt_sigma_n_max", "stress.swt_theta_deg", "stress.ruiz_F1_max", "stress.ruiz_F1_max_x",
        "stress.ruiz_F2_max", "stress.ruiz_F2_max_x", "stress.fatigue_seconds"},
       {}},
      {"crack", "Crack (stress intensity factors)", {"crack"}, {}},
      {"life", "Fatigue life", {"life"}, {}},
  };
  // Each plot once: its SVG, or its PNG where there is no SVG (the colour maps).
  auto has = [&plots](const std::string& name) { return std::find(plots.begin(), plots.end(), name) != plots.end(); };
  std::vector<std::string> shown_plots;
  for (const auto& p : plots)
    if (ends_with(p, ".svg") || (ends_with(p, ".png") && !has(p.substr(0, p.size() - 4) + ".svg")))
      shown_plots.push_back(p);
  const json& run = summary.value("effects_run", json::array());
  const bool fatigue = summary.contains("stress") && summary["stress"].contains("swt_max");
  std::vector<ReportSection> out;
  for (const Kind& k : kinds) {
    const std::string id = k.id;
    const bool ran = id == "fatigue" ? fatigue : std::find(run.begin(), run.end(), json(id)) != run.end();
    if (!ran) continue;
    ReportSection s{id, k.heading, {}, k.prefixes, k.exclude};
    for (const auto& p : shown_plots)
      if (plot_stage(p) == id) s.plots.push_back(p);
    out.push_back(std::move(s));
  }
  ReportSection other{"other", "Other plots", {}, {}, {}};
  for (const auto& p : shown_plots) {
    const std::string stage = plot_stage(p);
    const bool placed = std::any_of(out.begin(), out.end(), [&stage](const ReportSection& s) { return s.id == stage; });
    if (!placed) other.plots.push_back(p);
  }
  if (!other.plots.empty()) out.push_back(std::move(other));
  return out;
}

std::vector<ClosedFormRow> closed_form_rows(const std::string& id, const Scene& scene, const RunResult& result,
                                            const json& summary) {
  std::vector<ClosedFormRow> rows;
  const std::optional<Reference>& ref = result.normal.reference;
  if (id == "normal" && ref) {
    const json& c = summary["contact"];
    const std::string source = ref->kind == "hertz"           ? "Hertz cylinder, a = √(4PR/(πE*)), p0 = 2P/(πa)"
                               : ref->kind == "rounded_punch" ? "rounded punch, paper 000 eqs 3–4"
                                                              : "sharp flat punch, p = P/(π√(b² − x²))";
    const double half = 0.5 * (c["extent"][1].get<double>() - c["extent"][0].get<double>());
    rows.push_back({"contact half-width", "mm", half * 1e3, ref->half_width * 1e3, source});
    if (ref->kind != "flat_punch")  // the sharp punch's peak is singular: its edge cells are a grid measure
      rows.push_back({"peak pressure", "MPa", result.normal.p_max * 1e-6, ref->p_max * 1e-6, source});
  }
  const CycleStage* cycle = result.cycle ? &*result.cycle : nullptr;
  const bool plain_force = cycle && scene.control == LoadControl::force && scene.history.empty() &&
                           !cycle->plan.dissimilar() && scene.friction;
  if (id == "tangential" && ref && plain_force && cycle->result.regime == Regime::partial_slip &&
      cycle->result.stick_zone) {
    const double f = cycle->f, ratio = cycle->Q_max / (f * scene.P);
    const double A = summary["materials"]["A"].get<double>();
    const auto [l, r] = *cycle->result.stick_zone;
    const double c = 0.5 * (r - l), centre = 0.5 * (l + r);
    if (ref->kind == "hertz") {
      const auto h = closed_form::hertz(scene.P, A, scene.profile.R);
      const auto z = closed_form::hertz_stick(h, ratio, f, cycle->bulk_stress);
      const std::string source = "Cattaneo–Mindlin, c/a = √(1 − Q/fP)";
      rows.push_back({"stick-zone half-width c", "mm", c * 1e3, z.c * 1e3, source});
      rows.push_back({"c/a", "", c / h.a, std::sqrt(1.0 - ratio), source});
      if (cycle->bulk_stress != 0.0)
        rows.push_back({"stick-zone centre e (from the contact's centre)", "mm", (centre - ref->centre) * 1e3,
                        z.centre * 1e3, "Nowell and Hills 1987, e/a = σ/(4 f p0)"});
      else if (!cycle->result.slip_range.empty())  // the fretting loop's area
        rows.push_back({"energy dissipated per cycle (the loop's area)", "J/m", cycle->result.dissipated_energy,
                        hertz_dissipated_energy(f, h.p0, h.a, z.c, scene.profile.R),
                        "Hertz, E = 8 f ∫ p g dx over the slip zones"});
    } else if (ref->kind == "rounded_punch" && cycle->bulk_stress == 0.0) {
      const double cf =
          closed_form::rounded_punch_stick(closed_form::rounded_punch(scene.P, A, scene.profile.a, scene.profile.R),
                                           ratio);
      rows.push_back({"stick-zone half-width c", "mm", c * 1e3, cf * 1e3, "rounded punch, paper 000 eq 9"});
    }
  }
  if (id == "wear" && result.wear && summary["wear"].contains("asymptote") && !summary["wear"]["asymptote"].is_null()) {
    const json& w = summary["wear"];
    const std::string limit = "the wear limit (paper 002: complete contact over the initial stick zone)";
    rows.push_back({"worn area", "µm²", w["worn_area"].get<double>() * 1e12,
                    w["asymptote"]["worn_area"].get<double>() * 1e12, limit});
    rows.push_back({"largest wear depth", "µm", w["max_depth"].get<double>() * 1e6,
                    w["asymptote"]["max_depth"].get<double>() * 1e6, limit});
    if (ref && ref->kind == "hertz" && plain_force && cycle->bulk_stress == 0.0 && scene.blocks.empty()) {
      const double f = cycle->f, ratio = cycle->Q_max / (f * scene.P);
      const auto h = closed_form::hertz(scene.P, summary["materials"]["A"].get<double>(), scene.profile.R);
      const double W = hertz_worn_area_limit(h.a, h.a * std::sqrt(1.0 - ratio), scene.profile.R);
      rows.push_back({"worn area at the limit (computed limit against Hertz's)", "µm²",
                      w["asymptote"]["worn_area"].get<double>() * 1e12, W * 1e12,
                      "Hertz at the wear limit (PHYSICS.md, \"Wear\")"});
    }
  }
  return rows;
}

std::string report_html(const Scene& scene, const RunResult& result, const json& summary, const json& resolved_scene,
                        const std::vector<std::string>& plots, const std::vector<std::string>& tables) {
  std::string s = fmt::format("<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                              "<meta name=\"viewport\" content=\"width=device-width\"><title>fretwear: {0}</title>\n{1}"
                              "</head><body>\n<h1>{0}</h1>\n",
                              escape(scene.name), kStyle);
  const std::vector<ReportSection> sections = report_sections(summary, plots);
  // What ran, the files, and a line of contents.
  std::string effects;
  for (const auto& e : summary.value("effects_run", json::array())) effects += (effects.empty() ? "" : ", ") + e.get<std::string>();
  s += fmt::format("<p>fretwear {}, {}: {} in {:.3g} s. Values below in engineering units; summary.json holds them in "
                   "SI.</p>\n<p>Files: <a href=\"summary.json\">summary.json</a>, "
                   "<a href=\"scene.resolved.json\">scene.resolved.json</a>",
                   escape(summary.value("version", "")), escape(summary.value("status", "")), escape(effects),
                   summary.contains("timings") ? summary["timings"].value("total", 0.0) : 0.0);
  for (const auto& t : tables) s += fmt::format(", <a href=\"{0}\">{0}</a>", escape(t));
  s += ".</p>\n<nav>";
  s += "<a href=\"#warnings\">Warnings</a>";
  for (const auto& sec : sections) s += fmt::format("<a href=\"#{}\">{}</a>", sec.id, escape(sec.heading));
  s += "<a href=\"#scene\">Resolved scene</a></nav>\n";
  // The warnings, first.
  const json& warnings = summary.value("warnings", json::array());
  s += "<section id=\"warnings\"><h2>Warnings</h2>\n";
  if (warnings.empty()) {
    s += "<p class=\"nowarnings\">None.</p>\n";
  } else {
    s += "<div class=\"warnings\"><ul>\n";
    for (const auto& w : warnings)
      s += fmt::format("<li><b>{}</b>: {}</li>\n", escape(w.value("code", "")), escape(w.value("message", "")));
    s += "</ul></div>\n";
  }
  s += "</section>\n";
  for (const auto& sec : sections) {
    s += fmt::format("<section id=\"{}\" class=\"stage\"><h2>{}</h2>\n", sec.id, escape(sec.heading));
    for (const auto& p : sec.plots) s += fmt::format("<img src=\"{0}\" alt=\"{0}\">\n", escape(p));
    s += closed_form_html(closed_form_rows(sec.id, scene, result, summary));
    const std::string table = table_html(summary, sec);
    if (!table.empty()) s += "<h3>Summary values</h3>\n" + table;
    s += "</section>\n";
  }
  s += "<section id=\"run\"><h2>Run</h2>\n";
  s += table_html(summary, ReportSection{"run", "Run", {}, {"scene", "version", "status", "effects_run",
                                                             "effects_implied", "timings"}, {}});
  s += "</section>\n<section id=\"scene\"><h2>Resolved scene</h2>\n<p>As run (the window and the datum as used); "
       "<a href=\"scene.resolved.json\">scene.resolved.json</a> reproduces the run.</p>\n<pre>" +
       escape(resolved_scene.dump(2)) + "</pre></section>\n</body></html>\n";
  return s;
}

}  // namespace fretwear
