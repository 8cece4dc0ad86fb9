#include "engine/sweep_plots.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "engine/plot.hpp"

namespace fretwear {
using nlohmann::json;

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string last_part(const std::string& dotted) {
  const auto dot = dotted.rfind('.');
  return dot == std::string::npos ? dotted : dotted.substr(dot + 1);
}

json value_at(const json& j, const std::string& dotted) {
  const json* node = &j;
  std::size_t from = 0;
  while (true) {
    const auto dot = dotted.find('.', from);
    const std::string k = dotted.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
    if (!node->is_object() || !node->contains(k)) return nullptr;
    node = &(*node)[k];
    if (dot == std::string::npos) return *node;
    from = dot + 1;
  }
}

double total_width(const json& zones) {
  double w = 0.0;
  for (const json& z : zones) w += z[1].get<double>() - z[0].get<double>();
  return w;
}

// What the colour map shows: the worn area when the scene wears; else, with a load cycle, the stick zones' share of
// the contact zones, zone by zone (0 in gross slip; the gaps between several zones count in neither); else (the
// normal contact alone) the peak pressure.
enum class MapQuantity { worn_area, stick_share, p_max };

double map_value(const json& s, MapQuantity q) {
  auto number_at = [&s](const char* key) {
    const json v = value_at(s, key);
    return v.is_number() ? v.get<double>() : NAN;
  };
  if (q == MapQuantity::worn_area) return number_at("wear.worn_area");
  if (q == MapQuantity::p_max) return number_at("contact.p_max");
  const json stick = value_at(s, "cycle.stick_zones"), zones = value_at(s, "contact.zones");
  if (!zones.is_array() || zones.empty()) return NAN;
  if (!stick.is_array()) return 0.0;
  return total_width(stick) / total_width(zones);
}

// The regimes of a cycle (contact/tangential_solver.hpp's to_string), each with its colour on the regime map.
struct RegimeStyle {
  const char* word;
  const char* title;
  int rgb;
};
constexpr RegimeStyle kRegimes[] = {{"partial_slip", "partial slip", 0x2c7bb6},
                                    {"reverse_slip", "reverse slip", 0xfdae61},
                                    {"gross_slip", "gross slip", 0xd7191c}};
constexpr int kNoRegimeRgb = 0xbdbdbd;  // a run that failed, or whose cycle was not solved

std::string number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("NaN"); }

// One axis of a map: where each value of a varied key sits (its value, or its index when the values are not all
// numbers) and the cell it owns, bounded halfway to its neighbours (geometrically on a log axis), so that an n-value
// key gets n cells that tile the axis.
struct Axis {
  std::vector<double> at, lo, hi;
  bool log = false;
  std::string label, tics;
  double min = 0.0, max = 1.0;
};

// Values spanning this factor or more, all positive, are drawn on a log axis.
constexpr double kLogSpan = 10.0;

Axis axis_of(const Variation& v) {
  Axis a;
  a.label = axis_label(v.key);
  const std::size_t n = v.values.size();
  const bool numeric = std::all_of(v.values.begin(), v.values.end(), [](const json& x) { return x.is_number(); });
  for (std::size_t i = 0; i < n; ++i) a.at.push_back(numeric ? v.values[i].get<double>() : double(i));
  std::vector<double> sorted = a.at;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  a.log = numeric && sorted.front() > 0.0 && sorted.back() >= kLogSpan * sorted.front();
  auto mid = [&a](double l, double r) { return a.log ? std::sqrt(l * r) : 0.5 * (l + r); };
  auto mirror = [&a](double at, double edge) { return a.log ? at * at / edge : 2.0 * at - edge; };
  for (const double x : a.at) {
    const std::size_t j = std::size_t(std::lower_bound(sorted.begin(), sorted.end(), x) - sorted.begin());
    double lo = 0.0, hi = 0.0;
    if (sorted.size() == 1) {
      lo = x == 0.0 ? -0.5 : x - 0.1 * std::abs(x);
      hi = x == 0.0 ? 0.5 : x + 0.1 * std::abs(x);
    } else {
      hi = j + 1 < sorted.size() ? mid(x, sorted[j + 1]) : mirror(x, mid(sorted[j - 1], x));
      lo = j > 0 ? mid(sorted[j - 1], x) : mirror(x, hi);
    }
    a.lo.push_back(lo);
    a.hi.push_back(hi);
  }
  a.min = *std::min_element(a.lo.begin(), a.lo.end());
  a.max = *std::max_element(a.hi.begin(), a.hi.end());
  constexpr std::size_t kMostTics = 12;  // beyond, gnuplot's own tics read better
  // A value that is a list or an object labels its tic as the JSON it is, cut to kMostTicChars.
  constexpr std::size_t kMostTicChars = 32;
  if (!numeric || n <= kMostTics) {
    for (std::size_t i = 0; i < n; ++i) {
      std::string label = numeric                    ? fmt::format("{:.4g}", a.at[i])
                          : v.values[i].is_string() ? v.values[i].get<std::string>()
                                                    : v.values[i].dump();
      if (label.size() > kMostTicChars) {
        std::size_t cut = kMostTicChars - 3;
        while (cut > 0 && (static_cast<unsigned char>(label[cut]) & 0xC0) == 0x80) --cut;  // not inside a character
        label = label.substr(0, cut) + "...";
      }
      a.tics += fmt::format("{}{} {}", i ? ", " : "", gnuplot_text(label), number(a.at[i]));
    }
  }
  return a;
}

