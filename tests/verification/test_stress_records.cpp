// The stress maps and fatigue measures at every wear record (engine/stress_stage.hpp, engine/fatigue_stage.hpp):
// the map's first row is the surface, where the stresses are the tractions' closed-form limits; fatigue.csv and
// ruiz.csv hold one block per record, the unworn state first and the summary's values in the last, and
// surface_stress.csv is the map's surface row; and a record's maps are those of a run that ends at that record.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/output.hpp"
#include "engine/simulation.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The CSV files carry 10 significant digits (csv_number): a value read back is the run's to 1e-9, relative.
constexpr double kCsvDigits = 1e-9;

// Hertz in partial slip with bulk tension on 256 cells, worn (Archard) and mapped on a small map.
Scene worn(double cycles, std::vector<double> record) {
  Scene s = test::hertz_wear(1e5, 0.5, cycles, 256);
  s.bulk_stress = 5e7;
  s.wear->record = std::move(record);
  StressEffect stress;
  stress.nx = 41;
  stress.ny = 11;
  s.stress = stress;
  return s;
}

// σxx on the surface from the cell tractions by the strip loads summed cell by cell (not over the jumps, as
// contact/subsurface_stress.cpp sums them): for x inside cell k,
//     σxx(x, 0) = −p_k − (2/π) Σ_i q_i ln(|x − ξ_i| / |x − ξ_{i+1}|) + σ_bulk.
double surface_sxx(const Grid& g, const Phase& ph, double x) {
  const int k = int(std::floor((x - g.x_min) / g.h()));
  double s = 0.0;
  for (int i = 0; i < g.n; ++i)
    if (ph.q[i] != 0.0) s += ph.q[i] * std::log(std::abs(x - g.left(i)) / std::abs(x - g.left(i + 1)));
  return -ph.p[k] - 2.0 / std::numbers::pi * s + ph.sigma_bulk;
}

// A CSV file's rows grouped by its first column (cycles), in the order met, each row's cells as numbers.
struct Blocks {
  std::string header;
  std::vector<double> cycles;
  std::map<double, std::vector<std::vector<double>>> rows;
};
Blocks read_blocks(const fs::path& file) {
  Blocks b;
  std::ifstream in(file);
  std::getline(in, b.header);
  for (std::string line; std::getline(in, line);) {
    std::vector<double> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(std::stod(cell));
    if (b.cycles.empty() || b.cycles.back() != cells[0]) b.cycles.push_back(cells[0]);
    b.rows[cells[0]].push_back(cells);
  }
  return b;
}

}  // namespace

