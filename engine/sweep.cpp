#include "engine/sweep.hpp"

#include <atomic>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "engine/deferred_signals.hpp"
#include "engine/folder.hpp"
#include "engine/output.hpp"
#include "engine/plot.hpp"
#include "engine/preflight.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"

namespace fretwear {
namespace fs = std::filesystem;
using nlohmann::json;

Variation parse_variation(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError(fmt::format("--vary \"{}\": give key=v1,v2,... (a dotted scene key such as load.Q.ratio)", text));
  Variation v{text.substr(0, eq), {}};
  std::stringstream values(text.substr(eq + 1));
  for (std::string item; std::getline(values, item, ',');) {
    if (item.empty()) throw InputError(fmt::format("--vary \"{}\": an empty value", text));
    const json parsed = json::parse(item, nullptr, false);
    v.values.push_back(parsed.is_discarded() ? json(item) : parsed);
  }
  return v;
}

namespace {

void set_path(json& j, const std::string& dotted, const json& value) {
  json* node = &j;
  std::stringstream parts(dotted);
  std::vector<std::string> keys;
  for (std::string k; std::getline(parts, k, '.');) keys.push_back(k);
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    if (!node->contains(keys[i]) || !(*node)[keys[i]].is_object()) (*node)[keys[i]] = json::object();
    node = &(*node)[keys[i]];
  }
  (*node)[keys.back()] = value;
}

std::string word(const json& v) {
  std::string s = v.is_string() ? v.get<std::string>() : v.dump();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return s;
}

// The summary's scalars worth a column.
// Several contact or stick zones appear one pair each in contact.zones and cycle.stick_zones.
const char* kColumns[] = {"contact.p_max",      "contact.extent",          "contact.zones",
                          "cycle.regime",       "cycle.stick_zone",        "cycle.stick_zones",
                          "cycle.dissipated_energy", "cycle.slip_max",     "wear.worn_area",
                          "wear.max_depth",     "wear.fraction_of_asymptote", "crack.K_I_max",
                          "life.initiation.cycles", "life.propagation.cycles", "life.total_cycles", "life.fate",
                          "timings.total"};

json get(const json& j, const std::string& dotted) {
  const json* node = &j;
  std::stringstream parts(dotted);
  for (std::string k; std::getline(parts, k, '.');) {
    if (!node->is_object() || !node->contains(k)) return nullptr;
    node = &(*node)[k];
  }
  return *node;
}

// The total width of a list of zones [[l, r], ...] (m).
double total_width(const json& zones) {
  double w = 0.0;
  for (const json& z : zones) w += z[1].get<double>() - z[0].get<double>();
  return w;
}

// The fretting map's value of a run: the stick zones' share of the contact zones, zone by zone (0 in gross slip; the
// gaps between several zones count in neither), or the worn area when the scene wears.
double map_value(const json& s, bool wears) {
  if (wears) return get(s, "wear.worn_area").is_number() ? get(s, "wear.worn_area").get<double>() : NAN;
  const json stick = get(s, "cycle.stick_zones"), zones = get(s, "contact.zones");
  if (!zones.is_array() || zones.empty()) return NAN;
  if (!stick.is_array()) return 0.0;
  return total_width(stick) / total_width(zones);
}

}  // namespace

