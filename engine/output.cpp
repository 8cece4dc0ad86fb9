#include "engine/output.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/fatigue_stage.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string num(double v) { return csv_number(v); }

std::string contact_csv(const NormalResult& n) {
  std::string s = n.reference ? "x_m,gap0_m,p_Pa,gap_m,p_closed_form_Pa\n" : "x_m,gap0_m,p_Pa,gap_m\n";
  for (int i = 0; i < n.grid.n; ++i) {
    s += fmt::format("{},{},{},{}", num(n.grid.x(i)), num(n.g0[i]), num(n.state.p[i]), num(n.state.gap[i]));
    if (n.reference) s += "," + num(n.reference->p_cell[i]);
    s += "\n";
  }
  return s;
}

std::string pressure_plot_script(const Scene& scene, const NormalResult& n, const CycleStage* cycle) {
  std::string s = R"(# Pressure under the normal load. Re-run with: gnuplot pressure.gp
set datafile separator ','
set datafile missing 'inf'
set xlabel 'x (mm)'
set ylabel 'pressure p (MPa)'
set grid
set key top right
)";
  s += fmt::format("set title \"{}: P = {:.4g} kN/m, {} cells\" noenhanced\n", scene.name, scene.P * 1e-3, n.grid.n);
  s += fmt::format("set xrange [{}:{}]\n", n.grid.x_min * 1e3, n.grid.x_max * 1e3);
  for (const auto& z : n.zones)
    for (double x : {z.left.x, z.right.x})
      s += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead dt 3 lc rgb '#888888'\n", x * 1e3);
  std::string plot = "plot 'contact.csv' skip 1 using ($1*1e3):($3*1e-6) with steps lw 1.5 lc rgb '#1f77b4' "
                     "title 'fretwear (cell pressure)'";
  if (n.reference)
    plot += fmt::format(", '' skip 1 using ($1*1e3):($5*1e-6) with lines dt 2 lw 1.5 lc rgb '#d62728' "
                        "title 'closed form ({})'", n.reference->kind);
  if (cycle && !cycle->p_top.empty())  // β ≠ 0: the pressure the shear leaves at the top and the bottom of the cycle
    plot += ", 'cycle.csv' skip 1 using ($1*1e3):($10*1e-6) with steps lw 1.2 lc rgb '#d62728' title 'top of the "
            "cycle (coupled)', '' skip 1 using ($1*1e3):($11*1e-6) with steps lw 1.2 dt 2 lc rgb '#2ca02c' "
            "title 'bottom of the cycle (coupled)'";
  s += "set terminal svg size 900,560 dynamic font 'sans,12'\nset output 'pressure.svg'\n" + plot + "\n";
  s += "set terminal pngcairo size 900,560 font 'sans,11'\nset output 'pressure.png'\nreplot\nunset output\n";
  return s;
}

std::string cycle_csv(const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  const bool coupled = !st.p_top.empty();
  std::string s = "x_m,p_Pa,q_top_Pa,q_unloaded_Pa,q_bottom_Pa,q_reloaded_Pa,slip_range_m,slip_per_cycle_m,"
                  "energy_density_J_m2";
  s += coupled ? ",p_top_Pa,p_bottom_Pa\n" : "\n";
  for (int i = 0; i < n.grid.n; ++i) {
    s += fmt::format("{},{},{},{},{},{},{},{},{}", num(n.grid.x(i)), num(n.state.p[i]), num(c.q_top[i]),
                     num(c.q_unloaded[i]), num(c.q_bottom[i]), num(c.q_reloaded[i]), num(c.slip_range[i]),
                     num(c.slip_travelled[i]), num(c.energy_density[i]));
    s += coupled ? fmt::format(",{},{}\n", num(st.p_top[i]), num(st.p_bottom[i])) : "\n";
  }
  return s;
}

