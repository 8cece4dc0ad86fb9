#include "engine/life_stage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "contact/centre_stress.hpp"
#include "contact/fatigue_measures.hpp"
#include "contact/subsurface_stress.hpp"
#include "engine/crack_stage.hpp"
#include "engine/plot.hpp"
#include "engine/stress_stage.hpp"

namespace fretwear {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kLayerDepths = 24;    // depths of the SWT layer from the surface to ℓ + the deepest wear
constexpr int kMaxLayerPoints = 512;  // surface points across the layer: every cell centre on the default grids
constexpr int kStressDepths = 48;     // depths of the stresses the line method averages, to ℓ below the layer

// One state of the run: from `cycles` on, its loads at the top and the bottom, and the specimen's wear per cell.
struct State {
  double cycles = 0.0;
  std::vector<Phase> phases;
  std::vector<double> w_specimen;  // m per cell
};

// The states' loads are the stress stage's records (record_phases), with the specimen's share of each record's wear.
std::vector<State> life_states(const Scene& scene, const NormalResult& normal, const CycleStage& cycle,
                               const WearStage* wear) {
  std::vector<State> states;
  const std::vector<RecordPhases> records = record_phases(scene, normal, &cycle, wear);
  const double share = wear ? 1.0 - scene.wear->pad_fraction : 0.0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    State s{records[k].cycles, records[k].phases, std::vector<double>(normal.state.p.size(), 0.0)};
    if (wear && !wear->records[k].w_specimen.empty())  // the specimen's wear in its own frame (gross slip)
      s.w_specimen = wear->records[k].w_specimen;
    else if (wear)
      for (std::size_t i = 0; i < s.w_specimen.size(); ++i) s.w_specimen[i] = share * wear->records[k].w[i];
    states.push_back(std::move(s));
  }
  return states;
}

// SWT_ℓ on its critical plane over a layer of points under the surface, row-major (y outer): at depth y_j below
// surface point x_i, the SWT of the stress history averaged over the line [y_j, y_j + ℓ] below it (the point's own
// stress when ℓ = 0). The stresses are averaged, not the SWT values: at a square-root singular edge σ ∝ r^(−1/2), so
// the mean stress over the line converges as the grid is refined, while SWT ∝ 1/r and its mean grows like ln(ℓ/h).
struct SwtLayer {
  std::vector<double> x, y;
  std::vector<SwtResult> points;
  const SwtResult& at(std::size_t i, std::size_t j) const { return points[j * x.size() + i]; }
};

// The mean of a stress column sampled at depths ys over [d, d + ell] (trapezoids, linear between the samples and to
// the ends; held past the last sample).
Stress line_mean(const std::vector<double>& ys, const std::vector<Stress>& column, double d, double ell) {
  auto at = [&](double depth) {
    if (ys.size() == 1) return column[0];
    depth = std::clamp(depth, ys.front(), ys.back());
    std::size_t j = std::size_t(std::upper_bound(ys.begin(), ys.end(), depth) - ys.begin());
    j = std::clamp<std::size_t>(j, 1, ys.size() - 1);
    const double t = (depth - ys[j - 1]) / (ys[j] - ys[j - 1]);
    const Stress& a = column[j - 1];
    const Stress& b = column[j];
    return Stress{a.xx + t * (b.xx - a.xx), a.yy + t * (b.yy - a.yy), a.xy + t * (b.xy - a.xy)};
  };
  if (ell <= 0.0 || ys.size() == 1) return at(d);
  // Trapezoids from d through the samples inside the line to d + ℓ, as line_average() sums them (contact/
  // fatigue_life.hpp), without building the line's samples: this runs for every point of every layer.
  Stress sum{}, v0 = at(d);
  double y0 = 0.0;
  auto segment = [&](double y1, const Stress& v1) {
    const double w = y1 - y0, f = (y1 - y0) / (y1 - y0);
    sum.xx += 0.5 * (v0.xx + (v0.xx + (v1.xx - v0.xx) * f)) * w;
    sum.yy += 0.5 * (v0.yy + (v0.yy + (v1.yy - v0.yy) * f)) * w;
    sum.xy += 0.5 * (v0.xy + (v0.xy + (v1.xy - v0.xy) * f)) * w;
    y0 = y1, v0 = v1;
  };
  const auto first = std::upper_bound(ys.begin(), ys.end(), d);
  for (auto it = first; it != ys.end() && *it < d + ell; ++it) segment(*it - d, column[std::size_t(it - ys.begin())]);
  segment(ell, at(d + ell));
  return {sum.xx / ell, sum.yy / ell, sum.xy / ell};
}

