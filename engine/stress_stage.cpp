#include "engine/stress_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/plot.hpp"

namespace fretwear {
namespace {

std::string num(double v) { return csv_number(v); }

std::string stress_csv(const std::vector<StressMap>& maps, double nu) {
  std::string s = "phase,x_m,y_m,sxx_Pa,syy_Pa,sxy_Pa,von_mises_Pa,s1_Pa,s2_Pa\n";
  for (const StressMap& m : maps)
    for (std::size_t j = 0; j < m.y.size(); ++j)
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const Stress& t = m.sigma[j * m.x.size() + i];
        const Principal pr = principal(t);
        s += fmt::format("{},{},{},{},{},{},{},{},{}\n", m.phase, num(m.x[i]), num(m.y[j]), num(t.xx), num(t.yy),
                         num(t.xy), num(von_mises(t, nu)), num(pr.s1), num(pr.s2));
      }
  return s;
}

std::string surface_stress_csv(const std::vector<StressMap>& maps) {
  std::string s = "phase,x_m,sxx_Pa\n";
  for (const StressMap& m : maps)
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

// stress.gp: von Mises and σxx maps under the contact at the first phase.
std::string stress_plot_script(const Scene& scene, const StressMap& m) {
  std::string s = fmt::format(R"(# Stress under the surface. Re-run with: gnuplot stress.gp
set view map
set pm3d map interpolate 0,0
set xlabel 'x (mm)'
set ylabel 'depth y (mm)'
set yrange [{}:0]
set xrange [{}:{}]
set size ratio -1
unset key
)", m.y.back() * 1e3, m.x.front() * 1e3, m.x.back() * 1e3);
  const int height = map_height(m.x.back() - m.x.front(), m.y.back());
  s += colour_map_settings("von Mises stress (MPa)");
  s += fmt::format("set title \"{}: von Mises stress at the {} of the cycle (MPa), {}\" noenhanced\n", scene.name,
                   m.phase, cycles_text(m.cycles));
  s += png_only("stress_von_mises", "splot 'stress_map.dat' using ($1*1e3):($2*1e3):($6*1e-6) with pm3d\n", 1000,
                height);
  s += "set cblabel 'σ_{xx} (MPa)'\n";
  s += fmt::format("set title \"{}: σxx at the {} of the cycle (MPa), {}\" noenhanced\n", scene.name, m.phase,
                   cycles_text(m.cycles));
  s += png_only("stress_sxx", "splot 'stress_map.dat' using ($1*1e3):($2*1e3):($3*1e-6) with pm3d\n", 1000, height);
  return s;
}

}  // namespace

namespace {

// Every stride-th of 0 … n − 1, and n − 1.
std::vector<std::size_t> strided(int n, int stride) {
  std::vector<std::size_t> k;
  for (int i = 0; i < n; i += stride) k.push_back(std::size_t(i));
  if (k.back() != std::size_t(n - 1)) k.push_back(std::size_t(n - 1));
  return k;
}

}  // namespace

// The surface stresses at x. From piecewise-constant tractions σxx is logarithmically singular at every cell boundary
// where q jumps (σxx ∼ (2/π) Δq ln|x − ξ_b|): an artefact of the discretisation, not of the contact, which makes a
// surface point's value depend on how close it falls to a boundary. The discrete field converges to the continuous
// one at the cell centres (the collocation points), so the surface row takes the values there, at the two centres
// around x, and interpolates linearly between them (σyy = −p and σxy = −q become the same interpolation of the cell
// tractions).
Stress surface_stress(const SurfaceTractions& t, const Grid& grid, double x) {
  const double u = std::clamp((x - grid.x_min) / grid.h() - 0.5, 0.0, double(grid.n - 1));
  const int k = std::min(int(std::floor(u)), grid.n - 2);
  const double w = u - k;
  const Stress a = stress_at(t, grid.x(k), 0.0), b = stress_at(t, grid.x(k + 1), 0.0);
  return {a.xx + w * (b.xx - a.xx), a.yy + w * (b.yy - a.yy), a.xy + w * (b.xy - a.xy)};
}

std::vector<StressMap> stress_maps(const Grid& grid, const std::vector<Phase>& phases, double x_lo, double x_hi,
                                   double depth, const StressEffect& effect, double cycles, int stride,
                                   const StopCheck& stop) {
  // The full map's points: nx across; the surface and ny rows at (j + ½) depth / ny below it.
  std::vector<double> x_all, y_all{0.0};
  for (int i = 0; i < effect.nx; ++i) x_all.push_back(x_lo + (x_hi - x_lo) * i / (effect.nx - 1));
  for (int j = 0; j < effect.ny; ++j) y_all.push_back(depth * (j + 0.5) / effect.ny);
  std::vector<StressMap> out;
  const double columns = double(phases.size() * strided(effect.nx, stride).size());
  double done = 0.0;
  for (const Phase& ph : phases) {
    const SurfaceTractions t{grid, ph.p, ph.q, ph.sigma_bulk};
    StressMap m;
    m.phase = ph.name;
    m.cycles = cycles;
    for (std::size_t i : strided(effect.nx, stride)) m.x.push_back(x_all[i]);
    for (std::size_t j : strided(int(y_all.size()), stride)) m.y.push_back(y_all[j]);
    m.sigma.resize(m.x.size() * m.y.size());
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      stop_point(stop, {"stress", done++, columns, "map columns"});
      auto column = stress_along_depth(t, m.x[i], m.y);
      column.front() = surface_stress(t, grid, m.x[i]);  // the first row, y = 0
      for (std::size_t j = 0; j < m.y.size(); ++j) m.sigma[j * m.x.size() + i] = column[j];
      m.surface_sxx.push_back(column.front().xx);
    }
    const double mid = 0.5 * (x_lo + x_hi);
    for (std::size_t i = 0; i < m.x.size(); ++i)
      if (m.x[i] <= mid && (i == 0 || m.surface_sxx[i] > m.trailing_peak))
        m.trailing_peak = m.surface_sxx[i], m.trailing_peak_x = m.x[i];
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<RecordPhases> record_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle,
                                        const WearStage* wear) {
  if (!wear) return {{0.0, cycle_phases(scene, normal, cycle)}};  // the cycle's own pressure with β ≠ 0 or a history
  std::vector<RecordPhases> out;
  for (const WearRecord& rec : wear->records) out.push_back({rec.cycles, cycle_phases(scene, rec.p, &rec.q)});
  return out;
}

std::vector<Phase> final_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle,
                                const WearStage* wear) {
  return record_phases(scene, normal, cycle, wear).back().phases;
}

