#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/incremental_slip.hpp"
#include "contact/load_size.hpp"
#include "contact/reference_datum.hpp"
#include "engine/fatigue_stage.hpp"
#include "engine/version.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

}  // namespace

namespace {

Model model_on(const Scene& scene, const Grid& grid, const WindowChoice& window) {
  Model m{ElasticPair(scene.pad, scene.specimen, scene.plane), Profile(scene.profile), grid, window, {}, nullptr};
  m.g0.resize(m.grid.n);
  for (int i = 0; i < m.grid.n; ++i) m.g0[i] = m.profile.gap(m.grid.x(i));
  m.kernel = std::make_unique<HalfPlaneKernel>(m.grid, m.pair.A());
  return m;
}

// A wearing contact grows past its original edges up to the asymptote's worn extent (PHYSICS.md, "Wear": x_e > a),
// which the default window must cover with the same margin: compute the asymptote on a coarse, wide grid.
WindowChoice widen_for_wear(const Scene& scene, const Profile& profile, WindowChoice w) {
  constexpr int kTrialCells = 1024;
  const double centre = 0.5 * (w.x_min + w.x_max);
  double half = 0.5 * (w.x_max - w.x_min);
  for (int attempt = 0; attempt < 6; ++attempt, half *= 2.0) {
    const double lo = centre - 2.5 * half, hi = centre + 2.5 * half;
    const Model trial = model_on(scene, align_to_support(profile, lo, hi, kTrialCells), {lo, hi, "trial", 0.0});
    const NormalResult normal = solve_normal(scene, trial);
    const WearAsymptote a = wear_asymptote(scene, trial, normal);
    if (a.worn_area <= 0.0) return w;
    if (a.extent.first <= trial.grid.x_min + trial.grid.h() || a.extent.second >= trial.grid.x_max - trial.grid.h())
      continue;
    const double l = std::min(a.extent.first, normal.zones.front().left.x);
    const double r = std::max(a.extent.second, normal.zones.back().right.x);
    const double c = 0.5 * (l + r), hw = 0.5 * (r - l);
    return {std::min(w.x_min, c - 1.5 * hw), std::max(w.x_max, c + 1.5 * hw), w.method + "+wear_asymptote",
            w.expected_half_width};
  }
  throw InputError("grid: the asymptotic worn zone keeps reaching the end of a trial window 64 times the contact; "
                   "give grid.window");
}

}  // namespace

Model make_model(const Scene& scene, int cells) {
  if (cells <= 0) cells = scene.cells;
  const Profile profile(scene.profile);
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  if (scene.window) {
    return model_on(scene, Grid{scene.window->first, scene.window->second, cells},
                    {scene.window->first, scene.window->second, "given", 0.0});
  }
  WindowChoice w;
  try {
    w = choose_window(profile, pair.A(), scene.P_max(), cells);  // a history's largest P too
  } catch (const InputError& e) {
    throw InputError(fmt::format("grid.window: cannot be chosen for this profile and load ({}); give grid.window, "
                                 "or check load.P and the profile's size",
                                 e.what()));
  }
  if (scene.wear) w = widen_for_wear(scene, profile, w);
  return model_on(scene, align_to_support(profile, w.x_min, w.x_max, cells), w);
}

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
  const NormalSolver solver(*model.kernel);
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
  if (!r.summary.converged())
    throw ConvergenceError(fmt::format("normal contact: the solve stopped ({}) with residual {:.3g} above the "
                                       "tolerance {:.3g} on {} cells",
                                       to_string(r.summary.termination), r.summary.residual,
                                       solver.options().tolerance, g.n));
  for (int i = 0; i < g.n; ++i) {
    if (r.state.p[i] > r.p_max) r.p_max = r.state.p[i], r.x_p_max = g.x(i);
    r.cells_in_contact += r.state.p[i] > 0.0;
  }
  r.reference = closed_form_reference(scene, pair, r);
  return r;
}