// cells: the grid cells whose centres are x; stresses: the state's top and bottom stresses at every cell centre and
// at the depths ys (CentreStresses, rows of grid.n), down to y.back() + ℓ.
SwtLayer swt_layer(const Grid& grid, const std::vector<int>& cells, const std::vector<double>& x,
                   const std::vector<double>& y, const std::vector<double>& ys, const std::vector<Stress> (&stresses)[2],
                   double ell, const Material& specimen, PlaneState plane) {
  SwtLayer layer{x, y, std::vector<SwtResult>(x.size() * y.size())};
  const std::size_t n = std::size_t(grid.n);
  std::vector<Stress> a(ys.size()), b(ys.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t k = 0; k < ys.size(); ++k)
      a[k] = stresses[0][k * n + std::size_t(cells[i])], b[k] = stresses[1][k * n + std::size_t(cells[i])];
    for (std::size_t j = 0; j < y.size(); ++j) {
      const Stress pair[2] = {line_mean(ys, a, y[j], ell), line_mean(ys, b, y[j], ell)};
      layer.points[j * x.size() + i] = swt_critical_plane(pair, specimen, plane);
    }
  }
  return layer;
}

// SWT_ℓ at column i, depth d: linear between the layer's depths, held past them.
double swt_line(const SwtLayer& layer, std::size_t i, double d) {
  if (layer.y.size() == 1) return layer.at(i, 0).swt;
  d = std::clamp(d, layer.y.front(), layer.y.back());
  std::size_t j = std::size_t(std::upper_bound(layer.y.begin(), layer.y.end(), d) - layer.y.begin());
  j = std::clamp<std::size_t>(j, 1, layer.y.size() - 1);
  const double t = (d - layer.y[j - 1]) / (layer.y[j] - layer.y[j - 1]);
  return layer.at(i, j - 1).swt + t * (layer.at(i, j).swt - layer.at(i, j - 1).swt);
}

// The specimen's wear at x (m), of the cell holding x.
double wear_at(const Grid& grid, const std::vector<double>& w, double x) {
  const int i = std::clamp(int(std::floor((x - grid.x_min) / grid.h())), 0, grid.n - 1);
  return w[std::size_t(i)];
}

struct Initiation {
  LifeInitiationResult result;
  std::size_t state = 0;
};

// The layer's surface points x (the centres of the grid's cells `cells`), the depths y of its SWT_ℓ, and the depths
// ys of the stresses averaged over ℓ.
struct LayerAxes {
  std::vector<int> cells;
  std::vector<double> x, y, ys;
};