std::vector<StressMap> run_stress(const Scene& scene, const Model& model, const NormalResult& normal,
                                  const CycleStage* cycle, const WearStage* wear, const StopCheck& stop) {
  const double xl = normal.zones.front().left.x, xr = normal.zones.back().right.x, half = 0.5 * (xr - xl);
  const double depth = scene.stress->depth > 0.0 ? scene.stress->depth : half;
  const std::vector<RecordPhases> states = record_phases(scene, normal, cycle, wear);
  auto stride = [&](std::size_t k) { return k + 1 == states.size() ? 1 : kRecordStride; };
  // The columns of every state's maps, counted for `stop` across the stage.
  auto state_columns = [&](std::size_t k) {
    return double(states[k].phases.size() * strided(scene.stress->nx, stride(k)).size());
  };
  double columns = 0.0, before = 0.0;
  for (std::size_t k = 0; k < states.size(); ++k) columns += state_columns(k);
  const StopCheck counted = offset_parts(stop, &before, columns);
  std::vector<StressMap> out;
  for (std::size_t k = 0; k < states.size(); ++k) {
    auto maps = stress_maps(model.grid, states[k].phases, xl - 0.5 * half, xr + 0.5 * half, depth, *scene.stress,
                            states[k].cycles, stride(k), counted);
    before += state_columns(k);
    out.insert(out.end(), std::make_move_iterator(maps.begin()), std::make_move_iterator(maps.end()));
  }
  stop_point(stop, {"stress", columns, columns, "map columns"});
  return out;
}

