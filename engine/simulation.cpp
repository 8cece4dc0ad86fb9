#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/fatigue_stage.hpp"
#include "engine/version.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
    result.wear = std::make_shared<WearStage>(run_wear(scene_, model, result.normal, *result.cycle, control ? *control : WearControl{}));
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
      result.crack_x = c.at == CrackPosition::trailing_edge ? n.zones.front().left.x
                       : c.at == CrackPosition::leading_edge ? n.zones.back().right.x
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
        {"at", c.at == CrackPosition::x ? json(c.x) : json(to_string(c.at))},
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
