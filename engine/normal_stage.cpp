#include "engine/normal_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/load_size.hpp"
#include "engine/plot.hpp"

namespace fretwear {
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

std::string pressure_plot_script(const Scene& scene, const NormalResult& n, bool coupled) {
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
  if (coupled)  // β ≠ 0: the pressure the shear leaves at the top and the bottom of the cycle
    plot += ", 'cycle.csv' skip 1 using ($1*1e3):($10*1e-6) with steps lw 1.2 lc rgb '#d62728' title 'top of the "
            "cycle (coupled)', '' skip 1 using ($1*1e3):($11*1e-6) with steps lw 1.2 dt 2 lc rgb '#2ca02c' "
            "title 'bottom of the cycle (coupled)'";
  s += "set terminal svg size 900,560 dynamic font 'sans,12'\nset output 'pressure.svg'\n" + plot + "\n";
  s += "set terminal pngcairo size 900,560 font 'sans,11'\nset output 'pressure.png'\nreplot\nunset output\n";
  return s;
}


// The closed form of an untilted cylinder, rounded punch or sharp punch, on the grid.
std::optional<Reference> closed_form_reference(const Scene& scene, const ElasticPair& pair, const NormalResult& r) {
  const ProfileSpec& s = scene.profile;
  if (s.tilt_rad != 0.0) return std::nullopt;
  Reference ref;
  ref.centre = s.offset_x;
  const Grid& g = r.grid;
  ref.p_cell.resize(g.n);
  if (s.type == ProfileType::cylinder) {
    const auto hz = closed_form::hertz(scene.P, pair.A(), s.R);
    ref.kind = "hertz";
    ref.half_width = hz.a;
    ref.p_max = hz.p0;
    for (int i = 0; i < g.n; ++i) ref.p_cell[i] = hz.cell_average(g.left(i) - ref.centre, g.left(i + 1) - ref.centre);
  } else if (s.type == ProfileType::flat_rounded) {
    const auto rp = closed_form::rounded_punch(scene.P, pair.A(), s.a, s.R);
    ref.kind = "rounded_punch";
    ref.half_width = rp.b;
    ref.p_max = rp.peak();
    // The pressure is smooth inside the contact: a 3-point Gauss rule gives the cell average well below the error.
    const double w[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0}, z[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    for (int i = 0; i < g.n; ++i)
      for (int k = 0; k < 3; ++k) ref.p_cell[i] += w[k] * rp.pressure(g.x(i) + 0.5 * z[k] * g.h() - ref.centre);
  } else if (s.type == ProfileType::flat) {
    const auto fp = closed_form::flat_punch(scene.P, s.b);
    ref.kind = "flat_punch";
    ref.half_width = s.b;
    for (int i = 0; i < g.n; ++i) ref.p_cell[i] = fp.cell_average(g.left(i) - ref.centre, g.left(i + 1) - ref.centre);
    ref.p_max = *std::max_element(ref.p_cell.begin(), ref.p_cell.end());
  } else {
    return std::nullopt;
  }
  if (r.zones.size() != 1) return ref;
  const Zone& z = r.zones.front();
  ref.extent_error = std::max(std::abs(z.left.x - (ref.centre - ref.half_width)),
                              std::abs(z.right.x - (ref.centre + ref.half_width))) / ref.half_width;
  ref.p_max_error = std::abs(r.p_max - ref.p_max) / ref.p_max;
  double e2 = 0.0;
  int m = 0;
  for (int i = z.first_cell + 2; i <= z.last_cell - 2; ++i, ++m) e2 += std::pow(r.state.p[i] - ref.p_cell[i], 2);
  ref.rms_error = m > 0 ? std::sqrt(e2 / m) / ref.p_max : 0.0;
  return ref;
}

// K_N at the contact's outer ends, each fitted over kEdgeFitFraction of its own zone where it is a corner (a located
// square-root fall, or a zone too short to locate, is a bounded edge).
EdgeIntensities outer_edge_intensities(const Grid& g, const std::vector<double>& p, const std::vector<Zone>& zones) {
  EdgeIntensities k;
  if (zones.empty()) return k;
  const Zone& first = zones.front();
  const Zone& last = zones.back();
  if (first.left.method == EdgeMethod::corner)
    k.left = edge_intensity(g, p, first.left.x, +1, kEdgeFitFraction * (first.right.x - first.left.x));
  if (last.right.method == EdgeMethod::corner)
    k.right = edge_intensity(g, p, last.right.x, -1, kEdgeFitFraction * (last.right.x - last.left.x));
  return k;
}

}  // namespace

NormalResult solve_normal(const Scene& scene, int cells) { return solve_normal(scene, make_model(scene, cells)); }

NormalResult solve_normal(const Scene& scene, const Model& model) {
  const ElasticPair& pair = model.pair;
  const Profile& profile = model.profile;
  NormalResult r;
  r.window = model.window;
  r.grid = model.grid;
  if (profile.symmetric_single_zone()) r.load_size_half_width = half_width_for_load(profile, pair.A(), scene.P);
  const Grid& g = r.grid;
  r.g0 = model.g0;
  NormalSolverOptions options;
  // FRETWEAR_NORMAL_MAX_ITERATIONS (tests only): the normal solve's iteration limit, so that a test can stop it short
  // of its tolerance and see the ConvergenceError reported (exit status 3, summary.json "not_converged").
  if (const char* cap = std::getenv("FRETWEAR_NORMAL_MAX_ITERATIONS"))
    options.max_iterations = std::max(1, std::atoi(cap));
  const NormalSolver solver(*model.kernel, options);
  r.summary = solver.solve(r.g0, scene.P, r.state);
  if (r.summary.termination == Termination::no_admissible_cell)
    throw InputError(fmt::format("grid.window: [{:.6g}, {:.6g}] m holds no cell where the profile's gap is finite (the "
                                 "pad is absent there, or its gap overflows); give a window around the contact",
                                 g.x_min, g.x_max));
  r.zones = locate_zones(g, r.state.p, r.g0);
  if (r.zones.empty() && r.summary.converged())
    throw ConvergenceError(fmt::format("normal contact: the solve carried the load on no cell of {} (residual {:.3g})",
                                       g.n, r.summary.residual));
  // A contact clipped by a given window is the scene's problem, whether or not the solve converged.
  if (!r.zones.empty()) {
    const bool at_left = r.zones.front().first_cell == 0 && r.zones.front().left.method != EdgeMethod::corner;
    const bool at_right = r.zones.back().last_cell == g.n - 1 && r.zones.back().right.method != EdgeMethod::corner;
    if (at_left || at_right)
      throw InputError(fmt::format("grid.window: the contact reaches the window's {} end (x = {:.6g} m) and would "
                                   "be clipped; widen grid.window or leave it out to have it chosen",
                                   at_left ? "left" : "right", at_left ? g.x_min : g.x_max));
  }
  // An asperity beyond the window that the load presses through: the contact the window holds is not the scene's.
  if (!r.zones.empty() && r.summary.converged())
    if (const auto pressed = pressed_outside(profile, *model.kernel, r.state, scene.P)) {
      const bool given = model.window.method == "given";
      throw InputError(fmt::format(
          "grid.window: {}[{:.6g}, {:.6g}] m leaves out x = {:.6g} m, where the pad touches too (the load on the "
          "window presses it {:.3g} m through there); {}",
          given ? "" : "the window chosen, ", g.x_min, g.x_max, pressed->x, -pressed->gap,
          given ? "widen grid.window to take that place in, or leave it out to have it chosen"
                : "give grid.window taking in both places"));
    }
  if (!r.summary.converged())
    throw ConvergenceError(fmt::format("normal contact: the solve stopped ({}) with residual {:.3g} above the "
                                       "tolerance {:.3g} on {} cells",
                                       to_string(r.summary.termination), r.summary.residual,
                                       solver.options().tolerance, g.n));
  for (int i = 0; i < g.n; ++i) {
    if (r.state.p[i] > r.p_max) r.p_max = r.state.p[i], r.x_p_max = g.x(i);
    r.cells_in_contact += r.state.p[i] > 0.0;
  }
  r.edge_intensity = outer_edge_intensities(g, r.state.p, r.zones);
  r.reference = closed_form_reference(scene, pair, r);
  return r;
}

std::optional<NormalResult::PeakCheck> check_peak(const Scene& scene, const NormalResult& normal) {
  constexpr int kFewestCells = 64;  // below, half the cells resolve nothing worth comparing
  if (normal.reference || p_max_singular(normal) || normal.grid.n < kFewestCells || !(normal.p_max > 0.0))
    return std::nullopt;
  Scene half = scene;
  half.window = std::pair{normal.grid.x_min, normal.grid.x_max};
  half.cells = normal.grid.n / 2;
  NormalResult coarse;
  try {
    coarse = solve_normal(half, make_model(half));
  } catch (const std::exception&) {  // a check only: the run's own solve stands
    return std::nullopt;
  }
  return NormalResult::PeakCheck{half.cells, coarse.p_max, std::abs(normal.p_max - coarse.p_max) / normal.p_max};
}

bool p_max_singular(const NormalResult& n) {
  if (n.zones.empty()) return false;
  const double reach = 2.0 * n.grid.h();
  return (n.edge_intensity.left && std::abs(n.x_p_max - n.zones.front().left.x) <= reach) ||
         (n.edge_intensity.right && std::abs(n.x_p_max - n.zones.back().right.x) <= reach);
}

nlohmann::json summarise_normal(const Scene& scene, const NormalResult& n) {
  using nlohmann::json;
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  json zones = json::array();
  for (const auto& z : n.zones) zones.push_back({z.left.x, z.right.x});
  const Edge& left = n.zones.front().left;
  const Edge& right = n.zones.back().right;
  double load = 0.0;
  for (double p : n.state.p) load += p * n.grid.h();
  auto intensity = [](const std::optional<double>& k) { return k ? json(*k) : json(nullptr); };

  json contact = {
      {"extent", {left.x, right.x}},
      {"zones", zones},
      {"edge_method", left.method == right.method ? to_string(left.method) : "mixed"},
      {"edge_methods", {to_string(left.method), to_string(right.method)}},
      {"edge_intensity", {intensity(n.edge_intensity.left), intensity(n.edge_intensity.right)}},
      {"p_max", n.p_max},
      {"x_p_max", n.x_p_max},
      {"p_max_singular", p_max_singular(n)},
      {"p_max_half_cells", n.peak_check ? json(n.peak_check->p_max) : json(nullptr)},
      {"cells_in_contact", n.cells_in_contact},
      {"load", load},
  };
  if (n.load_size_half_width) contact["load_size_half_width"] = *n.load_size_half_width;
  if (n.reference) {
    const Reference& ref = *n.reference;
    contact["closed_form"] = {{"kind", ref.kind},       {"half_width", ref.half_width},
                              {"p_max", ref.p_max},     {"extent_error", ref.extent_error},
                              {"p_max_error", ref.p_max_error}, {"rms_error", ref.rms_error}};
  }
  return {{"contact", contact},
          {"materials", {{"A", pair.A()}, {"E_star", pair.E_star()}, {"alpha", pair.alpha()}, {"beta", pair.beta()}}},
          {"grid",
           {{"cells", n.grid.n}, {"window", {n.grid.x_min, n.grid.x_max}}, {"window_method", n.window.method},
            {"h", n.grid.h()}}},
          {"solver",
           {{"normal",
             {{"termination", to_string(n.summary.termination)},
              {"iterations", n.summary.iterations},
              {"residual", n.summary.residual},
              {"seconds", n.summary.seconds},
              {"brief", n.summary.brief()}}}}}};
}

void write_normal(const Scene& scene, const NormalResult& normal, const std::vector<double>& p_top,
                  OutputFolder& out, Written& written) {
  out.write("contact.csv", contact_csv(normal));
  written.tables.push_back("contact.csv");
  if (!scene.plots) return;
  out.write("pressure.gp", pressure_plot_script(scene, normal, !p_top.empty()));
  if (run_gnuplot(out.path(""), "pressure.gp"))
    written.plots.insert(written.plots.end(), {"pressure.svg", "pressure.png"});
}

}  // namespace fretwear