namespace {

// δ at the top of an analogy cycle: the stick zone of the steady cycle has never slipped (w = 0 there since the first
// loading), so at its cells the rigid shift is λ = (K q_top)_i + ε x_i (incremental_slip.hpp), and δ follows from the
// datum (reference_datum.hpp). In phase, the bottom is the top reversed: δ_max = |δ_top|.
void analogy_delta_max(const Model& model, const NormalResult& normal, const CyclicLoad& load,
                       const ReferenceDatum& datum, CycleResult& c) {
  if (!c.stick_zone || c.q_top.empty()) return;
  const Grid& g = model.grid;
  const double x_mid = 0.5 * (c.stick_zone->first + c.stick_zone->second);
  const int i = std::clamp(int(std::floor((x_mid - g.x_min) / g.h())), 0, g.n - 1);
  std::vector<double> u(g.n);
  model.kernel->apply(c.q_top, u);
  const double lambda = u[i] + load.bulk_strain * g.x(i);
  const double D0 = datum.relative_displacement(std::vector<double>(g.n, 0.0), normal.state.p);
  c.delta_max = std::abs(lambda + datum.relative_displacement(c.q_top, normal.state.p) - D0 -
                         load.bulk_strain * datum.x_c());
}

}  // namespace

CycleStage solve_cycle(const Scene& scene, const Model& model, const NormalResult& normal) {
  CycleStage stage;
  stage.f = *scene.friction;
  stage.Q_max = scene.Q_max();
  stage.bulk_stress = scene.bulk_stress;
  const ElasticPair& pair = model.pair;
  const double bulk_strain = pair.bulk_strain(scene.bulk_stress);
  const bool displacement = scene.control == LoadControl::displacement;
  CyclicLoad load{scene.P, stage.Q_max, stage.f, bulk_strain, displacement ? *scene.delta : 0.0};
  for (const auto& pt : scene.history) load.history.push_back({pt[0], pt[1], pt[2], pair.bulk_strain(pt[3])});
  const bool history = !load.history.empty();
  const TangentialRoute route = scene.tangential->route;
  // The datum: reference points 10 contact half-widths (or grid.reference_depth) below the contact's centre.
  const double x_left = normal.zones.front().left.x, x_right = normal.zones.back().right.x;
  stage.reference_x = 0.5 * (x_left + x_right);
  stage.reference_depth = scene.reference_depth ? *scene.reference_depth : 5.0 * (x_right - x_left);
  const ReferenceDatum datum(model.grid, pair, stage.reference_x, stage.reference_depth);
  if (route == TangentialRoute::analogy && (displacement || history))  // parse_scene refuses it too
    throw UnsupportedError("effects.tangential: route \"analogy\" cannot run load.control \"displacement\" or "
                           "load.history; use \"auto\" or \"incremental\"");
  // Dissimilar bodies (Dundurs β ≠ 0): normal and tangential problems coupled, the incremental route only.
  const bool dissimilar = std::abs(pair.beta()) > 1e-12;
  if (route == TangentialRoute::analogy && dissimilar)  // parse_scene refuses it too
    throw UnsupportedError(fmt::format("effects.tangential: route \"analogy\" needs similar bodies, and Dundurs beta "
                                       "= {:.4g}; use \"auto\" or \"incremental\"",
                                       pair.beta()));
  if (route != TangentialRoute::incremental && !displacement && !history && !dissimilar) {
    stage.route = "analogy";
    stage.result = TangentialSolver(*model.kernel).solve_cycle(model.g0, normal.state, normal.zones, load);
    if (stage.result.regime == Regime::partial_slip) analogy_delta_max(model, normal, load, datum, stage.result);
    if (stage.result.regime != Regime::reverse_slip) return stage;
    if (route == TangentialRoute::analogy)
      throw UnsupportedError("effects.tangential: " + stage.result.message +
                             "; the scene asks for route \"analogy\": use \"auto\" or \"incremental\"");
  }
  // The incremental route: the cycle marched in load increments with the traction as memory (reverse slip, and
  // whatever the analogy cannot do). The steady cycle is the second, after the first loading and one full cycle.
  IncrementalSlipOptions options;
  options.increments_per_cycle = scene.tangential->increments;
  if (dissimilar) options.cycles = 2;  // β ≠ 0: the first cycle after the first loading is not yet the steady one
  const IncrementalSlipSolver solver(*model.kernel, options);
  const NormalCoupling coupling{dissimilar ? pair.beta() : 0.0, model.g0};
  const IncrementalResult r = history ? solver.solve_history(normal.state, load, model.g0, &datum)
                                      : solver.solve(normal.state, load, &datum, &coupling);
  stage.route = route == TangentialRoute::incremental ? "incremental"
                : displacement ? "incremental (auto: displacement control)"
                : history      ? "incremental (auto: load history)"
                : dissimilar   ? "incremental (auto: dissimilar bodies)"
                               : "incremental (auto: the analogy found reverse slip)";
  if (dissimilar)
    stage.route += fmt::format(" [beta = {:.4g}: {} coupling sweeps over {} increments, at most {}]", pair.beta(),
                               r.n_coupling_sweeps, r.n_increments, r.max_coupling_sweeps);
  stage.result = r.cycles.back();
  if (dissimilar) stage.p_top = r.p_top, stage.p_bottom = r.p_bottom;
  if ((displacement || history) && !stage.result.slip_range.empty())
    stage.Q_max = stage.result.Q_peak;  // the peak Q reached
  return stage;
}