// The surface points and depths of the layer: cell centres over the contact and half a half-width beyond (at most
// kMaxLayerPoints), depths to ℓ plus the deepest wear of the specimen, graded as (j/J)² toward the surface, where
// the stresses of a contact edge vary fastest (like r^(−1/2) at a singular one); the stresses to ℓ further down.
LayerAxes layer_axes(const Grid& grid, const NormalResult& normal, const std::vector<State>& states, double ell) {
  const double xl = normal.zones.front().left.x, xr = normal.zones.back().right.x, half = 0.5 * (xr - xl);
  std::vector<int> cells;
  for (int i = 0; i < grid.n; ++i)
    if (grid.x(i) >= xl - 0.5 * half && grid.x(i) <= xr + 0.5 * half) cells.push_back(i);
  if (cells.size() > std::size_t(kMaxLayerPoints)) {
    std::vector<int> thinned;
    for (int k = 0; k < kMaxLayerPoints; ++k)
      thinned.push_back(cells[std::size_t(k) * (cells.size() - 1) / (kMaxLayerPoints - 1)]);
    cells = std::move(thinned);
  }
  std::vector<double> x;
  for (int i : cells) x.push_back(grid.x(i));
  double w_max = 0.0;
  for (const State& s : states)
    for (double w : s.w_specimen) w_max = std::max(w_max, w);
  const double depth = ell + w_max;
  auto graded = [](double to, int n) {
    std::vector<double> v{0.0};
    if (to > 0.0)
      for (int j = 1; j <= n; ++j) v.push_back(to * double(j * j) / double(n * n));
    return v;
  };
  LayerAxes axes{cells, x, graded(depth, kLayerDepths), {}};
  axes.ys = ell > 0.0 ? graded(depth + ell, kStressDepths) : axes.y;
  return axes;
}

Initiation initiate(const Scene& scene, const Grid& grid, const NormalResult& normal,
                    const std::vector<State>& states) {
  const LifeInitiation& li = *scene.life->initiation;
  const InitiationConstants k{li.sigma_f, li.b, li.eps_f, li.c, scene.specimen.E};
  const double ell = li.critical_distance;
  const LayerAxes axes = layer_axes(grid, normal, states, ell);
  const std::vector<double>& x = axes.x;
  const std::vector<double>& y = axes.y;
  // The stresses of every state at every cell centre and depth ys, by FFT: the kernels' spectra once for all states.
  const CentreStresses centre_stresses(grid, axes.ys);
  std::vector<SwtLayer> layers;
  for (const State& s : states) {
    const std::vector<Stress> stresses[2] = {
        centre_stresses(SurfaceTractions{grid, s.phases[0].p, s.phases[0].q, s.phases[0].sigma_bulk}),
        centre_stresses(SurfaceTractions{grid, s.phases[1].p, s.phases[1].q, s.phases[1].sigma_bulk})};
    layers.push_back(swt_layer(grid, axes.cells, x, y, axes.ys, stresses, ell, scene.specimen, scene.plane));
  }
  // The damage rate (per cycle) at column i, depth d below the surface of state j.
  auto rate = [&](std::size_t j, std::size_t i, double d) {
    const double n = initiation_life(k, swt_line(layers[j], i, d));
    return std::isinf(n) ? 0.0 : 1.0 / n;
  };
  auto wear = [&](std::size_t j, std::size_t i) { return wear_at(grid, states[j].w_specimen, x[i]); };
  // Miner's damage at N (in the interval of state kk) of the material point at depth d below that state's surface.
  auto damage = [&](std::size_t kk, std::size_t i, double d, double N) {
    double D = 0.0;
    for (std::size_t j = 0; j < kk; ++j)
      D += (states[j + 1].cycles - states[j].cycles) * rate(j, i, d + wear(kk, i) - wear(j, i));
    return D + (N - states[kk].cycles) * rate(kk, i, d);
  };
  Initiation best;
  best.result.cycles = kInfinity;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t kk = 0; kk < states.size(); ++kk) {
      const double D0 = damage(kk, i, 0.0, states[kk].cycles);
      const double r = rate(kk, i, 0.0);
      const double end = kk + 1 < states.size() ? states[kk + 1].cycles : kInfinity;
      double N = kInfinity;
      if (D0 >= 1.0) N = states[kk].cycles;
      else if (r > 0.0 && states[kk].cycles + (1.0 - D0) / r <= end) N = states[kk].cycles + (1.0 - D0) / r;
      if (std::isinf(N)) continue;
      if (N < best.result.cycles * (1.0 - 1e-12)) {  // ties: the first, the trailing side
        best.result.cycles = N;
        best.result.x = x[i];
        best.state = kk;
      }
      break;
    }
  }
  // The site: the largest SWT_ℓ at the surface of the last state when it never starts.
  if (std::isinf(best.result.cycles)) {
    best.state = states.size() - 1;
    double top = -kInfinity;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (const double v = swt_line(layers.back(), i, 0.0); v > top) top = v, best.result.x = x[i];
  }
  const std::size_t site = std::size_t(std::find(x.begin(), x.end(), best.result.x) - x.begin());
  best.result.swt = swt_line(layers[best.state], site, 0.0);
  best.result.angle_deg = layers[best.state].at(site, 0).theta * 180.0 / std::numbers::pi;
  best.result.state_cycles = states[best.state].cycles;
  // The damage map: at the initiation, or at cycles_max when it never starts.
  const double N_map = std::min(best.result.cycles, scene.life->cycles_max);
  best.result.map_x = x;
  best.result.map_y = y;
  for (std::size_t j = 0; j < y.size(); ++j)
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double d = y[j] - wear(best.state, i);  // original depth y₀ to the depth below the worn surface
      best.result.damage.push_back(d < 0.0 ? std::numeric_limits<double>::quiet_NaN()
                                           : damage(best.state, i, d, N_map));
    }
  for (std::size_t i = 0; i < x.size(); ++i) best.result.map_surface.push_back(wear(best.state, i));
  return best;
}

