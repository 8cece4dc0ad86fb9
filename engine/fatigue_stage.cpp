#include "engine/fatigue_stage.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "engine/folder.hpp"
#include "engine/plot.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

namespace {

const StressMap* find_map(const std::vector<StressMap>& maps, double cycles, const std::string& phase) {
  for (const StressMap& m : maps)
    if (m.cycles == cycles && m.phase == phase) return &m;
  return nullptr;
}

// Maxima closer than this (relative) are ties, which go to the first point met: rows from the surface down, x
// increasing. A cycle without bulk stress is symmetric (the bottom is the top mirrored), so both edges are equally
// critical; the report then names the trailing edge (−x), to within the normal solve's tolerance.
constexpr double kTie = 1e-6;

// `stop` is asked before each row, with the rows done.
SwtMap swt_map(const StressMap& top, const StressMap& bottom, const Material& specimen, PlaneState plane,
               const StopCheck& stop) {
  SwtMap out;
  out.x = top.x, out.y = top.y;
  out.points.resize(top.sigma.size());
  for (std::size_t k = 0; k < top.sigma.size(); ++k) {
    if (k % out.x.size() == 0)
      stop_point(stop, {"stress", double(k / out.x.size()), double(out.y.size()), "rows of the SWT maps"});
    const Stress states[2] = {top.sigma[k], bottom.sigma[k]};
    out.points[k] = swt_critical_plane(states, specimen, plane);
    if (k == 0 || out.points[k].swt > out.max.swt + kTie * std::abs(out.max.swt)) {
      out.max = out.points[k];
      out.max_x = out.x[k % out.x.size()], out.max_y = out.y[k / out.x.size()];
    }
  }
  return out;
}

std::string num(double v) { return fmt::format("{:.10g}", v); }

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

std::string fatigue_csv(const std::vector<FatigueRecord>& records) {
  std::string s = "cycles,x_m,y_m,swt_Pa,theta_crit_deg,sigma_n_max_Pa,delta_eps_n\n";
  for (const FatigueRecord& rec : records) {
    const SwtMap& m = rec.swt;
    const std::string cycles = num(rec.cycles);
    s.reserve(s.size() + m.points.size() * 90);
    for (std::size_t j = 0; j < m.y.size(); ++j)
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const SwtResult& r = m.points[j * m.x.size() + i];
        s += fmt::format("{},{},{},{},{},{},{}\n", cycles, num(m.x[i]), num(m.y[j]), num(r.swt),
                         num(degrees(r.theta)), num(r.sigma_n_max), num(r.delta_eps_n));
      }
  }
  return s;
}

// gnuplot's pm3d wants one block per depth: x, y, SWT.
std::string swt_map_dat(const SwtMap& m) {
  std::string s;
  for (std::size_t j = 0; j < m.y.size(); ++j) {
    for (std::size_t i = 0; i < m.x.size(); ++i)
      s += fmt::format("{} {} {}\n", num(m.x[i]), num(m.y[j]), num(m.points[j * m.x.size() + i].swt));
    s += "\n";
  }
  return s;
}

std::string ruiz_csv(const std::vector<FatigueRecord>& records) {
  std::string s = "cycles,x_m,sxx_top_Pa,tau_top_Pa,slip_amplitude_m,F1_Pa_m,F2_Pa2_m\n";
  for (const FatigueRecord& rec : records) {
    if (!rec.ruiz) continue;
    const RuizProfile& r = *rec.ruiz;
    const std::string cycles = num(rec.cycles);
    for (std::size_t i = 0; i < r.x.size(); ++i)
      s += fmt::format("{},{},{},{},{},{},{}\n", cycles, num(r.x[i]), num(r.sigma_t[i]), num(r.tau[i]),
                       num(r.delta[i]), num(r.F1[i]), num(r.F2[i]));
  }
  return s;
}

