// index.html as a report (engine/report.hpp): a section per stage that ran, a units column in engineering units, the
// closed forms where the scene has them, the warnings first and the resolved scene last.
#include <cmath>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/report.hpp"
#include "scenes.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

struct Run {
  Scene scene;
  RunResult result;
  json summary;
};

Run run(const Scene& scene) {
  Run r{scene, Simulation(scene).run(), {}};
  r.summary = make_summary(scene, r.result);
  return r;
}

std::string page(const Run& r, const std::vector<std::string>& plots = {}) {
  return report_html(r.scene, r.result, r.summary, r.scene.to_json(), plots, {"contact.csv"});
}

std::size_t at(const std::string& s, const std::string& what) {
  const std::size_t k = s.find(what);
  CAPTURE(what);
  REQUIRE(k != std::string::npos);
  return k;
}

}  // namespace

TEST_CASE("display units: engineering units by quantity, SI × scale") {
  struct Case {
    const char* path;
    const char* unit;
    double scale;
  };
  for (const Case& c : {Case{"contact.p_max", "MPa", 1e-6}, Case{"crack.K_II_max", "MPa·√m", 1e-6},
                        Case{"wear.asymptote.edge_intensity", "MPa·√m", 1e-6}, Case{"cycle.slip_max", "µm", 1e6},
                        Case{"wear.max_depth", "µm", 1e6}, Case{"crack.lengths", "µm", 1e6},
                        Case{"cycle.stick_zone", "mm", 1e3}, Case{"contact.extent", "mm", 1e3},
                        Case{"stress.swt_max_x", "mm", 1e3}, Case{"wear.worn_area", "µm²", 1e12},
                        Case{"cycle.Q_max", "N/mm", 1e-3}, Case{"contact.load", "N/mm", 1e-3},
                        Case{"materials.E_star", "GPa", 1e-9}, Case{"timings.total", "s", 1.0},
                        Case{"stress.swt_theta_deg", "°", 1.0}, Case{"wear.cycles", "cycles", 1.0},
                        Case{"cycle.Q_over_fP", "", 1.0}, Case{"grid.cells", "", 1.0}}) {
    CAPTURE(c.path);
    const DisplayUnit u = display_unit(c.path);
    CHECK(u.unit == c.unit);
    CHECK(u.scale == c.scale);
  }
}

TEST_CASE("the report has a section per stage that ran, each with a units column, warnings first, scene last") {
  const Run normal = run(test::normal_scene(test::cylinder(), 1e5, 256));
  const std::string n = page(normal);
  CHECK(n.find("<section id=\"normal\"") != std::string::npos);
  CHECK(n.find("<section id=\"tangential\"") == std::string::npos);  // a stage that did not run has no section
  CHECK(n.find("<th>unit</th>") != std::string::npos);

  const Run cycle = run(test::hertz_cycle(1e5, 0.5, 256));
  const std::string s = page(cycle);
  const std::size_t warnings = at(s, "<section id=\"warnings\""), first = at(s, "<section id=\"normal\""),
                    second = at(s, "<section id=\"tangential\""), scene = at(s, "<section id=\"scene\"");
  CHECK(warnings < first);
  CHECK(first < second);
  CHECK(second < scene);
  // The values in engineering units with the unit beside them: p_max in MPa, the stick zone in mm.
  const double p_max = cycle.summary["contact"]["p_max"].get<double>();
  CHECK(s.find(fmt::format("<td>contact.p_max</td><td>{:.4g}</td><td>MPa</td>", p_max * 1e-6)) != std::string::npos);
  CHECK(s.find("<td>cycle.stick_zone</td>") != std::string::npos);
  CHECK(s.find("<td>cycle.stick_zone</td><td>[") != std::string::npos);
  // Each stage's section holds its values and no other's.
  const std::string tangential = s.substr(second, scene - second);
  CHECK(tangential.find("<td>cycle.Q_max</td>") != std::string::npos);
  CHECK(tangential.find("<td>contact.p_max</td>") == std::string::npos);
  // The resolved scene, at the bottom, as JSON.
  CHECK(s.find("&quot;profile&quot;", scene) != std::string::npos);
}

TEST_CASE("the report's warnings come first, each with its code and message") {
  Run r = run(test::hertz_cycle(1e5, 0.5, 256));
  r.summary["warnings"] = json::array({{{"code", "contact_under_resolved"}, {"message", "too few cells <here>"}}});
  const std::string s = page(r);
  const std::size_t w = at(s, "<b>contact_under_resolved</b>: too few cells &lt;here&gt;");
  CHECK(w < at(s, "<section id=\"normal\""));
}