// The SIF tables of every state at kTableLengths lengths over [a_initial, a_final].
std::vector<SifTable> sif_tables(const Grid& grid, const std::vector<State>& states, const CrackEffect& crack) {
  std::vector<SifTable> tables;
  for (const State& s : states) {
    const std::vector<SifSet> sets = crack_sifs(grid, s.phases, crack.x, crack, s.cycles);
    std::vector<double> KI_top, KI_bottom, KII_top, KII_bottom;
    for (const CrackSif& k : sets[0].result.sifs) KI_top.push_back(k.K_I), KII_top.push_back(k.K_II);
    for (const CrackSif& k : sets[1].result.sifs) KI_bottom.push_back(k.K_I), KII_bottom.push_back(k.K_II);
    tables.emplace_back(crack.lengths, KI_top, KI_bottom, KII_top, KII_bottom);
  }
  return tables;
}

}  // namespace

SwtResult line_swt(const Grid& grid, const std::vector<Phase>& phases, double x, double d, double ell,
                   const Material& specimen, PlaneState plane) {
  std::vector<double> ys{0.0};
  for (int j = 1; j <= kStressDepths; ++j) ys.push_back((d + ell) * double(j * j) / double(kStressDepths * kStressDepths));
  if (d + ell <= 0.0) ys.resize(1);
  const SurfaceTractions top{grid, phases[0].p, phases[0].q, phases[0].sigma_bulk};
  const SurfaceTractions bottom{grid, phases[1].p, phases[1].q, phases[1].sigma_bulk};
  const std::vector<Stress> a = stress_along_depth(top, x, ys), b = stress_along_depth(bottom, x, ys);
  const Stress pair[2] = {line_mean(ys, a, d, ell), line_mean(ys, b, d, ell)};
  return swt_critical_plane(pair, specimen, plane);
}