SweepResult run_sweep(const fs::path& scene_file, const std::vector<Variation>& variations, int jobs,
                      std::ostream* progress) {
  std::ifstream in(scene_file);
  const Scene base_scene = load_scene(scene_file);  // the base must be valid on its own
  json base = json::parse(in, nullptr, false);
  SweepResult result;
  result.variations = variations;
  result.dir = output_folder(base_scene, OutputCommand::sweep);

  // Every combination, validated before anything runs.
  std::vector<Scene> scenes;
  std::vector<std::string> problems;
  std::size_t total = 1;
  for (const auto& v : variations) total *= v.values.size();
  for (std::size_t k = 0; k < total; ++k) {
    json j = base;
    SweepRun run;
    std::size_t rest = k;
    std::string name = base_scene.name;
    for (const auto& v : variations) {
      const json& value = v.values[rest % v.values.size()];
      rest /= v.values.size();
      set_path(j, v.key, value);
      run.values.push_back(value);
      name += "__" + v.key + "_" + word(value);
    }
    if (name.size() > 128) name = fmt::format("{}__run{}", base_scene.name, k);
    j["name"] = name;
    j["output"] = {{"dir", (result.dir / "runs" / name).string()}, {"plots", base_scene.plots}};
    try {
      scenes.push_back(parse_scene(j));
      for (const auto& p : physics_problems(scenes.back())) problems.push_back(name + ": " + p);
    } catch (const SceneError& e) {
      for (const auto& p : e.problems()) problems.push_back(name + ": " + p);
    }
    run.name = name;
    result.runs.push_back(run);
  }
  const std::vector<std::string> target = output_dir_problems(base_scene, scene_file, OutputCommand::sweep);
  problems.insert(problems.begin(), target.begin(), target.end());
  if (!problems.empty()) throw SceneError(problems);

  OutputFolder out(result.dir, OutputCommand::sweep);
  fs::create_directories(out.path("runs"));
  std::atomic<std::size_t> next{0};
  std::mutex report;
  auto worker = [&] {
    for (std::size_t k; (k = next++) < scenes.size();) {
      SweepRun& run = result.runs[k];
      Scene scene = scenes[k];
      scene.output_dir = out.path("runs") / run.name;
      try {
        OutputFolder folder(scene.output_dir);
        const RunResult r = Simulation(scene).run();
        run.summary = write_results(scene, r, folder);
        folder.commit();
      } catch (const ConvergenceError& e) {
        run.status = 3, run.message = e.what();
      } catch (const InputError& e) {
        run.status = 2, run.message = e.what();
      }
      std::lock_guard lock(report);
      if (progress)
        *progress << fmt::format("  [{}/{}] {}: {}\n", k + 1, scenes.size(), run.name,
                                 run.status == 0 ? "done" : run.message) << std::flush;
    }
  };
  std::vector<std::jthread> pool;
  for (int t = 0; t < std::max(1, jobs); ++t) pool.emplace_back(worker);
  pool.clear();  // joins

  // The table: the varied values, the status, and the summary's scalars.
  std::string csv;
  for (const auto& v : variations) csv += v.key + ",";
  csv += "status,name";
  for (const char* c : kColumns) csv += std::string(",") + c;
  csv += "\n";
  json table = json::array();
  for (const SweepRun& run : result.runs) {
    for (const auto& v : run.values) csv += (v.is_string() ? v.get<std::string>() : v.dump()) + ",";
    csv += fmt::format("{},{}", run.status, run.name);
    json row = {{"name", run.name}, {"status", run.status}, {"values", run.values}};
    for (const char* c : kColumns) {
      const json v = get(run.summary, c);
      std::string cell = v.is_null() ? "" : v.is_string() ? v.get<std::string>() : v.dump();
      if (v.is_array()) cell = "\"" + cell + "\"";
      csv += "," + cell;
      row[c] = v;
    }
    if (!run.message.empty()) row["message"] = run.message;
    csv += "\n";
    table.push_back(row);
  }
  out.write("sweep.csv", csv);
  out.write_json("sweep.json", {{"scene", base_scene.name}, {"runs", table}});

  // The fretting map over the first two varied keys (a line over one).
  if (base_scene.plots && !variations.empty()) {
    const bool wears = base_scene.wear.has_value();
    const std::string what = wears ? "worn area (m²)" : "stick zones / contact zones, in width";
    std::string dat;
    const std::size_t n0 = variations[0].values.size();
    for (std::size_t k = 0; k < result.runs.size(); ++k) {
      const auto& run = result.runs[k];
      const double value = run.status == 0 ? map_value(run.summary, wears) : NAN;
      const bool numeric = std::all_of(run.values.begin(), run.values.end(), [](const json& v) { return v.is_number(); });
      if (!numeric) continue;
      dat += fmt::format("{} {} {}\n", run.values[0].get<double>(),
                         variations.size() > 1 ? run.values[1].get<double>() : 0.0,
                         std::isfinite(value) ? fmt::format("{}", value) : std::string("NaN"));
      if ((k + 1) % n0 == 0) dat += "\n";
    }
    out.write("sweep_map.dat", dat);
    std::string gp = "# The fretting map. Re-run with: gnuplot sweep.gp\nset grid\n";
    gp += fmt::format("set title \"{}: {}\" noenhanced\nset xlabel '{}' noenhanced\n", base_scene.name, what,
                      variations[0].key);
    std::string plot;
    if (variations.size() > 1) {
      gp += fmt::format("set ylabel '{}' noenhanced\nset view map\nset pm3d map\nset palette rgbformulae 33,13,10\n"
                        "set cblabel '{}'\n", variations[1].key, what);
      plot = "splot 'sweep_map.dat' using 1:2:3 with pm3d notitle, '' using 1:2:3 with points pt 7 ps 0.6 lc rgb "
             "'black' notitle\n";
    } else {
      gp += fmt::format("set ylabel '{}'\n", what);
      plot = "plot 'sweep_map.dat' using 1:3 with linespoints pt 7 lw 2 notitle\n";
    }
    gp += "set terminal svg size 900,600 dynamic font 'sans,12'\nset output 'sweep_map.svg'\n" + plot;
    gp += "set terminal pngcairo size 900,600 font 'sans,11'\nset output 'sweep_map.png'\nreplot\nunset output\n";
    if (base_scene.life) {  // the life against the first varied key (a run that never fails is left out)
      std::string life;
      for (const auto& run : result.runs) {
        const json life_total = run.status == 0 ? get(run.summary, "life.total_cycles") : json(nullptr);
        const json init = run.status == 0 ? get(run.summary, "life.initiation.cycles") : json(nullptr);
        if (!run.values[0].is_number()) continue;
        life += fmt::format("{} {} {}\n", run.values[0].get<double>(),
                            life_total.is_number() ? fmt::format("{}", life_total.get<double>()) : std::string("NaN"),
                            init.is_number() ? fmt::format("{}", init.get<double>()) : std::string("NaN"));
      }
      out.write("sweep_life.dat", life);
      gp += fmt::format("reset\nset grid\nset logscale y\nset format y '10^{{%T}}'\nset title \"{}: life "
                        "(runs that never fail are left out)\" noenhanced\nset xlabel '{}' noenhanced\n"
                        "set ylabel 'cycles'\nset key left top\n",
                        base_scene.name, variations[0].key);
      gp += svg_and_png("sweep_life", "plot 'sweep_life.dat' using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' "
                                      "title 'total life', '' using 1:3 with linespoints pt 6 lw 1.5 dt 2 "
                                      "lc rgb '#1f77b4' title 'initiation'\n",
                        900, 600);
    }
    out.write("sweep.gp", gp);
    run_gnuplot(out.path(""), "sweep.gp");
  }
  const DeferredStopSignals hold;
  out.commit();
  return result;
}

}  // namespace fretwear
