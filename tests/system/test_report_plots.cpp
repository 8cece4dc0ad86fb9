// The run's report and plots as a user reads them: index.html with a section per stage, and the gnuplot scripts
// written beside the PNGs carrying the labels and palettes of docs/OUTPUTS.md. The scripts are written whether or
// not gnuplot is installed, so their text is tested here; the page's width at 1400 px is measured in headless
// Chromium where CMake found it.
#include <filesystem>
#include <regex>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/plot.hpp"
#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// Hertz worn in partial slip under a bulk tension, then the stresses, the fatigue measures and a crack: every
// plotting stage but life, on a coarse grid.
const char* kWorn = R"({"name": "report", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
  "load": {"P": 1e5, "Q": {"ratio": 0.5}, "bulk_stress": {"amplitude": 50e6}}, "grid": {"cells": 256},
  "effects": {"wear": {"k": 1e-12, "cycles": 1e5, "record": 3}, "stress": {},
              "crack": {"at": "trailing_edge", "lengths": [5e-6, 1e-5, 2e-5]}}})";

// The life stage's map under displacement control (no Cattaneo–Mindlin there: Q is not prescribed).
const char* kLife = R"({"name": "life", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.8,
  "load": {"P": 1e5, "control": "displacement", "delta": 1e-6, "bulk_stress": {"amplitude": 2e8}},
  "grid": {"cells": 256, "window": [-6e-4, 6e-4]},
  "effects": {"tangential": {}, "life": {
    "initiation": {"sigma_f": 1.817e9, "b": -0.08, "eps_f": 0.35, "c": -0.52, "critical_distance": 2e-5},
    "growth": {"C": 5e-30, "m": 3.0, "dK_th": 2e6, "a_final": 1e-3}}}})";

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t k = s.find(what); k != std::string::npos; k = s.find(what, k + what.size())) ++n;
  return n;
}

struct Results {
  Scratch scratch;
  fs::path dir;
  json summary;
  std::string file(const std::string& name) const { return read_file(dir / name); }
};

void run(Results& r, const std::string& name, const char* scene) {
  r.scratch.write(name + ".json", scene);
  const Outcome o = r.scratch.fretwear({"run", name + ".json", "-q"});
  REQUIRE_MESSAGE(o.exited(kDone), o.describe());
  r.dir = r.scratch.work / "output" / name;
  r.summary = json::parse(r.file("summary.json"));
}

// The colour-map settings every map shares (engine/plot.hpp): viridis, cropped to the data.
void check_colour_map(const std::string& script, const std::string& name) {
  CAPTURE(name);
  CHECK(script.find(fretwear::viridis_palette()) != std::string::npos);
  CHECK(script.find("set palette defined (0 '#440154'") != std::string::npos);
  CHECK(script.find("set autoscale xfix\nset autoscale yfix\n") != std::string::npos);
  CHECK(script.find("rgbformulae") == std::string::npos);  // the rainbow (jet-like) map it replaced
  CHECK(script.find("cubehelix") == std::string::npos);
  CHECK(script.find("set cblabel '") != std::string::npos);
}

}  // namespace

TEST_CASE("the report has a section per stage that ran, with a units column and engineering units") {
  Results r;
  run(r, "report", kWorn);
  const std::string html = r.file("index.html");
  for (const char* id : {"warnings", "normal", "tangential", "wear", "stress", "fatigue", "crack", "scene"})
    CHECK_MESSAGE(html.find(std::string("<section id=\"") + id + "\"") != std::string::npos, id);
  CHECK(html.find("<section id=\"life\"") == std::string::npos);
  CHECK(count(html, "<th>unit</th>") >= 7);  // every stage's table, and the run's
  for (const char* unit : {"<td>mm</td>", "<td>µm</td>", "<td>MPa</td>", "<td>MPa·√m</td>", "<td>µm²</td>"})
    CHECK_MESSAGE(html.find(unit) != std::string::npos, unit);
  CHECK(html.find("Cattaneo–Mindlin") != std::string::npos);
  CHECK(html.find("the wear limit") != std::string::npos);
  // summary.json stays SI.
  CHECK(r.summary["contact"]["p_max"].get<double>() > 1e8);
}