std::string cycle_plot_script(const Scene& scene, const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  std::string head = fmt::format(R"(# The load cycle. Re-run with: gnuplot cycle.gp
set datafile separator ','
set xlabel 'x (mm)'
set grid
set key outside right top
set xrange [{}:{}]
)", n.grid.x_min * 1e3, n.grid.x_max * 1e3);
  std::string marks;
  if (c.stick_zone)
    marks = fmt::format("set object 1 rect from {},graph 0 to {},graph 1 back fc rgb '#eeeeee' fs solid noborder\n",
                        c.stick_zone->first * 1e3, c.stick_zone->second * 1e3);
  const double f = st.f;
  std::string s = head + marks;
  s += fmt::format("set title \"{}: shear traction at the four phases (Q/fP = {:.3g}, f = {:.3g}; {})\" noenhanced\n",
                   scene.name, st.Q_max / (f * scene.P), f, c.stick_zone ? "grey: stick zone" : "gross slip: no stick zone");
  s += "set ylabel 'shear traction q (MPa)'\n";
  // The Coulomb bounds ±f p: with β ≠ 0 the pressure differs between the top and the bottom of the cycle.
  const std::string bounds =
      st.p_top.empty()
          ? fmt::format("'cycle.csv' skip 1 using ($1*1e3):({0}*$2*1e-6) with lines dt 3 lc rgb '#888888' title '±f p', "
                        "'' skip 1 using ($1*1e3):(-{0}*$2*1e-6) with lines dt 3 lc rgb '#888888' notitle, ",
                        f)
          : fmt::format("'cycle.csv' skip 1 using ($1*1e3):({0}*$10*1e-6) with lines dt 3 lc rgb '#888888' "
                        "title '±f p, top', '' skip 1 using ($1*1e3):(-{0}*$10*1e-6) with lines dt 3 lc rgb '#888888' "
                        "notitle, '' skip 1 using ($1*1e3):({0}*$11*1e-6) with lines dt 4 lc rgb '#555555' "
                        "title '±f p, bottom', '' skip 1 using ($1*1e3):(-{0}*$11*1e-6) with lines dt 4 "
                        "lc rgb '#555555' notitle, ",
                        f);
  s += "plot " + bounds;
  s += fmt::format(
      "'' skip 1 using ($1*1e3):($3*1e-6) with lines lw 1.5 lc rgb '#d62728' title 'top (+{0})', "
      "'' skip 1 using ($1*1e3):($4*1e-6) with lines lw 1.5 lc rgb '#ff7f0e' title 'unloaded ({0} = 0)', "
      "'' skip 1 using ($1*1e3):($5*1e-6) with lines lw 1.5 lc rgb '#1f77b4' title 'bottom (-{0})', "
      "'' skip 1 using ($1*1e3):($6*1e-6) with lines lw 1.5 dt 2 lc rgb '#2ca02c' title 'reloaded ({0} = 0)'\n",
      scene.control == LoadControl::displacement ? "δ" : "Q");  // the phases of the controlled quantity
  const std::string traction_plot = s.substr(s.find("plot 'cycle.csv'"));
  std::string out = s.substr(0, s.find("plot 'cycle.csv'"));
  out += "set terminal svg size 1000,560 dynamic font 'sans,12'\nset output 'traction.svg'\n" + traction_plot;
  out += "set terminal pngcairo size 1000,560 font 'sans,11'\nset output 'traction.png'\nreplot\nunset output\n";
  out += fmt::format("set title \"{}: slip per cycle (range and distance travelled)\" noenhanced\n", scene.name);
  out += "set ylabel 'slip (µm)'\nset y2label 'frictional energy per cycle (J/m²)'\nset y2tics\nset ytics nomirror\n";
  const std::string slip_plot =
      "plot 'cycle.csv' skip 1 using ($1*1e3):($7*1e6) with lines lw 1.5 lc rgb '#1f77b4' title 'slip range "
      "(peak to peak)', '' skip 1 using ($1*1e3):($8*1e6) with lines lw 1.5 dt 2 lc rgb '#1f77b4' title 'slip "
      "travelled per cycle', '' skip 1 using ($1*1e3):9 axes x1y2 with lines lw 1.5 lc rgb '#d62728' title "
      "'energy density'\n";
  out += "set terminal svg size 1000,560 dynamic font 'sans,12'\nset output 'slip.svg'\n" + slip_plot;
  out += "set terminal pngcairo size 1000,560 font 'sans,11'\nset output 'slip.png'\nreplot\nunset output\n";
  return out;
}