std::string axis_commands(const Axis& a, char axis) {
  std::string s =
      fmt::format("set {}label {} noenhanced\nset {}range [{}:{}]\n", axis, gnuplot_text(a.label), axis, a.min, a.max);
  if (a.log) s += fmt::format("set logscale {}\n", axis);
  if (!a.tics.empty()) s += fmt::format("set {}tics ({}) noenhanced\n", axis, a.tics);
  return s;
}

}  // namespace

KeyUnit key_unit(const std::string& key) {
  const std::string last = last_part(key);
  if (key == "load.P" || key == "load.Q.amplitude") return {"N/m", "N_m"};
  if (key == "load.bulk_stress.amplitude" || ends_with(key, ".sigma_f")) return {"Pa", "Pa"};
  if (key == "load.delta" || ends_with(key, ".a_initial") || ends_with(key, ".a_final") || key == "grid.window" ||
      key == "effects.crack.lengths")
    return {"m", "m"};
  if (key.rfind("materials.", 0) == 0 && last == "E") return {"Pa", "Pa"};
  if (key.rfind("profile.", 0) == 0) {
    if (last == "angle_deg") return {"°", "deg"};
    for (const char* length : {"R", "a", "b", "amplitude", "wavelength", "offset_x"})
      if (last == length) return {"m", "m"};
  }
  for (const char* coefficient : {"k", "alpha", "k_pad", "k_specimen", "alpha_pad", "alpha_specimen"})
    if (key == std::string("effects.wear.") + coefficient) return {"1/Pa", "per_Pa"};
  return {};
}

std::string axis_label(const std::string& key) {
  if (key == "load.Q.ratio") return "load.Q.ratio, Q/(fP)";
  const KeyUnit u = key_unit(key);
  return u.label.empty() ? key : fmt::format("{} ({})", key, u.label);
}

std::string column_name(const std::string& key) {
  const KeyUnit u = key_unit(key);
  return u.suffix.empty() ? key : key + "_" + u.suffix;
}