namespace {

// The loads at the top and the bottom of the cycle (just "loaded" without one): in phase, the bottom is the top
// reversed. In gross slip the whole contact slides: q = ±f p.
std::vector<Phase> cycle_phases(const Scene& scene, const std::vector<double>& p, const std::vector<double>* q_top) {
  if (!scene.tangential) return {{"loaded", p, {}, 0.0}};
  std::vector<double> q(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) q[i] = q_top && !q_top->empty() ? (*q_top)[i] : *scene.friction * p[i];
  std::vector<double> minus(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) minus[i] = -q[i];
  return {{"top", p, q, scene.bulk_stress}, {"bottom", p, minus, -scene.bulk_stress}};
}

}  // namespace

RunResult Simulation::run(const WearControl* control) const {
  const auto t0 = std::chrono::steady_clock::now();
  RunResult result;
  const Model model = make_model(scene_);
  result.normal = solve_normal(scene_, model);
  result.timings.normal = seconds_since(t0);
  if (scene_.tangential) {
    const auto t1 = std::chrono::steady_clock::now();
    result.cycle = solve_cycle(scene_, model, result.normal);
    result.timings.tangential = seconds_since(t1);
  }
  if (scene_.wear) {
    const auto t2 = std::chrono::steady_clock::now();
    result.wear = std::make_shared<WearStage>(run_wear(scene_, model, result.normal, control ? *control : WearControl{}));
    result.timings.wear = seconds_since(t2);
  }
  if ((scene_.stress || scene_.crack) && !(result.wear && result.wear->interrupted)) {
    const NormalResult& n = result.normal;
    const std::vector<double>* q_top = result.cycle ? &result.cycle->result.q_top : nullptr;
    const std::vector<Phase> initial = cycle_phases(scene_, n.state.p, q_top);
    if (scene_.stress) {
      const auto t3 = std::chrono::steady_clock::now();
      const double xl = n.zones.front().left.x, xr = n.zones.back().right.x, half = 0.5 * (xr - xl);
      const double depth = scene_.stress->depth > 0.0 ? scene_.stress->depth : half;
      const auto& last = result.wear ? result.wear->records.back() : WearRecord{};
      const std::vector<Phase> phases =
          result.wear ? cycle_phases(scene_, last.p, &last.q) : initial;  // the final state when wearing
      result.stress_maps = stress_maps(model.grid, phases, xl - 0.5 * half, xr + 0.5 * half, depth, *scene_.stress);
      if (result.cycle)  // fatigue measures from the maps' top and bottom (engine/fatigue_stage.hpp)
        result.fatigue = run_fatigue(scene_, model.grid, phases.front(), result.stress_maps, *result.cycle,
                                     result.wear.get());
      result.timings.stress = seconds_since(t3);
    }
    if (scene_.crack) {
      const auto t4 = std::chrono::steady_clock::now();
      const CrackEffect& c = *scene_.crack;
      result.crack_x = c.at == "trailing_edge" ? n.zones.front().left.x
                       : c.at == "leading_edge" ? n.zones.back().right.x
                                                : c.x;
      if (result.wear) {
        for (const WearRecord& rec : result.wear->records) {
          auto sets = crack_sifs(model.grid, cycle_phases(scene_, rec.p, &rec.q), result.crack_x, c, rec.cycles);
          result.sifs.insert(result.sifs.end(), sets.begin(), sets.end());
        }
      } else {
        result.sifs = crack_sifs(model.grid, initial, result.crack_x, c, 0.0);
      }
      result.timings.crack = seconds_since(t4);
    }
  }
  result.timings.total = seconds_since(t0);
  result.warnings = result_warnings(scene_, result);
  return result;
}

