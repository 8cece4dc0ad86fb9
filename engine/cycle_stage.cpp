#include "engine/cycle_stage.hpp"

#include <algorithm>
#include <tuple>
#include <cmath>

#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/incremental_slip.hpp"
#include "contact/reference_datum.hpp"
#include "engine/plot.hpp"
#include "engine/report.hpp"

namespace fretwear {
namespace {

std::string num(double v) { return csv_number(v); }

std::string cycle_csv(const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  const bool coupled = st.plan.dissimilar();  // a history's p_top is not reported (CycleStage)
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

// The Cattaneo–Mindlin traction at the top of the cycle where PHYSICS.md has it ("Partial slip"): Hertz under force
// control, similar bodies, one steady partial-slip cycle. q = f p0 [√(1 − x²/a²) − (c/a) √(1 − (x − e)²/c²)] in
// the stick zone, f p outside it, with c/a = √(1 − Q/fP) and the shift e/a = σ/(4 f p0) of a bulk tension (Nowell
// and Hills 1987). gnuplot definitions in mm and MPa, and the term of the plot command; empty where it does not hold.
struct Mindlin {
  closed_form::Hertz h;
  closed_form::StickZone z;
};
std::optional<Mindlin> mindlin(const Scene& scene, const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  if (!n.reference || n.reference->kind != "hertz" || scene.control != LoadControl::force || !scene.history.empty() ||
      st.plan.dissimilar() || c.regime != Regime::partial_slip || !c.stick_zone)
    return std::nullopt;
  const closed_form::Hertz h{n.reference->half_width, n.reference->p_max};
  return Mindlin{h, closed_form::hertz_stick(h, st.Q_max / (st.f * scene.P), st.f, st.bulk_stress)};
}

std::pair<std::string, std::string> mindlin_traction(const Scene& scene, const NormalResult& n, const CycleStage& st) {
  const std::optional<Mindlin> m = mindlin(scene, n, st);
  if (!m) return {};
  const closed_form::Hertz& h = m->h;
  const closed_form::StickZone& z = m->z;
  const std::string defs = fmt::format(
      "cm_x0 = {}; cm_a = {}; cm_p0 = {}; cm_f = {}; cm_c = {}; cm_e = {}\nset samples 2000\n"
      "cm_q(x) = abs(x - cm_x0) >= cm_a ? 1/0 : cm_f*cm_p0*(sqrt(1 - ((x - cm_x0)/cm_a)**2) - "
      "(abs(x - cm_x0 - cm_e) < cm_c ? (cm_c/cm_a)*sqrt(1 - ((x - cm_x0 - cm_e)/cm_c)**2) : 0))\n",
      num(n.reference->centre * 1e3), num(h.a * 1e3), num(h.p0 * 1e-6), num(st.f), num(z.c * 1e3), num(z.centre * 1e3));
  const std::string term = fmt::format(", cm_q(x) with lines lw 2 dt 3 lc rgb '#000000' title 'Cattaneo–Mindlin, top "
                                       "(c/a = {:.4g})'",
                                       z.c / h.a);
  return {defs, term};
}

std::string cycle_plot_script(const Scene& scene, const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  std::string head = fmt::format(R"(# The load cycle. Re-run with: gnuplot cycle.gp
set datafile separator ','
set xlabel 'x (mm)'
set grid
set key below maxrows 3
set xrange [{}:{}]
)", n.grid.x_min * 1e3, n.grid.x_max * 1e3);
  std::string marks;
  if (c.stick_zone)
    marks = fmt::format("set object 1 rect from {},graph 0 to {},graph 1 back fc rgb '#eeeeee' fs solid noborder\n",
                        c.stick_zone->first * 1e3, c.stick_zone->second * 1e3);
  const double f = st.f;
  const auto [mindlin_defs, mindlin_term] = mindlin_traction(scene, n, st);
  std::string s = head + marks + mindlin_defs;
  s += fmt::format("set title \"{}: shear traction at the four phases (Q/fP = {:.3g}, f = {:.3g}; {})\" noenhanced\n",
                   scene.name, st.Q_max / (f * scene.P), f, c.stick_zone ? "grey: stick zone" : "gross slip: no stick zone");
  s += "set ylabel 'shear traction q (MPa)'\n";
  // The Coulomb bounds ±f p: with β ≠ 0 the pressure differs between the top and the bottom of the cycle.
  const std::string bounds =
      !st.plan.dissimilar()
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
      "'' skip 1 using ($1*1e3):($6*1e-6) with lines lw 1.5 dt 2 lc rgb '#2ca02c' title 'reloaded ({0} = 0)'{1}\n",
      scene.control == LoadControl::displacement ? "δ" : "Q", mindlin_term);  // the phases of the controlled quantity
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

// The fretting loop: Q against δ at the end of every increment, the first loading and then the steady cycle, top to
// top (contact/reference_datum.hpp for the datum).
std::string loop_csv(const CycleResult& c) {
  std::string s = "phase,P_N_m,Q_N_m,delta_m\n";
  for (const LoopPoint& l : c.first_loading)
    s += fmt::format("first_loading,{},{},{}\n", num(l.P), num(l.Q), num(l.delta));
  for (const LoopPoint& l : c.loop) s += fmt::format("cycle,{},{},{}\n", num(l.P), num(l.Q), num(l.delta));
  return s;
}

// The loop's closed form where PHYSICS.md has one: its area, the energy Hertz dissipates per cycle without bulk
// tension (engine/report.hpp).
std::string loop_plot_script(const Scene& scene, const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  const std::size_t n0 = c.first_loading.size();
  const std::optional<Mindlin> m = mindlin(scene, n, st);
  const std::string closed =
      m && st.bulk_stress == 0.0
          ? fmt::format(" (closed form, Hertz: {:.4g} J/m)",
                        hertz_dissipated_energy(st.f, m->h.p0, m->h.a, m->z.c, scene.profile.R))
          : std::string();
  return fmt::format(R"gp(# The fretting loop. Re-run with: gnuplot loop.gp
set datafile separator ','
set title "{0}: fretting loop, reference points {1:.4g} mm deep" noenhanced
set label 1 "dissipated per cycle {3:.4g} J/m{4}\nreference points at x = {2:.4g} mm" at graph 0.97, graph 0.06 right
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
                     c.dissipated_energy, closed) +
         svg_and_png("loop",
                     fmt::format("plot 'loop.csv' skip 1 every ::0::{0} using ($4*1e6):($3*1e-3) with lines lw 1.5 "
                                 "dt 2 lc rgb '#888888' title 'first loading', '' skip 1 every ::{1} using "
                                 "($4*1e6):($3*1e-3) with linespoints pt 7 ps 0.4 lw 1.5 lc rgb '#d62728' "
                                 "title 'steady cycle'\n",
                                 n0 - 1, n0),
                     900, 640);
}


// δ at the top of an analogy cycle: the stick zones of the steady cycle have never slipped (w = 0 there since the
// first loading), so at their cells the rigid shift is λ = (K q_top)_i + ε x_i (incremental_slip.hpp), one λ for
// every zone, and δ follows from the datum (reference_datum.hpp). In phase, the bottom is the top reversed:
// δ_max = |δ_top|. λ is read at the middle of the widest stick zone: with several, the middle of their hull may lie
// between them, where the surfaces slip or part.
void analogy_delta_max(const Model& model, const NormalResult& normal, const CyclicLoad& load,
                       const ReferenceDatum& datum, CycleResult& c) {
  if (!c.stick_zone || c.q_top.empty()) return;
  const Grid& g = model.grid;
  auto zone = *c.stick_zone;
  if (!c.stick_zones.empty())
    zone = *std::max_element(c.stick_zones.begin(), c.stick_zones.end(), [](const auto& a, const auto& b) {
      return a.second - a.first < b.second - b.first;
    });
  const double x_mid = 0.5 * (zone.first + zone.second);
  const int i = std::clamp(int(std::floor((x_mid - g.x_min) / g.h())), 0, g.n - 1);
  std::vector<double> u(g.n);
  model.kernel->apply(c.q_top, u);
  const double lambda = u[i] + load.bulk_strain * g.x(i);
  const double D0 = datum.relative_displacement(std::vector<double>(g.n, 0.0), normal.state.p);
  c.delta_max = std::abs(lambda + datum.relative_displacement(c.q_top, normal.state.p) - D0 -
                         load.bulk_strain * datum.x_c());
}

}  // namespace

std::optional<closed_form::StickZone> mindlin_stick_zone(const Scene& scene, const NormalResult& n,
                                                         const CycleStage& cycle) {
  const std::optional<Mindlin> m = mindlin(scene, n, cycle);
  if (!m) return std::nullopt;
  return m->z;
}

std::pair<double, double> reference_point(const Scene& scene, const NormalResult& normal) {
  const double left = normal.zones.front().left.x, right = normal.zones.back().right.x;
  return {0.5 * (left + right), scene.reference_depth ? *scene.reference_depth : 5.0 * (right - left)};
}

namespace {

// Each history whose P moves, marched again at half the increments (a multiple of 4): the energy's error estimate
// (CycleStage::history_energy). The scene's own (load.blocks' first block's) is the cycle the stage solved; a later
// block's is marched at both counts on the unworn contact.
void history_energies(const Scene& scene, const Model& model, const NormalResult& normal, CycleStage& stage) {
  IncrementalSlipOptions options;
  options.increments_per_cycle = scene.tangential->increments;
  if (stage.plan.dissimilar()) options.cycles = 2;
  IncrementalSlipOptions half = options;
  half.increments_per_cycle = std::max(4, options.increments_per_cycle / 8 * 4);
  if (half.increments_per_cycle >= options.increments_per_cycle) return;
  const ReferenceDatum datum(model.grid, model.pair, stage.reference_x, stage.reference_depth);
  const NormalCoupling coupling{stage.plan.beta, model.g0};
  const auto march = [&](const IncrementalSlipOptions& o, const CyclicLoad& l) {
    return IncrementalSlipSolver(*model.kernel, o)
        .solve_history(normal.state, l, model.g0, &datum, &coupling)
        .cycles.back()
        .dissipated_energy;
  };
  const auto check = [&](const CyclicLoad& l, int block, const CycleResult* solved) {
    const bool P_moves = std::any_of(l.history.begin(), l.history.end(),
                                     [&](const HistoryPoint& pt) { return pt.P != l.history.front().P; });
    if (!P_moves) return;
    const double energy = solved ? solved->dissipated_energy : march(options, l);
    if (!(energy > 0.0)) return;  // gross slip (reported without fields), or nothing slides
    stage.history_energy.push_back({block, energy, march(half, l), half.increments_per_cycle});
  };
  const CyclicLoad& load = stage.plan.load;
  if (!load.history.empty() && !stage.result.slip_range.empty())
    check(load, scene.blocks.empty() ? -1 : 0, &stage.result);
  for (std::size_t b = 1; b < scene.blocks.size(); ++b)
    if (!scene.blocks[b].history.empty()) check(block_load(scene, model.pair, scene.blocks[b]), int(b), nullptr);
}

CycleStage solve_steady_cycle(const Scene& scene, const Model& model, const CyclePlan& plan,
                              const NormalResult& normal, const StopCheck& stop) {
  CycleStage stage;
  stage.plan = plan;
  stage.f = plan.load.f;
  stage.Q_max = plan.load.Q_max;
  stage.bulk_stress = scene.bulk_stress;
  stage.sigma_top = scene.bulk_stress, stage.sigma_bottom = -scene.bulk_stress;  // in phase with Q (or δ)
  const CyclicLoad& load = plan.load;
  std::tie(stage.reference_x, stage.reference_depth) = reference_point(scene, normal);
  const ReferenceDatum datum(model.grid, model.pair, stage.reference_x, stage.reference_depth);
  if (plan.analogy_first()) {
    stage.route = "analogy";
    stage.result = TangentialSolver(*model.kernel).solve_cycle(model.g0, normal.state, normal.zones, load);
    if (stage.result.regime == Regime::partial_slip) analogy_delta_max(model, normal, load, datum, stage.result);
    if (stage.result.regime != Regime::reverse_slip) return stage;
    if (plan.asked == TangentialRoute::analogy)
      throw UnsupportedError("effects.tangential: " + stage.result.message +
                             "; the scene asks for route \"analogy\": use \"auto\" or \"incremental\"");
  }
  // The incremental route: the cycle marched in load increments with the traction as memory (reverse slip, and
  // whatever the analogy cannot do). The steady cycle of a constant amplitude is the first after the first loading
  // (the second for β ≠ 0); a history's is the first that repeats the one before it.
  IncrementalSlipOptions options;
  options.increments_per_cycle = scene.tangential->increments;
  if (plan.dissimilar()) options.cycles = 2;  // β ≠ 0: the first cycle after the first loading is not yet the steady one
  const bool history = !load.history.empty();
  // A stop asked for ends the march at its next increment. A constant amplitude marches the first loading (a
  // quarter cycle) and `cycles` cycles; a history, cycles until one repeats the one before: its total is the most it
  // may march, and where it stops short of that its last part says so (done == total, what it marched).
  if (stop) {
    const int m = options.increments_per_cycle;
    const double total = history ? double(IncrementalSlipSolver::history_increments_at_most(options, load.history))
                                 : double(m / 4 + options.cycles * m);
    options.after_increment = [&stop, total](int marched) {
      stop_point(stop, StagePart{"tangential", double(marched), total, "increments"});
    };
  }
  const IncrementalSlipSolver solver(*model.kernel, options);
  const NormalCoupling coupling{plan.beta, model.g0};
  const IncrementalResult r = history ? solver.solve_history(normal.state, load, model.g0, &datum, &coupling)
                                      : solver.solve(normal.state, load, &datum, &coupling);
  if (history && r.n_increments > 0)
    stop_point(stop, StagePart{"tangential", double(r.n_increments), double(r.n_increments), "increments"});
  stage.ran = TangentialRoute::incremental;
  stage.route = plan.analogy_first() ? "incremental (auto: the analogy found reverse slip)" : plan.incremental_because;
  if (plan.dissimilar() && r.n_increments == 0)  // gross slip under force control: nothing marched
    stage.route += fmt::format(" [beta = {:.4g}]", plan.beta);
  else if (plan.dissimilar())
    stage.route += fmt::format(" [beta = {:.4g}: {} coupling sweeps over {} increments, at most {}]", plan.beta,
                               r.n_coupling_sweeps, r.n_increments, r.max_coupling_sweeps);
  stage.result = r.cycles.back();
  if (history) stage.history_cycles = r.cycles_marched, stage.history_steady = r.repeated;
  if (plan.dissimilar() || history) stage.p_top = r.p_top, stage.p_bottom = r.p_bottom;
  if (history && !r.p_top.empty()) {  // σ from the solver's ε = σ (κ₂ + 1)/(8 μ₂), linear in σ
    const double strain_per_stress = model.pair.bulk_strain(1.0);
    stage.sigma_top = r.bulk_strain_top / strain_per_stress;
    stage.sigma_bottom = r.bulk_strain_bottom / strain_per_stress;
  }
  if ((scene.control == LoadControl::displacement || history) && !stage.result.slip_range.empty())
    stage.Q_max = stage.result.Q_peak;  // the peak Q reached
  return stage;
}

}  // namespace

CycleStage solve_cycle(const Scene& scene, const Model& model, const CyclePlan& plan, const NormalResult& normal,
                       const StopCheck& stop) {
  CycleStage stage = solve_steady_cycle(scene, model, plan, normal, stop);
  if (scene.tangential) history_energies(scene, model, normal, stage);
  return stage;
}

CycleStage solve_cycle(const Scene& scene, const Model& model, const NormalResult& normal) {
  return solve_cycle(scene, model, plan_cycle(scene, model.pair), normal);
}

std::vector<Phase> cycle_phases(const Scene& scene, const std::vector<double>& p, const std::vector<double>* q_top) {
  if (!scene.tangential) return {{"loaded", p, {}, 0.0}};
  std::vector<double> q(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) q[i] = q_top && !q_top->empty() ? (*q_top)[i] : *scene.friction * p[i];
  std::vector<double> minus(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) minus[i] = -q[i];
  return {{"top", p, q, scene.bulk_stress}, {"bottom", p, minus, -scene.bulk_stress}};
}

std::vector<Phase> cycle_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle) {
  if (!cycle || cycle->p_top.empty()) return cycle_phases(scene, normal.state.p, cycle ? &cycle->result.q_top : nullptr);
  const CycleResult& c = cycle->result;
  // Gross slip leaves no traction field (force control refuses it with β ≠ 0 or a history: engine/scene.cpp); at
  // the stick limit every cell is at ±f p.
  auto shear = [&](const std::vector<double>& q, const std::vector<double>& p, double sign) {
    if (!q.empty()) return q;
    std::vector<double> out(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) out[i] = sign * cycle->f * p[i];
    return out;
  };
  return {{"top", cycle->p_top, shear(c.q_top, cycle->p_top, 1.0), cycle->sigma_top},
          {"bottom", cycle->p_bottom, shear(c.q_bottom, cycle->p_bottom, -1.0), cycle->sigma_bottom}};
}

nlohmann::json summarise_cycle(const Scene& scene, const CycleStage& st) {
  using nlohmann::json;
  const CycleResult& c = st.result;
  auto interval = [](const std::optional<Interval>& i) { return i ? json{i->first, i->second} : json(nullptr); };
  json stick_zones = json::array();
  for (const auto& z : c.stick_zones) stick_zones.push_back({z.first, z.second});
  const bool slips = !c.slip_range.empty();  // gross slip has fields only under displacement control
  json cycle = {{"route", st.route},
                {"regime", to_string(c.regime)},
                {"Q_max", st.Q_max},
                {"Q_over_fP", st.Q_max / (st.f * scene.P)},
                {"friction", st.f},
                {"bulk_stress", st.bulk_stress},
                {"stick_zone", interval(c.stick_zone)},
                {"stick_zones", stick_zones},
                {"stick_zone_unloaded", interval(c.stick_zone_unloaded)},
                {"dissipated_energy", slips ? json(c.dissipated_energy) : json(nullptr)},
                {"slip_max", slips ? json(c.slip_max) : json(nullptr)},
                {"delta_max", c.delta_max > 0.0 ? json(c.delta_max) : json(nullptr)},
                {"control", to_string(scene.control)},
                {"reference_depth", st.reference_depth},
                {"reference_x", st.reference_x},
                {"corrective_solves", c.solves.size()}};
  if (!c.message.empty()) cycle["message"] = c.message;
  if (st.plan.dissimilar()) {  // β ≠ 0: the shear moves the pressure; under force control in gross slip, undetermined
    const auto largest = [](const std::vector<double>& p) {
      return p.empty() ? json(nullptr) : json(*std::max_element(p.begin(), p.end()));
    };
    cycle["p_max_top"] = largest(st.p_top);
    cycle["p_max_bottom"] = largest(st.p_bottom);
  }
  if (st.history_cycles > 0) {  // a load history: the cycles marched to the steady one, and whether one repeated
    cycle["history_cycles"] = st.history_cycles;
    cycle["history_steady"] = st.history_steady;
  }
  if (scene.control == LoadControl::displacement) {
    cycle["delta"] = *scene.delta;
    cycle["sliding_amplitude"] = c.sliding_amplitude;  // 0 short of gross slip
  }
  return cycle;
}

void write_cycle(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, OutputFolder& out,
                 Written& written) {
  if (cycle.result.slip_range.empty()) return;  // gross slip under force control: nothing determined to write
  out.write("cycle.csv", cycle_csv(normal, cycle));
  written.tables.push_back("cycle.csv");
  const bool loop = !cycle.result.loop.empty();
  if (loop) {
    out.write("loop.csv", loop_csv(cycle.result));
    written.tables.push_back("loop.csv");
  }
  if (!scene.plots) return;
  out.write("cycle.gp", cycle_plot_script(scene, normal, cycle));
  if (run_gnuplot(out.path(""), "cycle.gp"))
    written.plots.insert(written.plots.end(), {"traction.svg", "traction.png", "slip.svg", "slip.png"});
  if (!loop) return;
  out.write("loop.gp", loop_plot_script(scene, normal, cycle));
  if (run_gnuplot(out.path(""), "loop.gp")) written.plots.insert(written.plots.end(), {"loop.svg", "loop.png"});
}

}  // namespace fretwear