void write_sweep_maps(const SweepResult& result, const std::string& scene_name, bool wears, bool life, bool plots,
                      const OutputFolder& out) {
  const auto& variations = result.variations;
  if (variations.empty()) return;
  const Axis x = axis_of(variations[0]);
  const bool two = variations.size() > 1;
  const Axis y = two ? axis_of(variations[1]) : Axis{};
  const std::size_t n0 = variations[0].values.size(), n1 = two ? variations[1].values.size() : 1;

  MapQuantity quantity = wears ? MapQuantity::worn_area : MapQuantity::p_max;
  for (const SweepRun& run : result.runs)
    if (!wears && run.status == 0 && run.summary.contains("cycle")) quantity = MapQuantity::stick_share;

  // One row per cell: the runs whose further varied keys (beyond the second) take their first value.
  std::string dat;
  bool regimes = false;
  for (std::size_t k = 0; k < std::min(result.runs.size(), n0 * n1); ++k) {
    const SweepRun& run = result.runs[k];
    const std::size_t i = k % n0, j = k / n0;
    const double value = run.status == 0 ? map_value(run.summary, quantity) : NAN;
    const json regime = run.status == 0 ? value_at(run.summary, "cycle.regime") : json(nullptr);
    int rgb = kNoRegimeRgb;
    for (const RegimeStyle& r : kRegimes)
      if (regime.is_string() && regime.get<std::string>() == r.word) rgb = r.rgb, regimes = true;
    dat += fmt::format("{} {} {} {} {} {} {} {} {}\n", number(x.at[i]), two ? number(y.at[j]) : "0", number(value),
                       number(x.lo[i]), number(x.hi[i]), two ? number(y.lo[j]) : "-0.5",
                       two ? number(y.hi[j]) : "0.5", rgb, regime.is_string() ? regime.get<std::string>() : "none");
    if (i + 1 == n0) dat += "\n";
  }
  out.write("sweep_map.dat", dat);
  if (life) {  // the life against the first varied key, a row per run (NaN where it failed or never fails)
    std::string lives;
    for (std::size_t k = 0; k < result.runs.size(); ++k) {
      const SweepRun& run = result.runs[k];
      const json total = run.status == 0 ? value_at(run.summary, "life.total_cycles") : json(nullptr);
      const json init = run.status == 0 ? value_at(run.summary, "life.initiation.cycles") : json(nullptr);
      lives += fmt::format("{} {} {}\n", number(x.at[k % n0]), total.is_number() ? number(total.get<double>()) : "NaN",
                           init.is_number() ? number(init.get<double>()) : "NaN");
    }
    out.write("sweep_life.dat", lives);
  }
  if (!plots) return;

  std::string gp = "# The sweep's maps. Re-run with: gnuplot sweep.gp\n"
                   "# sweep_map.dat, a row per run: x y value x_lo x_hi y_lo y_hi regime_rgb regime (the cell of a run\n"
                   "# spans [x_lo, x_hi] x [y_lo, y_hi]); sweep_life.dat: x total_cycles initiation_cycles\n";
  const std::string frame = axis_commands(x, 'x') + (two ? axis_commands(y, 'y') : "unset ytics\nset yrange [-0.5:0.5]\n");
  const int height = two ? 600 : 260;
  if (regimes) {
    gp += fmt::format("reset\nset title \"{}: regime of the cycle\" noenhanced\n", scene_name) + frame;
    gp += "set style fill solid 1.0 border lc rgb 'white'\nset key outside right top\n";
    std::string plot = "plot 'sweep_map.dat' using 1:2:4:5:6:7:8 with boxxyerror lc rgb variable notitle";
    for (const RegimeStyle& r : kRegimes)
      plot += fmt::format(", keyentry with boxes fc rgb '#{:06x}' title '{}'", r.rgb, r.title);
    plot += fmt::format(", keyentry with boxes fc rgb '#{:06x}' title 'no result'\n", kNoRegimeRgb);
    gp += svg_and_png("sweep_regime", plot, 900, height);
  }

  // The colour map, in a perceptual palette (viridis: Smith and van der Walt 2015); over one key, a line.
  const std::string what = quantity == MapQuantity::worn_area     ? "worn area (m²)"
                           : quantity == MapQuantity::stick_share ? "stick zones / contact zones, in width"
                                                                  : "peak pressure p_max (Pa)";
  gp += fmt::format("reset\nset grid\nset title \"{}: {}\" noenhanced\n", scene_name, what);
  if (two) {
    gp += frame + fmt::format("set cblabel '{}'\nset style fill solid 1.0 noborder\n", what);
    gp += "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', 4 '#fde725')\n";
    gp += svg_and_png("sweep_map", "plot 'sweep_map.dat' using 1:2:4:5:6:7:3 with boxxyerror lc palette notitle\n",
                      900, 600);
  } else {
    gp += axis_commands(x, 'x') + fmt::format("set ylabel '{}'\n", what);
    gp += svg_and_png("sweep_map", "plot 'sweep_map.dat' using 1:3 with linespoints pt 7 lw 2 lc rgb '#21918c' "
                                   "notitle\n",
                      900, 600);
  }

  if (life) {  // the life against the first varied key (a run that never fails is left out)
    gp += fmt::format("reset\nset grid\nset logscale y\nset format y '10^{{%T}}'\nset title \"{}: life "
                      "(runs that never fail are left out)\" noenhanced\n",
                      scene_name);
    gp += axis_commands(x, 'x') + "set ylabel 'cycles'\nset key left top\n";
    gp += svg_and_png("sweep_life", "plot 'sweep_life.dat' using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' "
                                    "title 'total life', '' using 1:3 with linespoints pt 6 lw 1.5 dt 2 "
                                    "lc rgb '#1f77b4' title 'initiation'\n",
                      900, 600);
  }
  out.write("sweep.gp", gp);
  run_gnuplot(out.path(""), "sweep.gp");
}

}  // namespace fretwear
