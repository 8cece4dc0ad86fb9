#include "engine/wear_stage.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include <fmt/format.h>

#include "common/error.hpp"
#include "engine/checkpoint.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"
#include "engine/wear_driver.hpp"
#include "wear/implicit_stepper.hpp"
#include "wear/reference_steppers.hpp"
#include "wear/wear_law.hpp"

namespace fretwear {

using nlohmann::json;

WearAsymptote wear_asymptote(const Scene& scene, const Model& model, const NormalResult& /*normal*/) {
  WearAsymptote a;
  if (scene.control == LoadControl::displacement) {
    a.unavailable = "under displacement control Q_max follows the prescribed displacement as the contact wears, so the "
                    "stick zone is not the initial one: paper 002's asymptote (complete contact over the initial "
                    "stick zone under a fixed Q) does not apply. In partial slip the wear still stops, at a complete "
                    "contact over a stick zone whose Q is the one the displacement gives (not computed); in gross "
                    "slip there is no stick zone and the wear never stops";
    return a;
  }
  // The stick zones of the first cycle, located to sub-cell accuracy (one per run of the corrective contact).
  AnalogyContactResponse contact(scene, model);
  wear::CycleResponse first;
  try {
    contact.respond(std::vector<double>(std::size_t(model.grid.n), 0.0), first);
  } catch (const UnsupportedError& e) {  // reverse slip: the incremental route wears it, with no asymptote here
    a.unavailable = std::string("the analogy route cannot give the initial stick zone: ") + e.what();
    return a;
  }
  static_cast<WearLimit&>(a) = wear_limit(model.profile, model.pair.A(), model.grid, scene.P, contact.stick_zones());
  return a;
}

namespace {

// Record times: the scene's list, or `count` log-spaced from cycles/10⁴ (at least 1) to cycles; always 0 first.
std::vector<double> record_times(const WearEffect& w) {
  std::vector<double> t{0.0};
  if (!w.record.empty()) {
    t.insert(t.end(), w.record.begin(), w.record.end());
  } else {
    const double first = std::max(1.0, w.cycles * 1e-4);
    const int k = w.record_count;
    for (int i = 0; i < k; ++i) {
      const double x = k == 1 ? w.cycles : first * std::pow(w.cycles / first, double(i) / (k - 1));
      const double rounded = std::round(x);
      if (rounded > t.back()) t.push_back(std::min(rounded, w.cycles));
    }
  }
  if (t.back() < w.cycles) t.push_back(w.cycles);
  return t;
}

}  // namespace

std::string cycle_by_cycle_problem(double stability_limit) {
  if (stability_limit > wear::kCycle || stability_limit == 0.0) return {};
  return fmt::format("effects.wear.stepper: \"cycle_by_cycle\" wears one cycle at a time, an explicit jump of one "
                     "cycle, which is unstable here: the explicit stability limit 1.5 Δx/(E* c s_max) is {:.3g} "
                     "cycles. Use \"implicit\", or coarser cells or a smaller wear coefficient",
                     stability_limit);
}

WearEstimate estimate_wear(const Scene& scene, const Model& model, const NormalResult& normal) {
  const WearEffect& effect = *scene.wear;
  const wear::WearLaw law{wear::law_from_string(effect.law), effect.coefficient, *scene.friction,
                          effect.pad_fraction};
  std::unique_ptr<WearContact> contact = make_wear_contact(scene, model, normal);
  const std::vector<double> w(model.grid.n, 0.0);
  wear::CycleResponse response;
  contact->respond(w, response);  // cold: the first cycle's solves start from nothing
  const auto t0 = std::chrono::steady_clock::now();
  contact->respond(w, response);  // warm-started, as the run's are
  WearEstimate e;
  e.seconds_per_response = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double s_max = 0.0;
  for (double s : response.s) s_max = std::max(s_max, s);
  if (s_max == 0.0) return e;  // nothing slips: nothing wears
  e.stability_limit = wear::explicit_stability_limit(model.grid.h(), model.pair.E_star(), law.rate_coefficient(), s_max);
  if (effect.stepper == "cycle_by_cycle") {
    e.responses = effect.cycles;
  } else if (effect.stepper == "explicit") {  // Dormand–Prince: six new stages a step, steps at the cap
    e.responses = 6.0 * std::ceil(effect.cycles / (kExplicitCapFraction * e.stability_limit));
  }
  return e;
}

WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal, const WearControl& control) {
  const WearEffect& effect = *scene.wear;
  wear::WearLaw law{wear::law_from_string(effect.law), effect.coefficient, *scene.friction, effect.pad_fraction};
  WearStage stage;
  stage.rate_coefficient = law.rate_coefficient();
  stage.asymptote = wear_asymptote(scene, model, normal);

  std::unique_ptr<WearContact> chosen = make_wear_contact(scene, model, normal);
  stage.route = wear_uses_incremental(scene) ? "incremental" : "analogy";
  WearContact& contact = *chosen;
  const int n = model.grid.n;
  const double h = model.grid.h();
  std::vector<double> w(n, 0.0);
  wear::CycleResponse response;
  contact.respond(w, response);
  double rate_max = 0.0, s_max = 0.0;
  for (int i = 0; i < n; ++i) {
    rate_max = std::max(rate_max, stage.rate_coefficient * response.p[i] * response.s[i]);
    s_max = std::max(s_max, response.s[i]);
  }
  stage.stability_limit = wear::explicit_stability_limit(h, model.pair.E_star(), stage.rate_coefficient, s_max);

  auto record = [&](const std::vector<double>& state, double cycles) {
    wear::CycleResponse r;
    contact.respond(state, r);
    WearRecord rec;
    rec.cycles = cycles;
    rec.w = state;
    rec.p = r.p;
    rec.s = r.s;
    rec.q = contact.shear_top();
    rec.Q_max = contact.Q_top();
    for (int i = 0; i < n; ++i) {
      rec.worn_area += state[i] * h;
      rec.max_depth = std::max(rec.max_depth, state[i]);
      rec.p_max = std::max(rec.p_max, r.p[i]);
    }
    if (r.has_stick) rec.stick_zone = Interval{r.stick_left, r.stick_right};
    std::vector<double> g0w(n);
    for (int i = 0; i < n; ++i) g0w[i] = model.g0[i] + state[i];
    const auto zones = locate_zones(model.grid, r.p, g0w);
    if (!zones.empty()) rec.contact = {zones.front().left.x, zones.back().right.x};
    rec.fraction = stage.asymptote.worn_area > 0.0 ? rec.worn_area / stage.asymptote.worn_area : 0.0;
    stage.records.push_back(std::move(rec));
  };

  const std::vector<double> times = record_times(effect);
  stage.cycles_reached = times.back();
  if (rate_max == 0.0) {  // nothing slips: nothing wears
    for (double t : times) record(w, t);
    return stage;
  }

  // Drives `stepper` from the start or from control.resume; save/restore carry the stepper's own state.
  auto drive = [&](auto& stepper, auto system, double dN, auto save, auto restore) {
    DriveState s{times.front(), dN, 0, 0};
    if (control.resume) {
      const json& j = *control.resume;
      s = resume_wear(j, scene, w, stage.records);
      contact.restore(j.at("contact"));
      restore(j.at("stepper_state"));
      stage.resumed_from = s.N;
    }
    using clock = std::chrono::steady_clock;
    auto last_checkpoint = clock::now();
    auto boundary = [&](const DriveState& st, bool recorded) {
      if (control.progress) {
        double area = 0.0;
        for (double wi : w) area += wi * h;
        control.progress({st.N, times.back(), st.dt,
                          stage.asymptote.worn_area > 0.0 ? area / stage.asymptote.worn_area : 0.0, int(st.steps)});
      }
      const bool stop = control.stop_requested && control.stop_requested();
      const bool due = std::chrono::duration<double>(clock::now() - last_checkpoint).count() >=
                       control.checkpoint_interval;
      if (!control.checkpoint.empty() && (recorded || stop || due)) {
        write_checkpoint(control.checkpoint, wear_checkpoint(scene, control.scene_hash, st, times.back(), w,
                                                             stage.records, contact.save(), save()));
        last_checkpoint = clock::now();
      }
      return !stop;
    };
    stage.interrupted = !drive_times(stepper, system, w, times, s, record, boundary);
    stage.cycles_reached = s.N;
    return s;
  };

  if (effect.stepper == "explicit") {
    // abs: the tolerance on the scale of the depth the run wears toward, as the implicit stepper's max-norm.
    const double depth = stage.asymptote.max_depth > 0.0 ? stage.asymptote.max_depth : rate_max * effect.cycles;
    stage.explicit_step_cap = kExplicitCapFraction * stage.stability_limit;
    wear::ExplicitWearStepper stepper(effect.tolerance * depth, effect.tolerance, stage.explicit_step_cap);
    wear::WearRateSystem rate(contact, stage.rate_coefficient);
    const double dN = std::min(stage.explicit_step_cap, std::max(1.0, effect.tolerance * depth / rate_max));
    drive(
        stepper, std::ref(rate), dN, [&] { return save_explicit(stepper, rate); },
        [&](const json& j) { restore_explicit(j, stepper, rate, w); });
    stage.steps = stepper.stats().accepted;
    stage.rejected_steps = stepper.stats().rejected;
    stage.explicit_max_step = stepper.stats().max_step;
    stage.responses = int(rate.evaluations());
  } else if (effect.stepper == "cycle_by_cycle") {
    if (const std::string problem = cycle_by_cycle_problem(stage.stability_limit); !problem.empty())
      throw UnsupportedError(problem);
    wear::WearRateSystem rate(contact, stage.rate_coefficient);
    AlwaysAccepted<wear::CycleByCycleStepper> stepper;
    const DriveState s = drive(
        stepper, std::ref(rate), wear::kCycle, [&] { return save_cycle_by_cycle(rate); },
        [&](const json& j) { restore_cycle_by_cycle(j, rate); });
    stage.steps = int(s.steps);
    stage.responses = int(rate.evaluations());
  } else {
    // First jump: a small share of the asymptote's depth at the initial rate, bounded by the first record.
    const double dN = std::max(1.0, effect.tolerance * stage.asymptote.max_depth / rate_max);
    wear::ImplicitWearStepper stepper(stage.rate_coefficient, effect.tolerance);
    try {
    drive(
        stepper, wear::ResponseRef{&contact}, dN, [&] { return save_implicit(stepper); },
        [&](const json& j) { restore_implicit(j, stepper); });
    } catch (const wear::ImplicitSolveFailure& e) {
      const SolveSummary& last = contact.last_unconverged;
      throw ConvergenceError(fmt::format("{} ({}, residual {:.3g})", e.what(), to_string(last.termination),
                                         last.residual));
    }
    stage.steps = stepper.stats().accepted;
    stage.unconverged_steps = stepper.stats().unconverged;
    stage.rejected_steps = stepper.stats().rejected;
    stage.implicit_solves = stepper.stats().implicit_solves;
    stage.responses = stepper.stats().responses;
  }
  stage.mean_iterations_cycle = double(contact.cycle_iterations) / double(std::max(1L, contact.cycle_solves));
  stage.mean_iterations_implicit = double(contact.implicit_iterations) / double(std::max(1L, contact.implicit_solves));
  return stage;
}

}  // namespace fretwear
