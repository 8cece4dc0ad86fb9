// The fatigue measures of a scene, end to end (engine/fatigue_stage.hpp): a Hertz cycle in partial slip with
// effects.stress reaches summary.json with Smith–Watson–Topper's maximum at the trailing edge on the surface
// and Ruiz's F2 peaking just inside it, and writes fatigue.csv and ruiz.csv.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/fatigue_stage.hpp"
#include "engine/output.hpp"
#include "engine/simulation.hpp"
#include "support.hpp"

using namespace fretwear;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {
// PHYSICS.md's public Hertz case at P = 100 N/mm, Q/fP = 0.5: a = 0.107641 mm, c/a = 0.707107.
constexpr double kA = 0.107641e-3;
constexpr double kStickRatio = 0.7071068;

// An angle in radians as degrees in (−90, 90]: 0 when two planes coincide.
double degrees_mod_180(double rad) {
  double d = std::fmod(rad * 180.0 / 3.141592653589793, 180.0);
  if (d > 90.0) d -= 180.0;
  if (d <= -90.0) d += 180.0;
  return d;
}

json hertz_scene(double bulk_stress, bool plots = false) {
  return {{"name", "fatigue_scene"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}, {"bulk_stress", {{"amplitude", bulk_stress}}}}},
          {"grid", {{"cells", 1024}}},
          {"effects", {{"tangential", json::object()}, {"stress", {{"nx", 121}, {"ny", 41}}}}},
          {"output", {{"dir", "output/fatigue_scene"}, {"plots", plots}}}};
}
}  // namespace

TEST_CASE("fatigue scene, Hertz partial slip: the keys, SWT at the contact's edges, Ruiz F2 as the closed form") {
  const Scene scene = parse_scene(hertz_scene(0.0));
  const RunResult run = Simulation(scene).run();
  const json s = make_summary(scene, run);
  const json& st = s["stress"];
  for (const char* key : {"swt_max", "swt_max_x", "swt_max_y", "swt_theta_deg", "ruiz_F2_max", "ruiz_F2_max_x",
                          "ruiz_F1_max"}) {
    CAPTURE(key);
    REQUIRE(st.contains(key));
    REQUIRE(st[key].is_number());
    CHECK(std::isfinite(st[key].get<double>()));
  }
  const double left = s["contact"]["extent"][0].get<double>();
  const StressMap& map = run.stress_maps.front();
  const double h_map = map.x[1] - map.x[0];
  CAPTURE(st["swt_max_x"].get<double>() / kA);
  CAPTURE(st["swt_theta_deg"].get<double>());
  CHECK(st["swt_max"].get<double>() > 0.0);
  // Without bulk stress the bottom of the cycle is the top mirrored, so SWT is even in x (θ → 180° − θ) and both
  // edges are equally critical: the tie goes to the trailing edge. The maximum is on the surface row, y = 0.
  CHECK(std::abs(st["swt_max_x"].get<double>() - left) < 2.0 * h_map);
  CHECK(map.y.front() == 0.0);
  CHECK(st["swt_max_y"].get<double>() == map.y.front());
  REQUIRE(run.fatigue);
  const SwtMap& swt = run.fatigue->last().swt;
  const std::size_t nx = swt.x.size();
  const auto i_max = std::size_t(std::lround((st["swt_max_x"].get<double>() - swt.x[0]) / h_map));
  const SwtResult &at = swt.points[i_max], &mirror = swt.points[nx - 1 - i_max];
  CHECK(mirror.swt == test::rel(at.swt, 1e-6));
  CHECK(std::abs(degrees_mod_180(mirror.theta + at.theta)) < 1e-3);  // θ + θ' = 180°: mirrored planes
  const double theta = st["swt_theta_deg"].get<double>();
  CHECK(theta >= 0.0);
  CHECK(theta < 180.0);
  // Ruiz's F2 peaks inside the trailing slip zone, near the edge: the closed form (tests/unit/
  // test_fatigue_measures.cpp) puts it at −0.97374 a with 1.17331e9 Pa²·m, and F1's peak at 5.49516 J/m². At 1024
  // cells (h = 2.8e-3 a) the engine's cell tractions give −0.974 a, 0.6 % low and 0.004 % high.
  const double x2 = st["ruiz_F2_max_x"].get<double>();
  CAPTURE(x2 / kA);
  CHECK(x2 > left);
  CHECK(x2 < -kStickRatio * kA);
  CHECK(std::abs(x2 - (-0.97374 * kA)) < 2.0 * s["grid"]["h"].get<double>());
  CHECK(st["ruiz_F2_max"].get<double>() == test::rel(1.17331e9, 0.02));
  CHECK(st["ruiz_F1_max"].get<double>() == test::rel(5.49516, 1e-3));
}