// fatigue.gp: the last record's SWT map with contour lines, the critical plane at its maximum, the contact's ends;
// Ruiz's F1 and F2 along x at every record (one colour per record) with the unworn cycle's stick zone shaded.
std::string fatigue_plot_script(const Scene& scene, const NormalResult& normal, const CycleStage& cycle,
                                const FatigueStage& f) {
  const SwtMap& m = f.last().swt;
  const double x0 = m.x.front() * 1e3, x1 = m.x.back() * 1e3, depth = m.y.back() * 1e3;
  std::string s = fmt::format(R"(# Fatigue measures (contact/fatigue_measures.hpp). Re-run with: gnuplot fatigue.gp
set view map
set pm3d map interpolate 0,0
set contour base
set cntrparam levels 12
unset clabel
set xlabel 'x (mm)'
set ylabel 'depth y (mm)'
set yrange [{}:0]
set xrange [{}:{}]
set cbrange [0:*]
set size ratio -1
unset key
)", depth, x0, x1);
  s += colour_map_settings("SWT = σ_{n,max} Δε_n / 2 (MPa = MJ/m³)");
  for (const auto& z : normal.zones)
    for (double x : {z.left.x, z.right.x})
      s += fmt::format("set arrow from {0},{1} to {0},0 nohead front dt 3 lc rgb '#ffffff'\n", x * 1e3, 0.25 * depth);
  // The critical plane at the maximum: a segment along the plane (its normal at θ from +x toward +y), drawn from the
  // point into the specimen (y down the page).
  const double theta = m.max.theta, length = 0.3 * depth;
  double tx = -std::sin(theta), ty = std::cos(theta);
  if (ty < 0.0) tx = -tx, ty = -ty;
  const double px = m.max_x * 1e3, py = m.max_y * 1e3;
  s += fmt::format("set arrow from {},{} to {},{} nohead front lw 3 lc rgb '#ff3030'\n", px, py, px + tx * length,
                   py + ty * length);
  s += fmt::format("set label 'max {:.3g} MPa at x = {:.4g} mm, y = {:.3g} µm; critical plane (red) θ_{{crit}} = "
                   "{:.1f}°' at graph 0.02,0.06 front tc rgb '#ffffff'\n",
                   m.max.swt * 1e-6, px, m.max_y * 1e6, degrees(theta));
  s += fmt::format("set title \"{}: Smith–Watson–Topper on the critical plane over the cycle, {}\" noenhanced\n",
                   scene.name, cycles_text(f.last().cycles));
  s += png_only("swt_map",
                "splot 'swt_map.dat' using ($1*1e3):($2*1e3):($3*1e-6) with pm3d notitle, "
                "'' using ($1*1e3):($2*1e3):($3*1e-6) nosurface with lines lc rgb '#c8c8c8' notitle\n",
                1000, map_height(m.x.back() - m.x.front(), m.y.back()));
  std::vector<const FatigueRecord*> ruiz;
  for (const FatigueRecord& rec : f.records)
    if (rec.ruiz) ruiz.push_back(&rec);
  if (!f.last().ruiz) return s;
  s += R"(
reset
set datafile separator ','
set grid
set key outside right top
set xlabel 'x (mm)'
set ylabel 'F1 = τ δ (J/m²)'
set y2label 'F2 = σ_T τ δ (MPa·J/m²)'
set ytics nomirror
set y2tics
set yrange [0:*]
set y2range [0:*]
)";
  s += fmt::format("set xrange [{}:{}]\n", x0, x1);
  const CycleResult& c = cycle.result;
  if (c.stick_zone)
    s += fmt::format("set object 1 rect from {},graph 0 to {},graph 1 back fc rgb '#eeeeee' fs solid noborder\n",
                     c.stick_zone->first * 1e3, c.stick_zone->second * 1e3);
  s += fmt::format("set title \"{}: Ruiz parameters along the surface, top of the cycle (grey: the unworn stick "
                   "zone)\\nsolid: F1 = τ δ, left axis; dashed: F2 = σ_T τ δ, right axis\" noenhanced\n", scene.name);
  // One record's rows of ruiz.csv: its cycles written as the CSV writes them, so that gnuplot compares equal numbers.
  std::string plot = "plot ";
  for (std::size_t k = 0; k < ruiz.size(); ++k) {
    const std::string colour = ramp(ruiz.size() == 1 ? 1.0 : double(k) / double(ruiz.size() - 1));
    const std::string rows = fmt::format("($1 == {} ? $2*1e3 : 1/0)", num(ruiz[k]->cycles));
    plot += fmt::format("{}'ruiz.csv' skip 1 using {}:6 with lines lw 1.8 lc rgb '{}' title '{}', "
                        "'' skip 1 using {}:($7*1e-6) axes x1y2 with lines lw 1.4 dt 2 lc rgb '{}' notitle",
                        k ? ", " : "", rows, colour, cycles_label(ruiz[k]->cycles), rows, colour);
  }
  s += svg_and_png("ruiz", plot + "\n", 1000, 600);
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::optional<FatigueStage> run_fatigue(const Scene& scene, const Grid& grid, const std::vector<RecordPhases>& states,
                                        const std::vector<StressMap>& maps, const CycleStage& cycle,
                                        const WearStage* wear, const StopCheck& stop) {
  const auto t0 = std::chrono::steady_clock::now();
  auto out = std::make_optional<FatigueStage>();
  // The maps' rows, counted for `stop` across the records.
  double rows = 0.0, before = 0.0;
  for (const RecordPhases& state : states)
    if (const StressMap* m = find_map(maps, state.cycles, "top")) rows += double(m->y.size());
  const StopCheck counted = offset_parts(stop, &before, rows);
  for (std::size_t k = 0; k < states.size(); ++k) {
    const double cycles = states[k].cycles;
    const StressMap *map_top = find_map(maps, cycles, "top"), *map_bottom = find_map(maps, cycles, "bottom");
    if (!map_top || !map_bottom) return std::nullopt;
    FatigueRecord& rec = out->records.emplace_back();
    rec.cycles = cycles;
    rec.swt = swt_map(*map_top, *map_bottom, scene.specimen, scene.plane, counted);
    before += double(map_top->y.size());
    if (cycle.result.regime == Regime::gross_slip) continue;
    // The slip of the state the maps show: the cycle's peak-to-peak range, or the wear record's slip travelled per
    // cycle, which is twice the range (each slip-zone point runs over its range once each way).
    std::vector<double> range = cycle.result.slip_range;
    if (wear && k < wear->records.size() && wear->records[k].s.size() == std::size_t(grid.n)) {
      range = wear->records[k].s;
      for (double& v : range) v *= 0.5;
    }
    const Phase& top = states[k].phases.front();
    if (range.size() == std::size_t(grid.n))
      rec.ruiz = ruiz_along_surface(SurfaceTractions{grid, top.p, top.q, top.sigma_bulk}, range);
  }
  stop_point(stop, {"stress", rows, rows, "rows of the SWT maps"});
  out->seconds = seconds_since(t0);
  return out;
}