std::vector<StressMap> last_record(const std::vector<StressMap>& maps) {
  std::vector<StressMap> out;
  for (const StressMap& m : maps)
    if (m.cycles == maps.back().cycles) out.push_back(m);
  return out;
}

bool SingularEdges::at(double px, double py) const {
  if (py > reach) return false;
  return std::any_of(x.begin(), x.end(), [&](double e) { return std::abs(px - e) <= reach; });
}

SingularEdges singular_edges(const NormalResult& normal, const CycleStage* cycle, const WearStage* wear,
                             const std::vector<StressMap>& maps) {
  SingularEdges e;
  if (normal.edge_intensity.left) e.x.push_back(normal.zones.front().left.x);
  if (normal.edge_intensity.right) e.x.push_back(normal.zones.back().right.x);
  const bool at_limit = wear && wear->asymptote.unavailable.empty() && wear->records.back().fraction >= kNearLimit;
  if (at_limit && cycle)
    for (const Interval& z : cycle->result.stick_zones) e.x.insert(e.x.end(), {z.first, z.second});
  // Two cells of the grid, or two spacings of the map (across, and from the surface to the next row) if coarser:
  // the map's largest value near a singular edge falls on one of its points next to the edge.
  double map_dx = 0.0, map_dy = 0.0;  // no maps: the grid alone
  if (!maps.empty()) {
    const StressMap& m = maps.back();
    map_dx = m.x.size() > 1 ? m.x[1] - m.x[0] : 0.0;
    map_dy = m.y.size() > 1 ? m.y[1] - m.y[0] : 0.0;
  }
  e.reach = 2.0 * std::max({normal.grid.h(), map_dx, map_dy});
  return e;
}

nlohmann::json summarise_stress(const Scene& scene, const std::vector<StressMap>& all, const WearStage* wear,
                                const SingularEdges& singular) {
  using nlohmann::json;
  const std::vector<StressMap> maps = last_record(all);
  json phases = json::object();
  for (const StressMap& m : maps) {
    double vm = 0.0, vm_x = 0.0, vm_y = 0.0;
    for (std::size_t j = 0; j < m.y.size(); ++j)
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const double v = von_mises(m.sigma[j * m.x.size() + i], scene.specimen.nu);
        if (v > vm) vm = v, vm_x = m.x[i], vm_y = m.y[j];
      }
    phases[m.phase] = {{"surface_sxx_trailing_peak", m.trailing_peak},
                       {"surface_sxx_trailing_peak_x", m.trailing_peak_x},
                       {"surface_sxx_trailing_peak_singular", singular.at(m.trailing_peak_x, 0.0)},
                       {"von_mises_max", vm},
                       {"von_mises_max_at", {vm_x, vm_y}},
                       {"von_mises_max_singular", singular.at(vm_x, vm_y)}};
  }
  return {{"phases", phases},
          {"cycles", wear ? wear->records.back().cycles : 0.0},
          {"window", {maps.front().x.front(), maps.front().x.back()}},
          {"depth", maps.front().y.back()}};
}

void write_stress(const Scene& scene, const std::vector<StressMap>& all, OutputFolder& out, Written& written) {
  const std::vector<StressMap> maps = last_record(all);
  out.write("stress.csv", stress_csv(maps, scene.specimen.nu));
  out.write("surface_stress.csv", surface_stress_csv(maps));
  written.tables.insert(written.tables.end(), {"stress.csv", "surface_stress.csv"});
  if (!scene.plots) return;
  out.write("stress_map.dat", stress_map_dat(maps.front(), scene.specimen.nu));
  out.write("stress.gp", stress_plot_script(scene, maps.front()));
  if (run_gnuplot(out.path(""), "stress.gp"))
    written.plots.insert(written.plots.end(), {"stress_von_mises.png", "stress_sxx.png"});
}

}  // namespace fretwear