TEST_CASE("the plot scripts carry K_{II}, viridis maps cropped to the data, labelled records and cycle counts") {
  Results r;
  run(r, "report", kWorn);
  // Crack: K_{II} as enhanced text, and every record's curve in the key by its cycle count.
  const std::string crack = r.file("crack.gp");
  CHECK(crack.find("set ylabel 'K_{I} (MPa·√m)'") != std::string::npos);
  CHECK(crack.find("set ylabel 'K_{II} (MPa·√m)'") != std::string::npos);
  CHECK(crack.find("'K_II") == std::string::npos);
  const std::size_t records = r.summary["wear"]["records"].get<std::size_t>();
  REQUIRE(records == 4);  // the unworn state and the 3 asked for
  CHECK(count(crack, "title 'N = ") == 2 * records);  // one per record in each of the K_{I} and K_{II} plots
  CHECK(count(crack, "title 'top'") == 2);           // the phases said once per plot
  CHECK(count(crack, "title 'bottom'") == 2);
  // The maps: viridis, cropped, titled with the cycle count of the state they show.
  const std::string stress = r.file("stress.gp"), fatigue = r.file("fatigue.gp");
  check_colour_map(stress, "stress.gp");
  check_colour_map(fatigue, "fatigue.gp");
  const std::string cycles = fretwear::cycles_text(r.summary["stress"]["cycles"].get<double>());
  CHECK(cycles == "N = 1e5");
  CHECK(count(stress, "set title \"") == 2);
  CHECK(count(stress, cycles + "\" noenhanced") == 2);
  CHECK(fatigue.find("over the cycle, " + cycles + "\" noenhanced") != std::string::npos);
  // The worn area on log–log axes: the cycle axis is logarithmic, and so is the area's.
  const std::string wear = r.file("wear.gp");
  const std::size_t area = wear.find("worn area against cycles");
  REQUIRE(area != std::string::npos);
  CHECK(wear.rfind("set logscale x", area) != std::string::npos);
  CHECK(wear.find("unset logscale x", wear.rfind("set logscale x", area)) == std::string::npos);
  CHECK(wear.find("set logscale y\n", area) != std::string::npos);
  // The traction with Cattaneo–Mindlin's over it (Hertz under force control).
  const std::string cycle = r.file("cycle.gp");
  CHECK(cycle.find("cm_q(x) with lines") != std::string::npos);
  CHECK(cycle.find("title 'Cattaneo–Mindlin, top (c/a = 0.7071)'") != std::string::npos);
  // The stick zone against cycles, with the unworn closed form (c/a = 0.7071 of the Hertz half-width) as its lines.
  const std::size_t stick = wear.find("stick zone and contact extent against cycles");
  REQUIRE(stick != std::string::npos);
  const std::size_t cm = wear.find("title 'Cattaneo–Mindlin, unworn'", stick);
  REQUIRE(cm != std::string::npos);
  const double a = r.summary["contact"]["closed_form"]["half_width"].get<double>();
  const double left = std::stod(wear.substr(wear.rfind(", ", cm) + 2, 40));
  const std::size_t next = wear.find("', ", cm) + 3;  // past the title's closing quote
  const double right = std::stod(wear.substr(next, 40));
  CHECK(wear.find("notitle", next) < wear.find(", ", next));  // the right end, the legend's second line
  CHECK(0.5 * (right - left) == doctest::Approx(0.7071 * a * 1e3).epsilon(2e-4));  // c/a = √(1 − Q/fP)
}

TEST_CASE("the life map is viridis and cropped, and displacement control draws no Cattaneo–Mindlin traction") {
  Results r;
  run(r, "life", kLife);
  const std::string life = r.file("life.gp");
  check_colour_map(life, "life.gp");
  CHECK(r.file("cycle.gp").find("Cattaneo–Mindlin") == std::string::npos);
  const std::string html = r.file("index.html");
  CHECK(html.find("<section id=\"life\"") != std::string::npos);
  CHECK(html.find("Cattaneo–Mindlin") == std::string::npos);
}

TEST_CASE("the fretting loop carries its closed form where PHYSICS.md has one (its area, Hertz)") {
  Results r;
  run(r, "loop", R"({"name": "loop", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.6}},
    "grid": {"cells": 256}, "effects": {"tangential": {"route": "incremental", "increments": 40}}})");
  const std::string loop = r.file("loop.gp");
  CHECK(loop.find("(closed form, Hertz: ") != std::string::npos);
  CHECK(r.file("index.html").find("energy dissipated per cycle (the loop's area)") != std::string::npos);
}

#ifdef FRETWEAR_CHROMIUM
// The report read at 1400 px: headless Chromium lays the page out in a 1400 px window and a script writes its
// scroll width into the DOM, which --dump-dom returns; a page wider than its window scrolls sideways. The page is
// screenshot too, as docs/OUTPUTS.md tells a reader to look at it.
TEST_CASE("the report fits 1400 px without sideways scrolling, in headless Chromium") {
  constexpr int kWidth = 1400;
  Results r;
  run(r, "report", kWorn);
  std::string page = r.file("index.html");
  const std::string probe = "<script>function probe(){document.body.setAttribute('data-scroll-width',"
                            "document.documentElement.scrollWidth)}probe();window.addEventListener('load',probe)"
                            "</script>";
  page.insert(page.rfind("</body>"), probe);
  write_file(r.dir / "width_probe.html", page);
  const fs::path profile = r.scratch.root / "chromium-profile";
  // What Chromium prints on stdout (each word reaches it as it is, never through a shell).
  auto chromium = [&](const std::string& mode, const std::string& file) {
    const fretwear::test::Command command{
        {"timeout", "60", FRETWEAR_CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--user-data-dir=" + profile.string(), fmt::format("--window-size={},2000", kWidth), mode,
         "file://" + (r.dir / file).string()}};
    return fretwear::test::run_program(command, r.scratch.work, {}, 120.0).out;
  };
  const std::string dom = chromium("--dump-dom", "width_probe.html");
  std::smatch m;
  REQUIRE_MESSAGE(std::regex_search(dom, m, std::regex("data-scroll-width=\"([0-9]+)\"")), dom.substr(0, 400));
  CHECK(std::stoi(m[1]) <= kWidth);
  chromium("--screenshot=" + (r.dir / "index_1400.png").string(), "index.html");
  CHECK(fs::exists(r.dir / "index_1400.png"));
}
#endif