void add_fatigue_summary(nlohmann::json& stress, const FatigueStage& f, const SingularEdges& singular) {
  using nlohmann::json;
  const SwtMap& m = f.last().swt;
  stress["swt_max"] = m.max.swt;
  stress["swt_max_x"] = m.max_x;
  stress["swt_max_y"] = m.max_y;
  stress["swt_max_singular"] = singular.at(m.max_x, m.max_y);
  stress["swt_theta_deg"] = degrees(m.max.theta);
  stress["swt_sigma_n_max"] = m.max.sigma_n_max;
  stress["swt_delta_eps_n"] = m.max.delta_eps_n;
  const std::optional<RuizProfile>& r = f.last().ruiz;
  stress["ruiz_F1_max"] = r ? json(r->F1_max) : json(nullptr);
  // A maximum of zero (nothing slips under load: a worn contact at its limit) has no place.
  stress["ruiz_F1_max_x"] = r && r->F1_max > 0.0 ? json(r->F1_max_x) : json(nullptr);
  stress["ruiz_F2_max"] = r ? json(r->F2_max) : json(nullptr);
  stress["ruiz_F2_max_x"] = r && r->F2_max > 0.0 ? json(r->F2_max_x) : json(nullptr);
  stress["fatigue_seconds"] = f.seconds;
}

void write_fatigue(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, const FatigueStage& f,
                   OutputFolder& out, Written& written) {
  auto& tables = written.tables;
  auto& plots = written.plots;
  out.write("fatigue.csv", fatigue_csv(f.records));
  tables.push_back("fatigue.csv");
  const bool ruiz = f.last().ruiz.has_value();
  if (ruiz) {
    out.write("ruiz.csv", ruiz_csv(f.records));
    tables.push_back("ruiz.csv");
  }
  if (!scene.plots) return;
  out.write("swt_map.dat", swt_map_dat(f.last().swt));
  out.write("fatigue.gp", fatigue_plot_script(scene, normal, cycle, f));
  if (!run_gnuplot(out.path(""), "fatigue.gp")) return;
  plots.insert(plots.end(), {"swt_map.png"});
  if (ruiz) plots.insert(plots.end(), {"ruiz.svg", "ruiz.png"});
}

}  // namespace fretwear