// One row per wear record (SI); the stick-zone ends are empty when the contact slips everywhere, the fraction when
// there is no asymptote (displacement control).
std::string wear_history_csv(const WearStage& w) {
  std::string s = "cycles,worn_area_m2,max_depth_m,fraction_of_asymptote,stick_left_m,stick_right_m,contact_left_m,"
                  "contact_right_m,p_max_Pa\n";
  const bool asymptote = w.asymptote.unavailable.empty();
  for (const WearRecord& r : w.records)
    s += fmt::format("{},{},{},{},{},{},{},{},{}\n", num(r.cycles), num(r.worn_area), num(r.max_depth),
                     asymptote ? num(r.fraction) : "", r.stick_zone ? num(r.stick_zone->first) : "",
                     r.stick_zone ? num(r.stick_zone->second) : "", num(r.contact.first), num(r.contact.second),
                     num(r.p_max));
  return s;
}

// Long format: one row per record and cell, then the asymptote as rows with cycles = inf (its slip is left empty:
// the asymptote is a limit, not a cycle). Rows of record k are rows k·n ... k·n + n − 1 after the header.
std::string profiles_csv(const Scene& scene, const NormalResult& n, const WearStage& w) {
  const double pad = scene.wear->pad_fraction;
  std::string s = "cycles,x_m,gap0_m,wear_m,wear_pad_m,wear_specimen_m,p_Pa,slip_per_cycle_m\n";
  s.reserve(s.size() + (w.records.size() + 1) * std::size_t(n.grid.n) * 110);
  for (const WearRecord& r : w.records) {
    const std::string c = num(r.cycles);
    for (int i = 0; i < n.grid.n; ++i)
      s += fmt::format("{},{},{},{},{},{},{},{}\n", c, num(n.grid.x(i)), num(n.g0[i]), num(r.w[i]),
                       num(pad * r.w[i]), num((1.0 - pad) * r.w[i]), num(r.p[i]), num(r.s[i]));
  }
  const WearAsymptote& a = w.asymptote;
  if (a.w.size() != std::size_t(n.grid.n) || a.p.size() != std::size_t(n.grid.n)) return s;
  for (int i = 0; i < n.grid.n; ++i)
    s += fmt::format("inf,{},{},{},{},{},{},\n", num(n.grid.x(i)), num(n.g0[i]), num(a.w[i]), num(pad * a.w[i]),
                     num((1.0 - pad) * a.w[i]), num(a.p[i]));
  return s;
}

// The records the evolution plots show: the initial state and at most 7 more, spread evenly in log cycles, always
// with the last.
std::vector<std::size_t> plotted_records(const WearStage& w) {
  constexpr std::size_t kMore = 7;
  std::vector<std::size_t> out, worn;
  for (std::size_t k = 0; k < w.records.size(); ++k) (w.records[k].cycles > 0.0 ? worn : out).push_back(k);
  if (worn.size() <= kMore) {
    for (std::size_t k : worn) out.push_back(k);
    return out;
  }
  // Each target in turn takes the nearest record not yet taken; targets and records both increase, so the picks do.
  const double lo = std::log(w.records[worn.front()].cycles), hi = std::log(w.records[worn.back()].cycles);
  std::size_t next = 0;  // the first record in `worn` still free
  for (std::size_t j = 0; j < kMore; ++j) {
    const double target = lo + (hi - lo) * double(j) / double(kMore - 1);
    const std::size_t last_free = worn.size() - (kMore - j);  // leave one record for each later target
    std::size_t best = next;
    for (std::size_t i = next; i <= last_free; ++i)
      if (std::abs(std::log(w.records[worn[i]].cycles) - target) <
          std::abs(std::log(w.records[worn[best]].cycles) - target))
        best = i;
    out.push_back(worn[best]);
    next = best + 1;
  }
  return out;
}

