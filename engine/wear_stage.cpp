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
  } catch (const UnsupportedError&) {  // reverse slip: the incremental route wears it, with no asymptote here
    a.unavailable = "the first cycle slips backwards at the leading edge (reverse slip), where paper 002's limit, a "
                    "complete contact over a stick zone that stays where it started, is not established: not computed";
    return a;
  }
  static_cast<WearLimit&>(a) = wear_limit(model.profile, model.pair.A(), model.grid, scene.P, contact.stick_zones());
  return a;
}

std::string cycle_by_cycle_problem(double stability_limit) {
  if (stability_limit > wear::kCycle || stability_limit == 0.0) return {};
  return fmt::format("effects.wear.stepper: \"cycle_by_cycle\" wears one cycle at a time, an explicit jump of one "
                     "cycle, which is unstable here: the explicit stability limit 1.5 Δx/(E* c s_max) is {:.3g} "
                     "cycles. Use \"implicit\", or coarser cells or a smaller wear coefficient",
                     stability_limit);
}

WearEstimate estimate_wear(const Scene& scene, const Model& model, const CycleStage& cycle) {
  const WearEffect& effect = *scene.wear;
  const wear::WearLaw law{wear::law_from_string(effect.law), effect.coefficient, *scene.friction,
                          effect.pad_fraction};
  std::unique_ptr<WearContact> contact = make_wear_contact(scene, model, cycle);
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

namespace {

using nlohmann::json;

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

// One wear run under way: the worn state w on the contact, driven by a stepper through the record times, recorded
// into the stage, and steered by the control at every step boundary (progress, a stop, checkpoints).
class WearRun {
 public:
  WearRun(const Scene& scene, const Model& model, const WearControl& control, WearContact& contact, WearStage& stage)
      : scene_(scene),
        effect_(*scene.wear),
        model_(model),
        control_(control),
        contact_(contact),
        stage_(stage),
        times_(record_times(effect_)),
        w_(std::size_t(model.grid.n), 0.0) {
    stage_.cycles_reached = times_.back();  // until a stop says otherwise
  }

  // Nothing slips, nothing wears: every record is of the unworn contact.
  void record_unworn() {
    for (double t : times_) record(w_, t);
  }

  // The three steppers; rate_max = max c p s at the start (m/cycle) sets the first step.
  void drive_explicit(double rate_max);
  void drive_cycle_by_cycle();
  void drive_implicit(double rate_max);

 private:
  // The record of `state` at `cycles`: one response on it.
  void record(const std::vector<double>& state, double cycles);
  // Drives `stepper` from the start, or from control.resume (save/restore carry the stepper's own state, as
  // engine/checkpoint.hpp's schemas), to the last record or a stop; the stage learns where it stopped.
  template <class Stepper, class System, class Save, class Restore>
  DriveState drive(Stepper& stepper, System system, double dN, Save save, Restore restore);
  // At each step boundary: progress, the stop request, a checkpoint when one is due. False: stop.
  template <class Save>
  bool boundary(const DriveState& at, bool recorded, Save& save);

  using clock = std::chrono::steady_clock;
  const Scene& scene_;
  const WearEffect& effect_;
  const Model& model_;
  const WearControl& control_;
  WearContact& contact_;
  WearStage& stage_;
  const std::vector<double> times_;
  std::vector<double> w_;
  clock::time_point last_checkpoint_;
};

void WearRun::record(const std::vector<double>& state, double cycles) {
  const int n = model_.grid.n;
  const double h = model_.grid.h();
  wear::CycleResponse r;
  contact_.respond(state, r);
  WearRecord rec;
  rec.cycles = cycles;
  rec.w = state;
  rec.p = r.p;
  rec.s = r.s;
  rec.q = contact_.shear_top();
  rec.Q_max = contact_.Q_top();
  for (int i = 0; i < n; ++i) {
    rec.worn_area += state[i] * h;
    rec.max_depth = std::max(rec.max_depth, state[i]);
    rec.p_max = std::max(rec.p_max, r.p[i]);
  }
  if (r.has_stick) rec.stick_zone = Interval{r.stick_left, r.stick_right};
  std::vector<double> g0w(n);
  for (int i = 0; i < n; ++i) g0w[i] = model_.g0[i] + state[i];
  const auto zones = locate_zones(model_.grid, r.p, g0w);
  if (!zones.empty()) rec.contact = {zones.front().left.x, zones.back().right.x};
  rec.fraction = stage_.asymptote.worn_area > 0.0 ? rec.worn_area / stage_.asymptote.worn_area : 0.0;
  stage_.records.push_back(std::move(rec));
}

template <class Stepper, class System, class Save, class Restore>
DriveState WearRun::drive(Stepper& stepper, System system, double dN, Save save, Restore restore) {
  DriveState s{times_.front(), dN, 0, 0};
  if (control_.resume) {
    const json& j = *control_.resume;
    s = resume_wear(j, scene_, w_, stage_.records);
    contact_.restore(j.at("contact"));
    restore(j.at("stepper_state"));
    stage_.resumed_from = s.N;
  }
  last_checkpoint_ = clock::now();
  const bool completed = drive_times(
      stepper, system, w_, times_, s, [this](const std::vector<double>& state, double N) { record(state, N); },
      [this, &save](const DriveState& at, bool recorded) { return boundary(at, recorded, save); });
  stage_.interrupted = !completed;
  stage_.cycles_reached = s.N;
  return s;
}

template <class Save>
bool WearRun::boundary(const DriveState& at, bool recorded, Save& save) {
  const double h = model_.grid.h();
  double area = 0.0;
  for (double wi : w_) area += wi * h;
  const double fraction = stage_.asymptote.worn_area > 0.0 ? area / stage_.asymptote.worn_area : 0.0;
  const WearProgress progress{at.N, times_.back(), at.dt, fraction, int(at.steps)};
  if (control_.progress) control_.progress(progress);
  const bool stop = control_.stop_requested && control_.stop_requested(progress);
  const bool due =
      std::chrono::duration<double>(clock::now() - last_checkpoint_).count() >= control_.checkpoint_interval;
  if (!control_.checkpoint.empty() && (recorded || stop || due)) {
    write_checkpoint(control_.checkpoint, wear_checkpoint(scene_, control_.scene_hash, at, times_.back(), w_,
                                                          stage_.records, contact_.save(), save()));
    last_checkpoint_ = clock::now();
  }
  return !stop;
}

void WearRun::drive_explicit(double rate_max) {
  // abs: the tolerance on the scale of the depth the run wears toward, as the implicit stepper's max-norm.
  const double depth = stage_.asymptote.max_depth > 0.0 ? stage_.asymptote.max_depth : rate_max * effect_.cycles;
  stage_.explicit_step_cap = kExplicitCapFraction * stage_.stability_limit;
  wear::ExplicitWearStepper stepper(effect_.tolerance * depth, effect_.tolerance, stage_.explicit_step_cap);
  wear::WearRateSystem rate(contact_, stage_.rate_coefficient);
  const double dN = std::min(stage_.explicit_step_cap, std::max(1.0, effect_.tolerance * depth / rate_max));
  drive(
      stepper, std::ref(rate), dN, [&] { return save_explicit(stepper, rate); },
      [&](const json& j) { restore_explicit(j, stepper, rate, w_); });
  stage_.steps = stepper.stats().accepted;
  stage_.rejected_steps = stepper.stats().rejected;
  stage_.explicit_max_step = stepper.stats().max_step;
  stage_.responses = int(rate.evaluations());
}

void WearRun::drive_cycle_by_cycle() {
  if (const std::string problem = cycle_by_cycle_problem(stage_.stability_limit); !problem.empty())
    throw UnsupportedError(problem);
  wear::WearRateSystem rate(contact_, stage_.rate_coefficient);
  AlwaysAccepted<wear::CycleByCycleStepper> stepper;
  const DriveState s = drive(
      stepper, std::ref(rate), wear::kCycle, [&] { return save_cycle_by_cycle(rate); },
      [&](const json& j) { restore_cycle_by_cycle(j, rate); });
  stage_.steps = int(s.steps);
  stage_.responses = int(rate.evaluations());
}

void WearRun::drive_implicit(double rate_max) {
  // First jump: a small share of the asymptote's depth at the initial rate, bounded by the first record.
  const double dN = std::max(1.0, effect_.tolerance * stage_.asymptote.max_depth / rate_max);
  wear::ImplicitWearStepper stepper(stage_.rate_coefficient, effect_.tolerance);
  try {
    drive(
        stepper, wear::ResponseRef{&contact_}, dN, [&] { return save_implicit(stepper); },
        [&](const json& j) { restore_implicit(j, stepper); });
  } catch (const wear::ImplicitSolveFailure& e) {
    const SolveSummary& last = contact_.last_unconverged;
    throw ConvergenceError(fmt::format("{} ({}, residual {:.3g})", e.what(), to_string(last.termination),
                                       last.residual));
  }
  stage_.steps = stepper.stats().accepted;
  stage_.unconverged_steps = stepper.stats().unconverged;
  stage_.rejected_steps = stepper.stats().rejected;
  stage_.implicit_solves = stepper.stats().implicit_solves;
  stage_.responses = stepper.stats().responses;
}

}  // namespace

WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal, const CycleStage& cycle,
                   const WearControl& control) {
  const WearEffect& effect = *scene.wear;
  const wear::WearLaw law{wear::law_from_string(effect.law), effect.coefficient, *scene.friction,
                          effect.pad_fraction};
  WearStage stage;
  stage.rate_coefficient = law.rate_coefficient();
  stage.asymptote = wear_asymptote(scene, model, normal);

  const std::unique_ptr<WearContact> contact = make_wear_contact(scene, model, cycle);
  stage.route = to_string(cycle.ran);
  // The first response: the fastest wear, and the explicit stability limit.
  wear::CycleResponse first;
  contact->respond(std::vector<double>(std::size_t(model.grid.n), 0.0), first);
  double rate_max = 0.0, s_max = 0.0;
  for (int i = 0; i < model.grid.n; ++i) {
    rate_max = std::max(rate_max, stage.rate_coefficient * first.p[i] * first.s[i]);
    s_max = std::max(s_max, first.s[i]);
  }
  stage.stability_limit =
      wear::explicit_stability_limit(model.grid.h(), model.pair.E_star(), stage.rate_coefficient, s_max);

  WearRun run(scene, model, control, *contact, stage);
  if (rate_max == 0.0) {  // nothing slips: nothing wears
    run.record_unworn();
    return stage;
  }
  if (effect.stepper == "explicit")
    run.drive_explicit(rate_max);
  else if (effect.stepper == "cycle_by_cycle")
    run.drive_cycle_by_cycle();
  else
    run.drive_implicit(rate_max);
  stage.mean_iterations_cycle = double(contact->cycle_iterations) / double(std::max(1L, contact->cycle_solves));
  stage.mean_iterations_implicit =
      double(contact->implicit_iterations) / double(std::max(1L, contact->implicit_solves));
  return stage;
}

}  // namespace fretwear