TEST_CASE("stress map: the first row is the surface, from the cell centres around each point: −p, −q and the strip loads' sum") {
  const Scene scene = worn(1e4, {1e3, 1e4});
  const RunResult run = Simulation(scene).run();
  const Grid g = make_setup(scene).model.grid;
  const auto states = record_phases(scene, run.normal, &*run.cycle, &*run.wear);
  REQUIRE(run.stress_maps.size() == 2 * states.size());
  // Sums over a few hundred cells of terms up to p_max: their rounding, with a margin.
  const double p_max = *std::max_element(states.back().phases[0].p.begin(), states.back().phases[0].p.end());
  const double tolerance = 64.0 * g.n * kEps * p_max;
  int checked = 0;
  for (std::size_t k = 0; k < states.size(); ++k)
    for (std::size_t f = 0; f < 2; ++f) {
      const StressMap& m = run.stress_maps[2 * k + f];
      const Phase& ph = states[k].phases[f];
      CAPTURE(m.cycles);
      CAPTURE(m.phase);
      CHECK(m.cycles == states[k].cycles);
      CHECK(m.phase == ph.name);
      REQUIRE(m.y.front() == 0.0);
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const Stress& s = m.sigma[i];
        CHECK(s.xx == m.surface_sxx[i]);
        // Between the two cell centres around x: their tractions and strip-load sums, linearly (stress_stage.cpp).
        const double u = std::clamp((m.x[i] - g.x_min) / g.h() - 0.5, 0.0, double(g.n - 1));
        const int c = std::min(int(std::floor(u)), g.n - 2);
        const double w = u - c;
        auto lerp = [w](double a, double b) { return a + w * (b - a); };
        CHECK(std::abs(s.yy + lerp(ph.p[c], ph.p[c + 1])) <= tolerance);
        CHECK(std::abs(s.xy + lerp(ph.q[c], ph.q[c + 1])) <= tolerance);
        CHECK(std::abs(s.xx - lerp(surface_sxx(g, ph, g.x(c)), surface_sxx(g, ph, g.x(c + 1)))) <= tolerance);
        ++checked;
      }
    }
  CHECK(checked > 100);
  // The summary's trailing surface peak is the largest σxx of the surface row on the trailing half.
  const json summary = make_summary(scene, run);
  const StressMap& top = run.stress_maps[run.stress_maps.size() - 2];
  REQUIRE(top.phase == "top");
  const double mid = 0.5 * (top.x.front() + top.x.back());
  double peak = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < top.x.size(); ++i)
    if (top.x[i] <= mid) peak = std::max(peak, top.sigma[i].xx);
  CHECK(summary["stress"]["phases"]["top"]["surface_sxx_trailing_peak"].get<double>() == peak);
}