// A colour ramp from dark blue to orange (matplotlib's plasma, up to 0.85): t in [0, 1].
std::string ramp(double t) {
  static const int stops[5][3] = {{13, 8, 135}, {106, 0, 168}, {177, 42, 144}, {225, 100, 98}, {244, 150, 40}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int k = std::min(3, int(t));
  const double u = t - k;
  int c[3];
  for (int j = 0; j < 3; ++j) c[j] = int(std::lround(stops[k][j] + u * (stops[k + 1][j] - stops[k][j])));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

// A cycle count for a legend (gnuplot enhanced text): 0, 250, 3.16×10^5.
std::string cycles_label(double c) {
  if (c == 0.0) return "N = 0 (unworn)";
  if (c < 1e4) return fmt::format("N = {:.0f}", c);
  const int e = int(std::floor(std::log10(c) + 1e-12));
  const double m = c / std::pow(10.0, e);
  if (std::abs(m - std::round(m)) < 5e-3) return fmt::format("N = {:.0f}×10^{{{}}}", std::round(m), e);
  return fmt::format("N = {:.3g}×10^{{{}}}", m, e);
}

// The fretting loop: Q against δ at the end of every increment, the first loading and then the steady cycle, top to
// top (contact/reference_datum.hpp for the datum).
std::string loop_csv(const CycleResult& c) {
  std::string s = "phase,P_N_m,Q_N_m,delta_m\n";
  for (const LoopPoint& l : c.first_loading)
    s += fmt::format("first_loading,{},{},{}\n", num(l.P), num(l.Q), num(l.delta));
  for (const LoopPoint& l : c.loop) s += fmt::format("cycle,{},{},{}\n", num(l.P), num(l.Q), num(l.delta));
  return s;
}

std::string loop_plot_script(const Scene& scene, const CycleStage& st) {
  const CycleResult& c = st.result;
  const std::size_t n0 = c.first_loading.size();
  return fmt::format(R"gp(# The fretting loop. Re-run with: gnuplot loop.gp
set datafile separator ','
set title "{0}: fretting loop, reference points {1:.4g} mm deep" noenhanced
set label 1 "dissipated per cycle {3:.4g} J/m\nreference points at x = {2:.4g} mm" at graph 0.97, graph 0.06 right
set label 1 noenhanced
set xlabel 'relative tangential displacement δ of the reference points (µm)'
set ylabel 'tangential load Q (kN/m)'
set grid
set key inside left top opaque box
set xzeroaxis lt -1 lw 0.5
set yzeroaxis lt -1 lw 0.5
)gp",
                     scene.name, st.reference_depth * 1e3,
                     std::abs(st.reference_x) < 1e-9 * st.reference_depth ? 0.0 : st.reference_x * 1e3,
                     c.dissipated_energy) +
         svg_and_png("loop",
                     fmt::format("plot 'loop.csv' skip 1 every ::0::{0} using ($4*1e6):($3*1e-3) with lines lw 1.5 "
                                 "dt 2 lc rgb '#888888' title 'first loading', '' skip 1 every ::{1} using "
                                 "($4*1e6):($3*1e-3) with linespoints pt 7 ps 0.4 lw 1.5 lc rgb '#d62728' "
                                 "title 'steady cycle'\n",
                                 n0 - 1, n0),
                     900, 640);
}

std::string sif_csv(const RunResult& r) {
  std::string s = "cycles,phase,length_m,K_I_Pa_sqrt_m,K_I_open_Pa_sqrt_m,K_II_Pa_sqrt_m,closed\n";
  for (const SifSet& set : r.sifs)
    for (const CrackSif& k : set.result.sifs)
      s += fmt::format("{},{},{},{},{},{},{}\n", num(set.cycles), set.phase, num(k.l), num(k.K_I), num(k.K_I_open),
                       num(k.K_II), k.closed ? 1 : 0);
  return s;
}

std::string stress_csv(const RunResult& r, double nu) {
  std::string s = "phase,x_m,y_m,sxx_Pa,syy_Pa,sxy_Pa,von_mises_Pa,s1_Pa,s2_Pa\n";
  for (const StressMap& m : r.stress_maps)
    for (std::size_t j = 0; j < m.y.size(); ++j)
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const Stress& t = m.sigma[j * m.x.size() + i];
        const Principal pr = principal(t);
        s += fmt::format("{},{},{},{},{},{},{},{},{}\n", m.phase, num(m.x[i]), num(m.y[j]), num(t.xx), num(t.yy),
                         num(t.xy), num(von_mises(t, nu)), num(pr.s1), num(pr.s2));
      }
  return s;
}

std::string surface_stress_csv(const RunResult& r) {
  std::string s = "phase,x_m,sxx_Pa\n";
  for (const StressMap& m : r.stress_maps)
    for (std::size_t i = 0; i < m.x.size(); ++i) s += fmt::format("{},{},{}\n", m.phase, num(m.x[i]), num(m.surface_sxx[i]));
  return s;
}

