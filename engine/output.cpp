#include "engine/output.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include <fmt/format.h>

namespace fretwear {
namespace fs = std::filesystem;
using nlohmann::json;

OutputFolder::OutputFolder(fs::path dir) : dir_(std::move(dir)) {
  staging_ = dir_;
  staging_ += fmt::format(".partial-{}", ::getpid());
  std::error_code ec;
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec || ::access(staging_.c_str(), W_OK) != 0) {
    if (!ec) fs::remove_all(staging_, ec);
    throw SceneError({fmt::format("output.dir: cannot write into \"{}\" ({}); give a folder you can write to",
                                  dir_.string(), ec ? ec.message() : "permission denied")});
  }
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void OutputFolder::write(const std::string& file, const std::string& content) const {
  std::ofstream out(path(file), std::ios::binary);
  out << content;
  if (!out) throw Error("cannot write " + path(file).string());
}

void OutputFolder::write_json(const std::string& file, const json& j) const { write(file, j.dump(2) + "\n"); }

void OutputFolder::commit() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
  fs::rename(staging_, dir_, ec);
  if (ec) throw Error(fmt::format("cannot move the results into {}: {}", dir_.string(), ec.message()));
  committed_ = true;
}

bool run_gnuplot(const fs::path& dir, const std::string& script_file) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::cerr << "fretwear: gnuplot not found; plots skipped (install it: apt-get install gnuplot-nox)\n";
    return false;
  }
  const std::string cmd = fmt::format("cd '{}' && gnuplot '{}' > gnuplot.log 2>&1", dir.string(), script_file);
  if (std::system(cmd.c_str()) != 0) {
    std::cerr << "fretwear: gnuplot failed on " << (dir / script_file).string() << "; see gnuplot.log\n";
    return false;
  }
  std::error_code ec;
  if (fs::file_size(dir / "gnuplot.log", ec) == 0) fs::remove(dir / "gnuplot.log", ec);
  return true;
}

namespace {

std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.10g}", v);
}

std::string contact_csv(const NormalResult& n) {
  std::string s = n.reference ? "x_m,gap0_m,p_Pa,gap_m,p_closed_form_Pa\n" : "x_m,gap0_m,p_Pa,gap_m\n";
  for (int i = 0; i < n.grid.n; ++i) {
    s += fmt::format("{},{},{},{}", num(n.grid.x(i)), num(n.g0[i]), num(n.state.p[i]), num(n.state.gap[i]));
    if (n.reference) s += "," + num(n.reference->p_cell[i]);
    s += "\n";
  }
  return s;
}

std::string pressure_plot_script(const Scene& scene, const NormalResult& n) {
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
  s += "set terminal svg size 900,560 dynamic font 'sans,12'\nset output 'pressure.svg'\n" + plot + "\n";
  s += "set terminal pngcairo size 900,560 font 'sans,11'\nset output 'pressure.png'\nreplot\nunset output\n";
  return s;
}

std::string cycle_csv(const NormalResult& n, const CycleResult& c) {
  std::string s = "x_m,p_Pa,q_top_Pa,q_unloaded_Pa,q_bottom_Pa,q_reloaded_Pa,slip_range_m,slip_per_cycle_m,"
                  "energy_density_J_m2\n";
  for (int i = 0; i < n.grid.n; ++i)
    s += fmt::format("{},{},{},{},{},{},{},{},{}\n", num(n.grid.x(i)), num(n.state.p[i]), num(c.q_top[i]),
                     num(c.q_unloaded[i]), num(c.q_bottom[i]), num(c.q_reloaded[i]), num(c.slip_range[i]),
                     num(c.slip_travelled[i]), num(c.energy_density[i]));
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
  s += fmt::format("set title \"{}: shear traction at the four phases (Q/fP = {:.3g}, f = {:.3g}; grey: stick zone)\" "
                   "noenhanced\n", scene.name, st.Q_max / (f * scene.P), f);
  s += "set ylabel 'shear traction q (MPa)'\n";
  s += fmt::format(
      "plot 'cycle.csv' skip 1 using ($1*1e3):({0}*$2*1e-6) with lines dt 3 lc rgb '#888888' title '±f p', "
      "'' skip 1 using ($1*1e3):(-{0}*$2*1e-6) with lines dt 3 lc rgb '#888888' notitle, "
      "'' skip 1 using ($1*1e3):($3*1e-6) with lines lw 1.5 lc rgb '#d62728' title 'top (+Q)', "
      "'' skip 1 using ($1*1e3):($4*1e-6) with lines lw 1.5 lc rgb '#ff7f0e' title 'unloaded (Q = 0)', "
      "'' skip 1 using ($1*1e3):($5*1e-6) with lines lw 1.5 lc rgb '#1f77b4' title 'bottom (-Q)', "
      "'' skip 1 using ($1*1e3):($6*1e-6) with lines lw 1.5 dt 2 lc rgb '#2ca02c' title 'reloaded (Q = 0)'\n",
      f);
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

void flatten(const json& j, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& rows) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, rows);
  } else {
    rows.emplace_back(prefix, j.is_number_float() ? fmt::format("{:.6g}", j.get<double>()) : j.dump());
  }
}

std::string index_html(const Scene& scene, const json& summary, const std::vector<std::string>& plots) {
  std::vector<std::pair<std::string, std::string>> rows;
  flatten(summary, "", rows);
  std::string s = fmt::format(R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>fretwear: {0}</title>
<style>body{{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}}
table{{border-collapse:collapse}}td{{border-bottom:1px solid #ddd;padding:2px 10px;font-family:monospace}}</style>
</head><body><h1>{0}</h1>
<p>fretwear {1}. Files: <a href="summary.json">summary.json</a>, <a href="scene.resolved.json">scene.resolved.json</a>,
<a href="contact.csv">contact.csv</a>.</p>
)", scene.name, summary.value("version", ""));
  for (const auto& plot : plots)
    if (plot.ends_with(".svg")) s += fmt::format("<p><img src=\"{0}\" alt=\"{0}\" width=\"900\"></p>\n", plot);
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
  out.write_json("scene.resolved.json", resolved.to_json());
  out.write("contact.csv", contact_csv(result.normal));
  const bool slips = result.cycle && result.cycle->result.regime != Regime::gross_slip;
  if (slips) out.write("cycle.csv", cycle_csv(result.normal, result.cycle->result));
  std::vector<std::string> plots;
  if (scene.plots) {
    out.write("pressure.gp", pressure_plot_script(scene, result.normal));
    if (run_gnuplot(out.path(""), "pressure.gp")) plots.insert(plots.end(), {"pressure.svg", "pressure.png"});
    if (slips) {
      out.write("cycle.gp", cycle_plot_script(scene, result.normal, *result.cycle));
      if (run_gnuplot(out.path(""), "cycle.gp"))
        plots.insert(plots.end(), {"traction.svg", "traction.png", "slip.svg", "slip.png"});
    }
  }
  summary["plots"] = plots;
  out.write_json("summary.json", summary);
  out.write("index.html", index_html(scene, summary, plots));
  return summary;
}

}  // namespace fretwear