TEST_CASE("fatigue.csv and ruiz.csv: one block per record from the unworn state, the last the summary's, and the surface row in surface_stress.csv") {
  const Scene scene = worn(1e4, {1e3, 1e4});
  const RunResult run = Simulation(scene).run();
  const json summary = make_summary(scene, run);
  const fs::path dir = fs::temp_directory_path() / ("fretwear-records-" + std::to_string(::getpid()));
  {
    Scene quiet = scene;
    quiet.plots = false;
    OutputFolder out(dir);
    write_results(quiet, run, out);
    out.commit();
  }
  const std::vector<double> want{0.0, 1e3, 1e4};
  const json& st = summary["stress"];

  const Blocks fatigue = read_blocks(dir / "fatigue.csv");
  CHECK(fatigue.header == "cycles,x_m,y_m,swt_Pa,theta_crit_deg,sigma_n_max_Pa,delta_eps_n");
  CHECK(fatigue.cycles == want);
  // The last record on the full map (41 × (11 + 1) points), the earlier ones every second point of it.
  CHECK(fatigue.rows.at(1e4).size() == 41u * 12u);
  CHECK(fatigue.rows.at(0.0).size() == 21u * 7u);
  double swt = 0.0, swt_x = 0.0, swt_y = 0.0;
  for (const auto& r : fatigue.rows.at(1e4))
    if (r[3] > swt) swt = r[3], swt_x = r[1], swt_y = r[2];
  CHECK(swt == test::rel(st["swt_max"].get<double>(), kCsvDigits));
  CHECK(swt_x == test::rel(st["swt_max_x"].get<double>(), kCsvDigits));
  CHECK(swt_y == doctest::Approx(st["swt_max_y"].get<double>()).epsilon(kCsvDigits).scale(1e-9));

  const Blocks ruiz = read_blocks(dir / "ruiz.csv");
  CHECK(ruiz.header == "cycles,x_m,sxx_top_Pa,tau_top_Pa,slip_amplitude_m,F1_Pa_m,F2_Pa2_m");
  CHECK(ruiz.cycles == want);
  double F1 = 0.0, F2 = 0.0;
  for (const auto& r : ruiz.rows.at(1e4)) F1 = std::max(F1, r[5]), F2 = std::max(F2, r[6]);
  CHECK(F1 == test::rel(st["ruiz_F1_max"].get<double>(), kCsvDigits));
  CHECK(F2 == test::rel(st["ruiz_F2_max"].get<double>(), kCsvDigits));
  // surface_stress.csv is the last state's surface row, whose trailing-half peak the summary holds.
  {
    std::ifstream in(dir / "surface_stress.csv");
    std::string line;
    std::getline(in, line);
    CHECK(line == "phase,x_m,sxx_Pa");
    const StressMap& top = run.stress_maps[run.stress_maps.size() - 2];
    REQUIRE(top.phase == "top");
    std::size_t i = 0;
    double peak = -std::numeric_limits<double>::infinity();
    while (std::getline(in, line) && line.rfind("top,", 0) == 0) {
      std::stringstream ss(line.substr(4));
      std::string x, sxx;
      std::getline(ss, x, ',');
      std::getline(ss, sxx, ',');
      REQUIRE(i < top.x.size());
      CHECK(std::stod(sxx) == test::rel(top.sigma[i].xx, kCsvDigits));
      if (top.x[i] <= 0.5 * (top.x.front() + top.x.back())) peak = std::max(peak, std::stod(sxx));
      ++i;
    }
    CHECK(i == top.x.size());
    CHECK(peak == test::rel(st["phases"]["top"]["surface_sxx_trailing_peak"].get<double>(), kCsvDigits));
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST_CASE("a record's stresses and SWT are those of a run that ends at that record") {
  // The run to 1e4 cycles recorded at 1e3 and 3e3, and the run that stops at 3e3: the wear stepper reaches 3e3 up
  // to its tolerance, so the maps agree to the wear's relative tolerance on the profile.
  const Scene longer = worn(1e4, {1e3, 3e3, 1e4}), shorter = worn(3e3, {1e3, 3e3});
  const RunResult a = Simulation(longer).run(), b = Simulation(shorter).run();
  const double tolerance = longer.wear->tolerance;
  const auto maps_b = last_record(b.stress_maps);
  REQUIRE(maps_b.front().cycles == 3e3);
  double scale = 0.0;
  for (const Stress& s : maps_b.front().sigma) scale = std::max({scale, std::abs(s.xx), std::abs(s.yy)});
  int checked = 0;
  for (const StressMap& ma : a.stress_maps) {
    if (ma.cycles != 3e3) continue;
    const StressMap& mb = ma.phase == maps_b[0].phase ? maps_b[0] : maps_b[1];
    REQUIRE(mb.phase == ma.phase);
    // The record's map takes every second point of the full one.
    for (std::size_t j = 0; j < ma.y.size(); ++j)
      for (std::size_t i = 0; i < ma.x.size(); ++i) {
        const std::size_t ib = std::find(mb.x.begin(), mb.x.end(), ma.x[i]) - mb.x.begin();
        const std::size_t jb = std::find(mb.y.begin(), mb.y.end(), ma.y[j]) - mb.y.begin();
        REQUIRE(ib < mb.x.size());
        REQUIRE(jb < mb.y.size());
        const Stress &sa = ma.sigma[j * ma.x.size() + i], &sb = mb.sigma[jb * mb.x.size() + ib];
        CHECK(std::abs(sa.xx - sb.xx) <= tolerance * scale);
        CHECK(std::abs(sa.yy - sb.yy) <= tolerance * scale);
        CHECK(std::abs(sa.xy - sb.xy) <= tolerance * scale);
        ++checked;
      }
  }
  CHECK(checked == 2 * 21 * 7);
  const FatigueRecord* ra = nullptr;
  for (const FatigueRecord& r : a.fatigue->records)
    if (r.cycles == 3e3) ra = &r;
  REQUIRE(ra);
  REQUIRE(ra->ruiz);
  REQUIRE(b.fatigue->last().ruiz);
  CHECK(ra->ruiz->F1_max == test::rel(b.fatigue->last().ruiz->F1_max, tolerance));
  CHECK(ra->ruiz->F2_max == test::rel(b.fatigue->last().ruiz->F2_max, tolerance));
}
