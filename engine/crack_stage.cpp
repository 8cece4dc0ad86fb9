#include "engine/crack_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/plot.hpp"

namespace fretwear {
namespace {

std::string num(double v) { return csv_number(v); }

std::string sif_csv(const std::vector<SifSet>& sifs) {
  std::string s = "cycles,phase,length_m,K_I_Pa_sqrt_m,K_I_open_Pa_sqrt_m,K_II_Pa_sqrt_m,closed\n";
  for (const SifSet& set : sifs)
    for (const CrackSif& k : set.result.sifs)
      s += fmt::format("{},{},{},{},{},{},{}\n", num(set.cycles), set.phase, num(k.l), num(k.K_I), num(k.K_I_open),
                       num(k.K_II), k.closed ? 1 : 0);
  return s;
}

// crack.gp: K_I and K_II against crack length, top (solid) and bottom (dashed) of the cycle, every state labelled
// by its cycle count, the initial and the last in thick lines.
std::string crack_plot_script(const Scene& scene, const std::vector<SifSet>& sifs, double x, bool worn) {
  std::vector<double> states;
  for (const SifSet& set : sifs)
    if (states.empty() || states.back() != set.cycles) states.push_back(set.cycles);
  const std::string hi = scene.tangential ? "top" : "loaded", lo = scene.tangential ? "bottom" : "loaded";
  std::string s = fmt::format(R"(# Stress intensity factors. Re-run with: gnuplot crack.gp
set datafile separator ','
set xlabel 'crack length l (µm)'
set grid
set key outside right top
set title "{}: crack at x = {:.4g} mm ({}), {}" noenhanced
)", scene.name, x * 1e3, scene.crack->at == CrackPosition::x ? "given" : to_string(scene.crack->at),
                              scene.crack->angle_deg == 90.0
                                  ? std::string("normal to the surface")
                                  : fmt::format("at {:g}° to the surface, face friction {:g}", scene.crack->angle_deg,
                                                scene.crack->face_friction));
  // Every state's curve in the key by its cycle count; with two phases, the top solid and the bottom dashed, said
  // once by two black key entries.
  for (const char* mode : {"K_{I}", "K_{II}"}) {
    const int col = std::string(mode) == "K_{I}" ? 4 : 6;
    std::string plot = "plot ";
    if (lo != hi)
      plot += fmt::format("NaN with lines lw 2 lc rgb '#000000' title '{0}', NaN with lines lw 2 dt 2 "
                          "lc rgb '#000000' title '{1}', ",
                          hi, lo);
    for (std::size_t k = 0; k < states.size(); ++k) {
      const bool ends = k == 0 || k + 1 == states.size();
      const double t = states.size() > 1 ? double(k) / double(states.size() - 1) : 0.0;
      auto line = [&](const std::string& phase, const char* dash, bool titled) {
        const std::string title = worn ? cycles_label(states[k]) : std::string("initial");
        return fmt::format("'sif.csv' skip 1 using ($1 == {} && strcol(2) eq '{}' ? $3*1e6 : 1/0):(${}*1e-6) with "
                           "linespoints pt 7 ps 0.4 lw {} {} lc rgb '{}' {}, ",
                           num(states[k]), phase, col, ends ? 2.0 : 1.0, dash, ramp(t),
                           titled ? fmt::format("title '{}{}'", title, lo != hi ? "" : ", " + phase)
                                  : std::string("notitle"));
      };
      plot += line(hi, "", true);
      if (lo != hi) plot += line(lo, "dt 2", false);
    }
    plot.resize(plot.size() - 2);
    s += fmt::format("set ylabel '{} (MPa·√m)'\n", mode);
    s += svg_and_png(std::string("sif_") + (col == 4 ? "I" : "II"), plot + "\n");
  }
  return s;
}

}  // namespace

std::vector<SifSet> crack_sifs(const Grid& grid, const std::vector<Phase>& phases, double x_c,
                               const CrackEffect& effect, double cycles) {
  CrackSolverOptions options;
  options.n_quadrature = effect.quadrature;
  const CrackSolver solver(options, CrackSpec{effect.angle_deg, effect.face_friction});
  std::vector<SifSet> out;
  for (const Phase& ph : phases) {
    const SurfaceTractions t{grid, ph.p, ph.q, ph.sigma_bulk};
    out.push_back({ph.name, cycles, solver.solve(t, x_c, effect.lengths)});
  }
  return out;
}