TEST_CASE("fatigue scene, bulk tension in phase with Q: SWT peaks at the trailing edge at the surface") {
  const Scene scene = parse_scene(hertz_scene(1e8));
  const RunResult run = Simulation(scene).run();
  const json s = make_summary(scene, run);
  const json& st = s["stress"];
  const double left = s["contact"]["extent"][0].get<double>();
  const StressMap& map = run.stress_maps.front();
  CAPTURE(st["swt_max_x"].get<double>() / kA);
  CAPTURE(st["swt_theta_deg"].get<double>());
  CHECK(std::abs(st["swt_max_x"].get<double>() - left) < 2.0 * (map.x[1] - map.x[0]));
  CHECK(map.y.front() == 0.0);
  CHECK(st["swt_max_y"].get<double>() == map.y.front());
  // Not a tie any more: the leading edge's best is clearly lower.
  const SwtMap& swt = run.fatigue->last().swt;
  double leading = 0.0;
  for (std::size_t i = 0; i < swt.x.size(); ++i)
    if (swt.x[i] > 0.0) leading = std::max(leading, swt.points[i].swt);
  CHECK(leading < 0.9 * st["swt_max"].get<double>());
  CHECK(st["ruiz_F2_max_x"].get<double>() > left);
  CHECK(st["ruiz_F2_max_x"].get<double>() < 0.0);
}

TEST_CASE("fatigue scene: a bulk tension in phase with Q raises SWT and F2, the CSV files and plots are written") {
  const Scene plain = parse_scene(hertz_scene(0.0)), tension = parse_scene(hertz_scene(1e8, true));
  const json s0 = make_summary(plain, Simulation(plain).run());
  const RunResult run = Simulation(tension).run();
  const json s1 = make_summary(tension, run);
  CHECK(s1["stress"]["swt_max"].get<double>() > s0["stress"]["swt_max"].get<double>());
  CHECK(s1["stress"]["ruiz_F2_max"].get<double>() > s0["stress"]["ruiz_F2_max"].get<double>());

  const fs::path dir = fs::temp_directory_path() / ("fretwear-fatigue-" + std::to_string(::getpid()));
  {
    OutputFolder out(dir);
    const json written = write_results(tension, run, out);
    out.commit();
    // With gnuplot installed, the two plots are made and listed (index.html shows what the list holds). The map is
    // a PNG alone: as SVG it was a polygon per grid point, 8 MB.
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
      for (const char* plot : {"swt_map.png", "ruiz.svg", "ruiz.png"}) {
        CAPTURE(plot);
        CHECK(std::find(written["plots"].begin(), written["plots"].end(), plot) != written["plots"].end());
        CHECK(fs::file_size(dir / plot) > 0);
      }
      CHECK_FALSE(fs::exists(dir / "swt_map.svg"));
      std::ifstream index(dir / "index.html");
      const std::string html((std::istreambuf_iterator<char>(index)), {});
      CHECK(html.find("<img src=\"swt_map.png\"") != std::string::npos);
      CHECK(html.find("<img src=\"ruiz.svg\"") != std::string::npos);
      CHECK(html.find("<img src=\"ruiz.png\"") == std::string::npos);
    }
  }
  auto header = [&](const char* file) {
    std::ifstream in(dir / file);
    std::string line;
    std::getline(in, line);
    return line;
  };
  CHECK(header("fatigue.csv") == "cycles,x_m,y_m,swt_Pa,theta_crit_deg,sigma_n_max_Pa,delta_eps_n");
  CHECK(header("ruiz.csv") == "cycles,x_m,sxx_top_Pa,tau_top_Pa,slip_amplitude_m,F1_Pa_m,F2_Pa2_m");
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST_CASE("Ruiz's places are null where nothing slips under load (a maximum of zero has no place)") {
  FatigueStage f;
  FatigueRecord rec;
  RuizProfile r;
  r.x = {-1e-4, 0.0, 1e-4};
  r.F1 = r.F2 = {0.0, 0.0, 0.0};
  r.F1_max = r.F2_max = 0.0;
  r.F1_max_x = r.F2_max_x = -1e-4;  // the first point, as ruiz() leaves a maximum of zero
  rec.ruiz = r;
  rec.swt.points.resize(1);
  f.records.push_back(rec);
  nlohmann::json stress;
  add_fatigue_summary(stress, f, SingularEdges{});
  CHECK(stress["ruiz_F1_max"] == 0.0);
  CHECK(stress["ruiz_F1_max_x"].is_null());
  CHECK(stress["ruiz_F2_max_x"].is_null());
  // A maximum above zero keeps its place.
  f.records.back().ruiz->F1_max = 1.0;
  f.records.back().ruiz->F2_max = 2.0;
  nlohmann::json slipping;
  add_fatigue_summary(slipping, f, SingularEdges{});
  CHECK(slipping["ruiz_F1_max_x"] == -1e-4);
  CHECK(slipping["ruiz_F2_max_x"] == -1e-4);
}