// gnuplot's pm3d wants one block per depth: x, y, σxx, σyy, σxy, von Mises.
std::string stress_map_dat(const StressMap& m, double nu) {
  std::string s;
  for (std::size_t j = 0; j < m.y.size(); ++j) {
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      const Stress& t = m.sigma[j * m.x.size() + i];
      s += fmt::format("{} {} {} {} {} {}\n", num(m.x[i]), num(m.y[j]), num(t.xx), num(t.yy), num(t.xy),
                       num(von_mises(t, nu)));
    }
    s += "\n";
  }
  return s;
}

// crack.gp: K_I and K_II against crack length, top (solid) and bottom (dashed) of the cycle, the initial and the
// last state, the records between in thin lines.
std::string crack_plot_script(const Scene& scene, const RunResult& r) {
  std::vector<double> states;
  for (const SifSet& set : r.sifs)
    if (states.empty() || states.back() != set.cycles) states.push_back(set.cycles);
  const std::string hi = scene.tangential ? "top" : "loaded", lo = scene.tangential ? "bottom" : "loaded";
  std::string s = fmt::format(R"(# Stress intensity factors. Re-run with: gnuplot crack.gp
set datafile separator ','
set xlabel 'crack length l (µm)'
set grid
set key outside right top
set title "{}: crack at x = {:.4g} mm ({}), {}" noenhanced
)", scene.name, r.crack_x * 1e3, scene.crack->at == CrackPosition::x ? "given" : to_string(scene.crack->at),
                              scene.crack->angle_deg == 90.0
                                  ? std::string("normal to the surface")
                                  : fmt::format("at {:g}° to the surface, face friction {:g}", scene.crack->angle_deg,
                                                scene.crack->face_friction));
  for (const char* mode : {"K_I", "K_II"}) {
    const int col = std::string(mode) == "K_I" ? 4 : 6;
    std::string plot = "plot ";
    for (std::size_t k = 0; k < states.size(); ++k) {
      const bool shown = k == 0 || k + 1 == states.size();
      const double t = states.size() > 1 ? double(k) / double(states.size() - 1) : 0.0;
      auto line = [&](const std::string& phase, const char* dash) {
        return fmt::format("'sif.csv' skip 1 using ($1 == {} && strcol(2) eq '{}' ? $3*1e6 : 1/0):(${}*1e-6) with "
                           "linespoints pt 7 ps 0.4 lw {} {} lc rgb '{}' {}, ",
                           num(states[k]), phase, col, shown ? 2.0 : 0.7, dash, ramp(t),
                           shown ? fmt::format("title '{}, {}'", r.wear ? cycles_label(states[k]) : "initial", phase)
                                 : std::string("notitle"));
      };
      plot += line(hi, "");
      if (lo != hi) plot += line(lo, "dt 2");
    }
    plot.resize(plot.size() - 2);
    s += fmt::format("set ylabel '{} (MPa√m)'\n", mode);
    s += svg_and_png(std::string("sif_") + (col == 4 ? "I" : "II"), plot + "\n");
  }
  return s;
}

// stress.gp: von Mises and σxx maps under the contact at the first phase.
std::string stress_plot_script(const Scene& scene, const StressMap& m) {
  std::string s = fmt::format(R"(# Stress under the surface. Re-run with: gnuplot stress.gp
set view map
set pm3d map interpolate 0,0
set palette rgbformulae 33,13,10
set xlabel 'x (mm)'
set ylabel 'depth y (mm)'
set yrange [{}:0]
set xrange [{}:{}]
set size ratio -1
unset key
)", m.y.back() * 1e3, m.x.front() * 1e3, m.x.back() * 1e3);
  s += fmt::format("set title \"{}: von Mises stress at the {} of the cycle (MPa)\" noenhanced\n", scene.name, m.phase);
  s += png_only("stress_von_mises", "splot 'stress_map.dat' using ($1*1e3):($2*1e3):($6*1e-6) with pm3d\n");
  s += fmt::format("set title \"{}: σxx at the {} of the cycle (MPa)\" noenhanced\n", scene.name, m.phase);
  s += png_only("stress_sxx", "splot 'stress_map.dat' using ($1*1e3):($2*1e3):($3*1e-6) with pm3d\n");
  return s;
}