std::optional<QuadratureCheck> quadrature_check(const Scene& scene, const Model& model, const NormalResult& normal,
                                                const CycleStage* cycle, const WearStage* wear,
                                                const std::vector<SifSet>& sifs) {
  CrackEffect half = *scene.crack;
  const int n = scene.crack->quadrature;
  half.quadrature = n / 2 >= 2 ? n / 2 : 2 * n;  // 2 or 3 points: against twice as many
  if (sifs.empty()) return std::nullopt;
  const double x = crack_position(*scene.crack, normal);
  const double last = sifs.back().cycles;
  const std::vector<Phase> phases = wear ? cycle_phases(scene, wear->records.back().p, &wear->records.back().q)
                                         : cycle_phases(scene, normal, cycle);
  QuadratureCheck check{scene.crack->quadrature, half.quadrature, true, 0.0, false, 0.0, ""};
  std::vector<SifSet> coarse;
  try {
    coarse = crack_sifs(model.grid, phases, x, half, last);
  } catch (const ConvergenceError&) {
    check.settled = false;  // the face contact cycles on the other points: no estimate from them
    return check;
  }
  double scale = 0.0;
  for (const SifSet& set : sifs)
    if (set.cycles == last)
      for (const CrackSif& k : set.result.sifs) scale = std::max({scale, std::abs(k.K_I), std::abs(k.K_II)});
  if (!(scale > 0.0)) return std::nullopt;
  for (const SifSet& c : coarse)
    for (const SifSet& set : sifs) {
      if (set.cycles != last || set.phase != c.phase) continue;
      for (std::size_t i = 0; i < set.result.sifs.size(); ++i) {
        const CrackSif &fine = set.result.sifs[i], &k = c.result.sifs[i];
        const double d = std::max(std::abs(fine.K_I - k.K_I), std::abs(fine.K_II - k.K_II)) / scale;
        check.opens_or_closes = check.opens_or_closes || fine.closed != k.closed;
        if (d > check.change) check.change = d, check.at_l = fine.l, check.phase = set.phase;
      }
    }
  return check;
}

double crack_position(const CrackEffect& effect, const NormalResult& normal) {
  switch (effect.at) {
    case CrackPosition::trailing_edge: return normal.zones.front().left.x;
    case CrackPosition::leading_edge: return normal.zones.back().right.x;
    case CrackPosition::x: return effect.x;
  }
  return effect.x;
}

std::vector<SifSet> run_crack(const Scene& scene, const Model& model, const NormalResult& normal,
                              const CycleStage* cycle, const WearStage* wear, const StopCheck& stop) {
  const CrackEffect& c = *scene.crack;
  const double x = crack_position(c, normal);
  if (!wear) {
    stop_point(stop, "crack");
    return crack_sifs(model.grid, cycle_phases(scene, normal, cycle), x, c, 0.0);
  }
  std::vector<SifSet> sifs;
  const double records = double(wear->records.size());
  double done = 0.0;
  for (const WearRecord& rec : wear->records) {
    stop_point(stop, {"crack", done++, records, "records"});
    auto sets = crack_sifs(model.grid, cycle_phases(scene, rec.p, &rec.q), x, c, rec.cycles);
    sifs.insert(sifs.end(), sets.begin(), sets.end());
  }
  stop_point(stop, {"crack", records, records, "records"});
  return sifs;
}

nlohmann::json summarise_crack(const Scene& scene, const std::vector<SifSet>& sifs, double x) {
  using nlohmann::json;
  const double last_cycles = sifs.back().cycles;
  auto column = [&](const std::string& phase, auto member) {
    json v = json::array();
    for (const SifSet& set : sifs)
      if (set.cycles == last_cycles && set.phase == phase)
        for (const CrackSif& k : set.result.sifs) v.push_back(member(k));
    return v;
  };
  const std::string hi = scene.tangential ? "top" : "loaded", lo = scene.tangential ? "bottom" : "loaded";
  const CrackEffect& c = *scene.crack;
  return {{"at", c.at == CrackPosition::x ? json(c.x) : json(to_string(c.at))},
          {"x", x},
          {"angle_deg", c.angle_deg},
          {"quadrature", c.quadrature},
          {"cycles", last_cycles},
          {"lengths", c.lengths},
          {"K_I_max", column(hi, [](const CrackSif& k) { return k.K_I; })},
          {"K_I_min", column(lo, [](const CrackSif& k) { return k.K_I; })},
          {"K_II_max", column(hi, [](const CrackSif& k) { return k.K_II; })},
          {"K_II_min", column(lo, [](const CrackSif& k) { return k.K_II; })},
          {"K_I_open_max", column(hi, [](const CrackSif& k) { return k.K_I_open; })},
          {"K_I_open_min", column(lo, [](const CrackSif& k) { return k.K_I_open; })},
          {"closed_max", column(hi, [](const CrackSif& k) { return k.closed; })},
          {"closed_min", column(lo, [](const CrackSif& k) { return k.closed; })}};
}

void write_crack(const Scene& scene, const std::vector<SifSet>& sifs, double x, bool worn, OutputFolder& out,
                 Written& written) {
  out.write("sif.csv", sif_csv(sifs));
  written.tables.push_back("sif.csv");
  if (!scene.plots) return;
  out.write("crack.gp", crack_plot_script(scene, sifs, x, worn));
  if (run_gnuplot(out.path(""), "crack.gp"))
    written.plots.insert(written.plots.end(), {"sif_I.svg", "sif_I.png", "sif_II.svg", "sif_II.png"});
}

}  // namespace fretwear