nlohmann::json make_summary(const Scene& scene, const RunResult& result) {
  using nlohmann::json;
  const NormalResult& n = result.normal;
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  json zones = json::array();
  for (const auto& z : n.zones) zones.push_back({z.left.x, z.right.x});
  const Edge& left = n.zones.front().left;
  const Edge& right = n.zones.back().right;
  double load = 0.0;
  for (double p : n.state.p) load += p * n.grid.h();

  json contact = {
      {"extent", {left.x, right.x}},
      {"zones", zones},
      {"edge_method", left.method == right.method ? to_string(left.method) : "mixed"},
      {"edge_methods", {to_string(left.method), to_string(right.method)}},
      {"p_max", n.p_max},
      {"x_p_max", n.x_p_max},
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
  json effects_run = {"normal"};
  json timings = {{"total", result.timings.total}, {"normal", result.timings.normal}};
  json cycle;
  if (result.cycle) {
    const CycleStage& st = *result.cycle;
    const CycleResult& c = st.result;
    effects_run.push_back("tangential");
    timings["tangential"] = *result.timings.tangential;
    auto interval = [](const std::optional<Interval>& i) { return i ? json{i->first, i->second} : json(nullptr); };
    json stick_zones = json::array();
    for (const auto& z : c.stick_zones) stick_zones.push_back({z.first, z.second});
    const bool slips = !c.slip_range.empty();  // gross slip has fields only under displacement control
    cycle = {{"route", st.route},
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
    if (!st.p_top.empty()) {  // β ≠ 0: the shear moves the pressure
      cycle["p_max_top"] = *std::max_element(st.p_top.begin(), st.p_top.end());
      cycle["p_max_bottom"] = *std::max_element(st.p_bottom.begin(), st.p_bottom.end());
    }
    if (scene.control == LoadControl::displacement) {
      cycle["delta"] = *scene.delta;
      cycle["sliding_amplitude"] = c.sliding_amplitude;  // 0 short of gross slip
    }
  }
  json summary = {
      {"scene", scene.name},
      {"version", kVersion},
      {"status", result.wear && result.wear->interrupted ? "interrupted" : "completed"},
      {"effects_run", effects_run},
      {"materials", {{"A", pair.A()}, {"E_star", pair.E_star()}, {"alpha", pair.alpha()}, {"beta", pair.beta()}}},
      {"grid",
       {{"cells", n.grid.n}, {"window", {n.grid.x_min, n.grid.x_max}}, {"window_method", n.window.method},
        {"h", n.grid.h()}}},
      {"contact", contact},
      {"solver",
       {{"normal",
         {{"termination", to_string(n.summary.termination)},
          {"iterations", n.summary.iterations},
          {"residual", n.summary.residual},
          {"seconds", n.summary.seconds},
          {"brief", n.summary.brief()}}}}},
      {"timings", timings},
  };
  if (result.cycle) summary["cycle"] = cycle;
  summary["warnings"] = json::array();
  for (const Warning& w : result.warnings) summary["warnings"].push_back({{"code", w.code}, {"message", w.message}});
  if (!result.stress_maps.empty()) {
    summary["effects_run"].push_back("stress");
    summary["timings"]["stress"] = *result.timings.stress;
    json phases = json::object();
    for (const StressMap& m : result.stress_maps) {
      double vm = 0.0, vm_x = 0.0, vm_y = 0.0;
      for (std::size_t j = 0; j < m.y.size(); ++j)
        for (std::size_t i = 0; i < m.x.size(); ++i) {
          const double v = von_mises(m.sigma[j * m.x.size() + i], scene.specimen.nu);
          if (v > vm) vm = v, vm_x = m.x[i], vm_y = m.y[j];
        }
      phases[m.phase] = {{"surface_sxx_trailing_peak", m.trailing_peak},
                         {"surface_sxx_trailing_peak_x", m.trailing_peak_x},
                         {"von_mises_max", vm},
                         {"von_mises_max_at", {vm_x, vm_y}}};
    }
    summary["stress"] = {{"phases", phases},
                         {"cycles", result.wear ? result.wear->records.back().cycles : 0.0},
                         {"window", {result.stress_maps.front().x.front(), result.stress_maps.front().x.back()}},
                         {"depth", result.stress_maps.front().y.back()}};
    if (result.fatigue) add_fatigue_summary(summary["stress"], *result.fatigue);
  }
  if (!result.sifs.empty()) {
    summary["effects_run"].push_back("crack");
    summary["timings"]["crack"] = *result.timings.crack;
    const double last_cycles = result.sifs.back().cycles;
    auto column = [&](const std::string& phase, auto member) {
      json v = json::array();
      for (const SifSet& set : result.sifs)
        if (set.cycles == last_cycles && set.phase == phase)
          for (const CrackSif& k : set.result.sifs) v.push_back(member(k));
      return v;
    };
    const std::string hi = scene.tangential ? "top" : "loaded", lo = scene.tangential ? "bottom" : "loaded";
    const CrackEffect& c = *scene.crack;
    summary["crack"] = {
        {"at", c.at == "x" ? json(c.x) : json(c.at)},
        {"x", result.crack_x},
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
  if (scene.tangential_implied) summary["effects_implied"] = {{"tangential", "needed by wear"}};
  if (result.wear) {
    const WearStage& w = *result.wear;
    const WearEffect& e = *scene.wear;
    summary["effects_run"].push_back("wear");
    summary["timings"]["wear"] = *result.timings.wear;
    auto interval = [](const std::optional<Interval>& i) { return i ? json{i->first, i->second} : json(nullptr); };
    const WearRecord& last = w.records.back();
    summary["wear"] = {
        {"law", e.law},
        {"coefficient", e.coefficient},
        {"rate_coefficient", w.rate_coefficient},
        {"pad_fraction", e.pad_fraction},
        {"stepper", e.stepper},
        {"tolerance", e.tolerance},
        {"cycles", last.cycles},
        {"worn_area", last.worn_area},
        {"max_depth", last.max_depth},
        {"fraction_of_asymptote", w.asymptote.unavailable.empty() ? json(last.fraction) : json(nullptr)},
        {"stick_zone_initial", interval(w.records.front().stick_zone)},
        {"stick_zone_final", interval(last.stick_zone)},
        {"contact_final", {last.contact.first, last.contact.second}},
        {"steps", w.steps},
        {"rejected_steps", w.rejected_steps},
        {"implicit_solves", w.implicit_solves},
        {"cycle_solves", w.responses},
        {"mean_iterations_cycle", w.mean_iterations_cycle},
        {"mean_iterations_implicit", w.mean_iterations_implicit},
        {"explicit_stability_limit", w.stability_limit},
        {"records", w.records.size()},
        {"asymptote",
         {{"worn_area", w.asymptote.worn_area},
          {"max_depth", w.asymptote.max_depth},
          {"x_max_depth", w.asymptote.x_max_depth},
          {"extent", {w.asymptote.extent.first, w.asymptote.extent.second}}}}};
    // Where the run got to (the last record is wear.cycles); an interrupted run stops short of cycles_target.
    // The cycle's route on the worn profile; without an asymptote (displacement control), null and the reason.
    summary["wear"]["route"] = w.route;
    summary["wear"]["Q_max_initial"] = w.records.front().Q_max;
    summary["wear"]["Q_max_final"] = last.Q_max;
    if (!w.asymptote.unavailable.empty()) {
      summary["wear"]["asymptote"] = nullptr;
      summary["wear"]["asymptote_note"] = w.asymptote.unavailable;
    }
    summary["wear"]["cycles_target"] = e.cycles;
    summary["wear"]["cycles_reached"] = w.cycles_reached;
    if (w.resumed_from) summary["wear"]["resumed_from"] = *w.resumed_from;
    if (e.stepper == "explicit") {  // the cap on ΔN below the stability limit, and the longest step taken (cycles)
      summary["wear"]["explicit_step_cap"] = w.explicit_step_cap;
      summary["wear"]["explicit_max_step"] = w.explicit_max_step;
    }
  }
  return summary;
}

}  // namespace fretwear