LifeStage run_life(const Scene& scene, const Model& model, const NormalResult& normal, const CycleStage& cycle,
                   const WearStage* wear, const StopCheck& stop) {
  const LifeEffect& effect = *scene.life;
  const std::vector<State> states = life_states(scene, normal, cycle, wear);
  LifeStage stage;
  double N_start = 0.0;
  if (effect.initiation) {
    stage.initiation = initiate(scene, model.grid, normal, states).result;
    stage.initiation->singular = singular_edges(normal, &cycle, wear, {}).at(stage.initiation->x, 0.0);
    N_start = stage.initiation->cycles;
  }
  stop_point(stop, {"life", 1.0, 2.0, "parts (initiation, growth)"});
  if (!effect.growth) {
    stage.total_cycles = N_start;
    stage.fate = N_start <= effect.cycles_max ? "initiation" : "runout";
    return stage;
  }
  if (!(N_start <= effect.cycles_max)) {  // it never starts a crack within cycles_max
    stage.total_cycles = kInfinity;
    stage.fate = "runout";
    return stage;
  }
  // Where the crack grows: the crack effect's place and angle, or normal to the surface at the initiation site.
  CrackEffect crack = scene.crack ? *scene.crack : CrackEffect{};
  crack.at = CrackPosition::x;
  crack.x = scene.crack ? crack_position(*scene.crack, normal) : stage.initiation->x;
  stage.crack_x = crack.x;
  stage.crack_angle_deg = crack.angle_deg;
  stage.a_initial = effect.a_initial();
  stage.a_final = effect.growth->a_final;
  crack.lengths.clear();
  for (int j = 0; j < kTableLengths; ++j)
    crack.lengths.push_back(stage.a_initial * std::pow(stage.a_final / stage.a_initial, double(j) / (kTableLengths - 1)));
  const std::vector<SifTable> tables = sif_tables(model.grid, states, crack);
  std::vector<GrowthState> growth_states;
  for (std::size_t k = 0; k < states.size(); ++k) growth_states.push_back({states[k].cycles, &tables[k]});
  const LifeGrowth& lg = *effect.growth;
  const GrowthConstants g{lg.C,
                          lg.m,
                          lg.dK_th,
                          lg.el_haddad ? el_haddad_length(lg.dK_th, lg.fatigue_limit) : 0.0,
                          lg.K_c.value_or(0.0),
                          lg.mode == GrowthMode::equivalent};
  // The growth starts at the initiation's count, in the state in force then.
  stage.propagation = grow_crack(g, stage.a_initial, stage.a_final, N_start, growth_states, effect.cycles_max - N_start);
  stage.fate = to_string(stage.propagation->fate);
  stage.final_length = stage.propagation->final_length;
  stage.total_cycles = N_start + stage.propagation->cycles;
  if (stage.propagation->fate == GrowthFate::runout) stage.total_cycles = kInfinity;
  return stage;
}

nlohmann::json summarise_life(const Scene& scene, const LifeStage& life) {
  using nlohmann::json;
  auto count = [](double n) { return std::isfinite(n) ? json(n) : json(nullptr); };
  json out = {{"fate", life.fate}, {"total_cycles", count(life.total_cycles)}, {"cycles_max", scene.life->cycles_max}};
  if (life.initiation) {
    const LifeInitiationResult& i = *life.initiation;
    out["initiation"] = {{"cycles", count(i.cycles)},
                         {"swt", i.swt},
                         {"x", i.x},
                         {"y", i.y},
                         {"angle_deg", i.angle_deg},
                         {"method", scene.life->initiation->critical_distance > 0.0 ? "line" : "point"},
                         {"critical_distance", scene.life->initiation->critical_distance},
                         {"state_cycles", i.state_cycles},
                         {"singular", i.singular}};
  }
  if (life.propagation) {
    out["propagation"] = {{"cycles", count(life.propagation->cycles)},
                          {"x", life.crack_x},
                          {"angle_deg", life.crack_angle_deg},
                          {"a_initial", life.a_initial},
                          {"a_final", life.a_final},
                          {"steps", life.propagation->path.size()}};
    out["final_length"] = life.final_length;
  }
  return out;
}