// wear.gp: the worn profile and the pressure as they evolve (with the asymptote dashed), the stick zone and the
// worn area against cycles.
std::string wear_plot_script(const Scene& scene, const NormalResult& n, const WearStage& w) {
  const int cells = n.grid.n;
  const std::vector<std::size_t> shown = plotted_records(w);
  const WearAsymptote& a = w.asymptote;
  const WearRecord& last = w.records.back();
  // The x range: the region that wears (the asymptote's extent, or the last contact) with a quarter margin.
  double l = std::min(a.extent.first, last.contact.first), r = std::max(a.extent.second, last.contact.second);
  for (const auto& z : n.zones) l = std::min(l, z.left.x), r = std::max(r, z.right.x);
  const double m = 0.25 * (r - l);
  l = std::max(n.grid.x_min, l - m), r = std::min(n.grid.x_max, r + m);

  std::string s = fmt::format(R"(# The wear run. Re-run with: gnuplot wear.gp
# profiles.csv holds {0} rows per record (record k: data rows k*{0} ... k*{0}+{1}, counted from 0 after the header);
# the asymptote (cycles = inf) comes last.
set datafile separator ','
set grid
)", cells, cells - 1);
  const auto series = [&](const std::string& column, const std::string& asymptote_title) {
    std::string plot = "plot ";
    for (std::size_t j = 0; j < shown.size(); ++j) {
      const std::size_t k = shown[j];
      const double t = shown.size() > 1 ? double(j) / double(shown.size() - 1) : 1.0;
      plot += fmt::format("'profiles.csv' skip 1 every ::{}::{} using ($2*1e3):({}) with lines lw 1.5 "
                          "lc rgb '{}' title '{}', ",
                          k * cells, k * cells + cells - 1, column, ramp(t),
                          cycles_label(w.records[k].cycles));
    }
    const std::size_t k = w.records.size();
    if (a.w.size() != std::size_t(cells)) return plot.substr(0, plot.size() - 2) + "\n";  // no asymptote rows
    plot += fmt::format("'profiles.csv' skip 1 every ::{}::{} using ($2*1e3):({}) with lines lw 2 dt 2 "
                        "lc rgb '#000000' title '{}'\n",
                        k * cells, k * cells + cells - 1, column, asymptote_title);
    return plot;
  };
  const std::string law = scene.wear->law == "archard" ? "Archard k" : "energy α";
  s += fmt::format("set xrange [{}:{}]\nset xlabel 'x (mm)'\nset key outside right top\n", l * 1e3, r * 1e3);
  s += fmt::format("set title \"{}: wear depth, both bodies ({} = {:.3g} 1/Pa; pad share {:.3g})\" noenhanced\n",
                   scene.name, law, scene.wear->coefficient, scene.wear->pad_fraction);
  s += "set ylabel 'wear depth w (µm)'\nset yrange [0:*]\n";
  s += svg_and_png("wear_depth", series("$4*1e6", "asymptote"));
  if (a.unavailable.empty())
    s += fmt::format("set title \"{}: contact pressure as the slip zones wear (the asymptote's is singular at the "
                     "stick-zone ends)\" noenhanced\n", scene.name);
  else  // displacement control: no asymptote; in gross slip no stick zone, and the whole contact wears
    s += fmt::format("set title \"{}: contact pressure as the contact wears ({})\" noenhanced\n", scene.name,
                     w.records.front().stick_zone ? "no asymptote under displacement control"
                                                  : "gross slip: no stick zone, no asymptote");
  s += "set ylabel 'pressure p (MPa)'\n";
  s += svg_and_png("wear_pressure", series("$7*1e-6", "asymptote"));

  // Against cycles: log axis; the unworn record (cycles = 0) cannot be shown there, and a run stopped before its
  // first record after it has nothing to show.
  if (!(last.cycles > 0.0)) return s;
  double n_lo = last.cycles;
  for (const WearRecord& rec : w.records)
    if (rec.cycles > 0.0) n_lo = std::min(n_lo, rec.cycles);
  s += "\nunset xrange\nunset yrange\nset logscale x\nset format x '10^{%L}'\nset xlabel 'cycles N'\n";
  s += "set key inside right center opaque box\n";
  if (n_lo < last.cycles)
    s += fmt::format("set xrange [{}:{}]\n", std::pow(10.0, std::floor(std::log10(n_lo))),
                     std::pow(10.0, std::ceil(std::log10(last.cycles))));
  const auto& s0 = w.records.front().stick_zone;
  std::string stick;
  if (s0) {
    // Both ends and the contact's ends on one scale: the stick zone standing still inside a growing contact.
    double lo = s0->first, hi = s0->second;
    for (const WearRecord& rec : w.records) {
      lo = std::min(lo, rec.contact.first), hi = std::max(hi, rec.contact.second);
      if (rec.stick_zone) lo = std::min(lo, rec.stick_zone->first), hi = std::max(hi, rec.stick_zone->second);
    }
    if (w.asymptote.unavailable.empty())
      lo = std::min(lo, w.asymptote.extent.first), hi = std::max(hi, w.asymptote.extent.second);
    const double pad = 0.08 * (hi - lo);
    s += fmt::format("set yrange [{}:{}]\n", (lo - pad) * 1e3, (hi + pad) * 1e3);
    s += fmt::format("set title \"{}: stick zone and contact extent against cycles\" noenhanced\n", scene.name);
    s += "set ylabel 'x (mm)'\n";
    stick = fmt::format(
        "plot {0} with lines lw 9 lc rgb '#d9d9d9' title 'initial stick zone', "
        "{1} with lines lw 9 lc rgb '#d9d9d9' notitle, "
        "'wear_history.csv' skip 1 using ($1 > 0 ? $1 : NaN):($5*1e3) with linespoints pt 7 ps 0.7 lw 1.5 "
        "lc rgb '#1f77b4' title 'stick zone, left end', "
        "'' skip 1 using ($1 > 0 ? $1 : NaN):($6*1e3) with linespoints pt 5 ps 0.7 lw 1.5 lc rgb '#d62728' "
        "title 'stick zone, right end', "
        "'' skip 1 using ($1 > 0 ? $1 : NaN):($7*1e3) with linespoints pt 6 ps 0.7 lw 1 lc rgb '#6baed6' "
        "title 'contact, left end', "
        "'' skip 1 using ($1 > 0 ? $1 : NaN):($8*1e3) with linespoints pt 4 ps 0.7 lw 1 lc rgb '#fc9272' "
        "title 'contact, right end'",
        num(s0->first * 1e3), num(s0->second * 1e3));
    // The worn extent of the asymptote, where the contact tends (its worn zones touch at zero pressure there, so
    // near the limit the contact's ends move by a few cells from record to record).
    if (w.asymptote.unavailable.empty())
      stick += fmt::format(", {0} with lines dt 2 lw 1 lc rgb '#555555' title 'worn extent of the asymptote', {1} with "
                           "lines dt 2 lw 1 lc rgb '#555555' notitle",
                           num(w.asymptote.extent.first * 1e3), num(w.asymptote.extent.second * 1e3));
    s += svg_and_png("wear_stick_zone", stick + "\n");
  }
  const double area_top = 1.12 * std::max(a.worn_area, [&] {
    double v = 0.0;
    for (const WearRecord& rec : w.records) v = std::max(v, rec.worn_area);
    return v;
  }());
  s += fmt::format("set title \"{}: worn area against cycles\" noenhanced\n", scene.name);
  s += "set key inside left top opaque box\nset ylabel 'worn area ∫ w dx (µm²)'\n";
  if (area_top > 0.0) {
    s += fmt::format("set yrange [0:{}]\n", area_top * 1e12);
    if (a.worn_area > 0.0)
      s += fmt::format("set y2range [0:{}]\nset y2label 'fraction of the asymptote'\nset ytics nomirror\n"
                       "set y2tics\n", area_top / a.worn_area);
  }
  // Without an asymptote (displacement control) the dashed line is the initial rate c ∫ p s dx carried on: the
  // worn area of uniform wear at the rate of the unworn contact (Archard, for sliding: k P s N).
  double rate0 = 0.0;
  for (std::size_t i = 0; i < w.records.front().p.size(); ++i)
    rate0 += w.rate_coefficient * w.records.front().p[i] * w.records.front().s[i] * n.grid.h();
  const std::string reference = a.unavailable.empty()
                                    ? fmt::format("{} with lines lw 2 dt 2 lc rgb '#000000' title 'asymptote'",
                                                  num(a.worn_area * 1e12))
                                    : fmt::format("{}*x with lines lw 2 dt 2 lc rgb '#000000' title 'initial rate "
                                                  "c ∫ p s dx, times N'",
                                                  num(rate0 * 1e12));
  s += svg_and_png("wear_area",
                   fmt::format("plot {} , "
                               "'wear_history.csv' skip 1 using ($1 > 0 ? $1 : NaN):($2*1e12) with linespoints pt 7 "
                               "ps 0.7 lw 1.5 lc rgb '#1f77b4' title 'fretwear'\n",
                               reference));
  return s;
}

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
  out.write("contact.csv", contact_csv(result.normal));
  std::vector<std::string> tables{"contact.csv"};
  const bool slips = result.cycle && !result.cycle->result.slip_range.empty();  // gross slip under force control: none
  if (slips) {
    out.write("cycle.csv", cycle_csv(result.normal, *result.cycle));
    tables.push_back("cycle.csv");
    if (!result.cycle->result.loop.empty()) {
      out.write("loop.csv", loop_csv(result.cycle->result));
      tables.push_back("loop.csv");
    }
  }
  std::vector<std::string> plots;
  if (scene.plots) {
    out.write("pressure.gp", pressure_plot_script(scene, result.normal, result.cycle ? &*result.cycle : nullptr));
    if (run_gnuplot(out.path(""), "pressure.gp")) plots.insert(plots.end(), {"pressure.svg", "pressure.png"});
    if (slips) {
      out.write("cycle.gp", cycle_plot_script(scene, result.normal, *result.cycle));
      if (run_gnuplot(out.path(""), "cycle.gp"))
        plots.insert(plots.end(), {"traction.svg", "traction.png", "slip.svg", "slip.png"});
    }
    if (slips && !result.cycle->result.loop.empty()) {
      out.write("loop.gp", loop_plot_script(scene, *result.cycle));
      if (run_gnuplot(out.path(""), "loop.gp")) plots.insert(plots.end(), {"loop.svg", "loop.png"});
    }
  }
  if (result.wear) {
    const WearStage& w = *result.wear;
    out.write("wear_history.csv", wear_history_csv(w));
    out.write("profiles.csv", profiles_csv(scene, result.normal, w));
    tables.insert(tables.end(), {"wear_history.csv", "profiles.csv"});
    if (scene.plots) {
      out.write("wear.gp", wear_plot_script(scene, result.normal, w));
      if (run_gnuplot(out.path(""), "wear.gp")) {
        plots.insert(plots.end(), {"wear_depth.svg", "wear_depth.png", "wear_pressure.svg", "wear_pressure.png"});
        if (w.records.back().cycles > 0.0) {  // against cycles, on a log axis
          if (w.records.front().stick_zone)
            plots.insert(plots.end(), {"wear_stick_zone.svg", "wear_stick_zone.png"});
          plots.insert(plots.end(), {"wear_area.svg", "wear_area.png"});
        }
      }
    }
  }
  if (!result.sifs.empty()) {
    out.write("sif.csv", sif_csv(result));
    tables.push_back("sif.csv");
    if (scene.plots) {
      out.write("crack.gp", crack_plot_script(scene, result));
      if (run_gnuplot(out.path(""), "crack.gp"))
        plots.insert(plots.end(), {"sif_I.svg", "sif_I.png", "sif_II.svg", "sif_II.png"});
    }
  }
  if (!result.stress_maps.empty()) {
    out.write("stress.csv", stress_csv(result, scene.specimen.nu));
    out.write("surface_stress.csv", surface_stress_csv(result));
    tables.insert(tables.end(), {"stress.csv", "surface_stress.csv"});
    if (scene.plots) {
      out.write("stress_map.dat", stress_map_dat(result.stress_maps.front(), scene.specimen.nu));
      out.write("stress.gp", stress_plot_script(scene, result.stress_maps.front()));
      if (run_gnuplot(out.path(""), "stress.gp"))
        plots.insert(plots.end(), {"stress_von_mises.png", "stress_sxx.png"});
    }
    if (result.fatigue) write_fatigue(scene, result, *result.fatigue, out, tables, plots);
  }
  summary["plots"] = plots;
  out.write_json("summary.json", summary);
  out.write("index.html", index_html(scene, summary, plots, tables));
  return summary;
}

}  // namespace fretwear