TEST_CASE("the report compares Hertz and the Cattaneo–Mindlin stick zone with their closed forms") {
  const int cells = 512;
  const Run r = run(test::hertz_cycle(1e5, 0.5, cells));
  const auto normal = closed_form_rows("normal", r.scene, r.result, r.summary);
  REQUIRE(normal.size() == 2);
  CHECK(normal[0].quantity == "contact half-width");
  CHECK(normal[0].unit == "mm");
  const auto tangential = closed_form_rows("tangential", r.scene, r.result, r.summary);
  REQUIRE(tangential.size() >= 2);
  CHECK(tangential[0].quantity == "stick-zone half-width c");
  // c/a = √(1 − Q/fP) = √0.5; the computed stick zone's ends are located to within a cell each.
  const double h = r.result.normal.grid.h(), a = normal[0].closed_form * 1e-3;
  CHECK(tangential[1].quantity == "c/a");
  CHECK(tangential[1].closed_form == doctest::Approx(std::sqrt(0.5)).epsilon(1e-12));
  CHECK(std::abs(tangential[1].computed - tangential[1].closed_form) < h / a);
  const std::string s = page(r);
  CHECK(s.find("Against the closed forms") != std::string::npos);
  CHECK(s.find("Cattaneo–Mindlin, c/a = √(1 − Q/fP)") != std::string::npos);
  // Under displacement control Q is not prescribed: no Cattaneo–Mindlin row.
  Scene d = test::hertz_cycle(1e5, 0.5, 256);
  d.Q_ratio.reset();
  d.control = LoadControl::displacement;
  d.delta = 0.3e-6;
  const Run dr = run(d);
  CHECK(closed_form_rows("tangential", dr.scene, dr.result, dr.summary).empty());
}

TEST_CASE("the report compares the worn area with the wear limit, and Hertz's limit with its closed form") {
  const Run r = run(test::hertz_wear(1e5, 0.5, 1e6, 512));
  const auto rows = closed_form_rows("wear", r.scene, r.result, r.summary);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].quantity == "worn area");
  CHECK(rows[0].unit == "µm²");
  CHECK(rows[0].closed_form == doctest::Approx(r.summary["wear"]["asymptote"]["worn_area"].get<double>() * 1e12));
  // PHYSICS.md's worn area at the limit for Hertz, c = a/√2, against a quadrature of its depth profile
  // w = [a² arccosh(x/c) − x √(x² − c²)]/(2R) over c < |x| < x_e (midpoint rule, 20000 intervals: 1e-6).
  const double a = r.result.normal.reference->half_width, c = a / std::sqrt(2.0);
  auto depth = [&](double x) { return (a * a * std::acosh(x / c) - x * std::sqrt(x * x - c * c)) / (2.0 * test::kHertzR); };
  double xe = c * 1.0001;  // the worn zone's end, where the depth returns to zero
  while (depth(xe * 1.0001) > 0.0) xe *= 1.0001;
  double W = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) W += 2.0 * depth(c + (k + 0.5) * (xe - c) / n) * (xe - c) / n;
  CHECK(rows[2].closed_form == doctest::Approx(W * 1e12).epsilon(1e-3));
  CHECK(page(r).find("<section id=\"wear\"") != std::string::npos);
}

TEST_CASE("the loop's closed form: Hertz's dissipated energy, exact at the onset of sliding, met by the cycle") {
  // At c → 0 the slip is g = f x²/(2R) and E = 8 f ∫_0^a p0 √(1 − x²/a²) f x²/(2R) dx = π f² p0 a³/(4R).
  const double f = 0.5, p0 = 5.9e8, a = 1.1e-4, R = 0.01, pi = std::acos(-1.0);
  CHECK(hertz_dissipated_energy(f, p0, a, 1e-9 * a, R) == doctest::Approx(pi * f * f * p0 * a * a * a / (4 * R)).epsilon(1e-6));
  CHECK(hertz_dissipated_energy(f, p0, a, a, R) == 0.0);  // no slip zone, nothing dissipated
  // The steady cycle's energy against it, without bulk tension: a row of the report.
  const Run r = run(test::hertz_cycle(1e5, 0.6, 1024));
  const auto rows = closed_form_rows("tangential", r.scene, r.result, r.summary);
  REQUIRE(rows.size() == 3);
  CHECK(rows[2].quantity == "energy dissipated per cycle (the loop's area)");
  CHECK(rows[2].unit == "J/m");
  // The slip zones' ends are located to within a cell, and E ∝ (a − c)-weighted slip: within a few cells' share.
  const double h = r.result.normal.grid.h(), c = std::sqrt(0.4) * r.result.normal.reference->half_width;
  const double a_minus_c = r.result.normal.reference->half_width - c;
  CHECK(std::abs(rows[2].computed - rows[2].closed_form) < 2.0 * h / a_minus_c * rows[2].closed_form);
}

TEST_CASE("the report puts each plot in the section of its stage, once") {
  const Run r = run(test::hertz_cycle(1e5, 0.5, 256));
  const auto sections =
      report_sections(r.summary, {"pressure.svg", "pressure.png", "traction.svg", "traction.png", "loop.svg",
                                  "loop.png", "swt_map.png", "mystery.png"});
  REQUIRE(sections.size() == 3);
  CHECK(sections[0].id == "normal");
  CHECK(sections[0].plots == std::vector<std::string>{"pressure.svg"});
  CHECK(sections[1].id == "tangential");
  CHECK(sections[1].plots == std::vector<std::string>{"traction.svg", "loop.svg"});
  CHECK(sections[2].id == "other");  // a plot of no stage that ran is still shown
  CHECK(sections[2].plots == std::vector<std::string>{"swt_map.png", "mystery.png"});
}