namespace {

std::string num(double v) { return csv_number(v); }

std::string growth_csv(const GrowthResult& g) {
  std::string s = "cycles,a_m,dK_I_Pa_m05,dK_II_Pa_m05,da_dN_m\n";
  for (const GrowthPoint& p : g.path)
    s += fmt::format("{},{},{},{},{}\n", num(p.N), num(p.a), num(p.dK_I), num(p.dK_II), num(p.da_dN));
  return s;
}

std::string damage_csv(const LifeInitiationResult& i) {
  std::string s = "x_m,y_m,damage\n";
  for (std::size_t j = 0; j < i.map_y.size(); ++j)
    for (std::size_t k = 0; k < i.map_x.size(); ++k)
      s += fmt::format("{},{},{}\n", num(i.map_x[k]), num(i.map_y[j]), num(i.damage[j * i.map_x.size() + k]));
  return s;
}

// gnuplot's pm3d wants one block per depth.
std::string damage_dat(const LifeInitiationResult& i) {
  std::string s;
  for (std::size_t j = 0; j < i.map_y.size(); ++j) {
    for (std::size_t k = 0; k < i.map_x.size(); ++k)
      s += fmt::format("{} {} {}\n", num(i.map_x[k]), num(i.map_y[j]), num(i.damage[j * i.map_x.size() + k]));
    s += "\n";
  }
  return s;
}

std::string life_plot_script(const Scene& scene, const LifeStage& life) {
  std::string s = "# The fatigue life. Re-run with: gnuplot life.gp\nset datafile separator ','\nset grid\n";
  if (life.propagation) {
    s += fmt::format("set title \"{}: crack growth from {:.3g} µm (fate: {})\" noenhanced\n", scene.name,
                     life.a_initial * 1e6, life.fate);
    s += "set xlabel 'cycles'\nset ylabel 'crack length a (µm)'\nset key left top\n";
    s += svg_and_png("crack_growth", "plot 'crack_growth.csv' skip 1 using 1:($2*1e6) with lines lw 2 lc rgb "
                                     "'#d62728' title 'a(N), Paris'\n");
  }
  if (life.initiation && life.initiation->map_y.size() > 1) {
    const LifeInitiationResult& i = *life.initiation;
    s += "reset\nset datafile separator ','\nset view map\nset pm3d map\n" + colour_map_settings("damage D (Miner)");
    s += fmt::format("set title \"{}: Miner's damage {} (red: the site, x = {:.4g} mm; black: the worn surface)\" noenhanced\n", scene.name,
                     i.cycles <= scene.life->cycles_max ? fmt::format("at initiation, N = {:.4g}", i.cycles)
                                                        : fmt::format("after {:.4g} cycles", scene.life->cycles_max),
                     i.x * 1e3);
    s += fmt::format("set xlabel 'x (mm)'\nset ylabel 'depth below the unworn surface (µm)'\nset yrange [{}:0]\n",
                     i.map_y.back() * 1e6);
    // The worn surface then, over the removed layer (left blank: its material went with the wear debris).
    std::string surface;
    double site_depth = 0.0;
    for (std::size_t k = 0; k < i.map_x.size(); ++k)
      if (i.map_x[k] == i.x) site_depth = i.map_surface[k];
    for (std::size_t k = 0; k < i.map_x.size(); ++k)
      surface += fmt::format("{} {} 0\n", num(i.map_x[k] * 1e3), num(i.map_surface[k] * 1e6));
    s += "set datafile separator whitespace\n";
    s += png_only("life_damage", fmt::format("splot 'life_damage.dat' using ($1*1e3):($2*1e6):3 with pm3d notitle, "
                                             "'-' using 1:2:3 with lines lw 2 lc rgb 'black' notitle, "
                                             "'-' using 1:2:3 with points pt 7 ps 1.5 lc rgb 'red' notitle\n"
                                             "{}e\n{} {} 0\ne\n",
                                             surface, i.x * 1e3, site_depth * 1e6));
  }
  return s;
}

}  // namespace

void write_life(const Scene& scene, const LifeStage& life, OutputFolder& out, Written& written) {
  if (life.propagation) {
    out.write("crack_growth.csv", growth_csv(*life.propagation));
    written.tables.push_back("crack_growth.csv");
  }
  if (life.initiation) {
    out.write("damage.csv", damage_csv(*life.initiation));
    written.tables.push_back("damage.csv");
  }
  if (!scene.plots) return;
  if (life.initiation && life.initiation->map_y.size() > 1) out.write("life_damage.dat", damage_dat(*life.initiation));
  out.write("life.gp", life_plot_script(scene, life));
  if (!run_gnuplot(out.path(""), "life.gp")) return;
  if (life.propagation) written.plots.insert(written.plots.end(), {"crack_growth.svg", "crack_growth.png"});
  if (life.initiation && life.initiation->map_y.size() > 1) written.plots.push_back("life_damage.png");
}

}  // namespace fretwear
