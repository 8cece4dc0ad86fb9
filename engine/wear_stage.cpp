#include "engine/wear_stage.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include <fmt/format.h>

#include "contact/contact_zones.hpp"
#include "common/error.hpp"
#include "engine/checkpoint.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_driver.hpp"
#include "wear/wear_law.hpp"

namespace fretwear {

using nlohmann::json;

bool WearContact::solve_implicit(const NormalSolver& solver, const Model& model, double P,
                                 std::span<const double> w, std::span<const double> d, std::vector<double>& p) {
  const int n = model.grid.n;
  gap_.resize(n);
  for (int i = 0; i < n; ++i) gap_[i] = model.g0[i] + w[i];
  implicit_.p = p;
  const SolveSummary s = solver.solve(gap_, P, implicit_, d);
  ++implicit_solves;
  implicit_iterations += s.iterations;
  if (!s.converged()) {
    last_unconverged = s;
    return false;
  }
  p = implicit_.p;
  return true;
}

AnalogyContactResponse::AnalogyContactResponse(const Scene& scene, const Model& model)
    : scene_(scene), model_(model), solver_(*model.kernel, worn_options()), implicit_solver_(*model.kernel, implicit_options(model.grid.n)) {
  const double f = *scene.friction;
  tilt_ = model.pair.bulk_strain(scene.bulk_stress) / f;
  corrective_load_ = scene.P - scene.Q_max() / f;
  if (!(corrective_load_ > 0.0))
    throw UnsupportedError(fmt::format("effects.wear: Q = {:.6g} N/m reaches f P = {:.6g} N/m: the bodies slide, and "
                                       "under force control the slip, hence the wear, is not determined; prescribe "
                                       "the displacement instead (load.control \"displacement\" with load.delta)",
                                       scene.Q_max(), f * scene.P));
}

int AnalogyContactResponse::cells() const { return model_.grid.n; }
double AnalogyContactResponse::cell_width() const { return model_.grid.h(); }

void AnalogyContactResponse::respond(std::span<const double> w, wear::CycleResponse& out) {
  const Grid& grid = model_.grid;
  const int n = grid.n;
  gap_.resize(n);
  for (int i = 0; i < n; ++i) gap_[i] = model_.g0[i] + w[i];
  auto check = [this](const SolveSummary& s, const char* what) {
    ++cycle_solves;
    cycle_iterations += s.iterations;
    if (!s.converged())
      throw ConvergenceError(fmt::format("wear: the {} solve on the worn profile stopped ({}) with residual {:.3g}",
                                         what, to_string(s.termination), s.residual));
  };
  if (int(out.p.size()) == n) normal_.p = out.p;
  check(solver_.solve(gap_, scene_.P, normal_), "normal");
  for (int i = 0; i < n; ++i) gap_[i] -= tilt_ * grid.x(i);
  check(solver_.solve(gap_, corrective_load_, corrective_), "corrective");
  const double f = *scene_.friction;
  out.p = normal_.p;
  out.s.assign(n, 0.0);
  q_top_.resize(n);  // q = f (p − p*) at the top of the cycle
  for (int i = 0; i < n; ++i) {
    if (corrective_.p[i] > 0.0 && !(normal_.p[i] > 0.0))
      throw UnsupportedError(fmt::format("effects.wear: the worn contact slips backwards at its leading edge (reverse "
                                         "slip at x = {:.6g} m), which the analogy route cannot follow; set "
                                         "effects.tangential.route to \"incremental\"",
                                         grid.x(i)));
    if (normal_.p[i] > 0.0 && !(corrective_.p[i] > 0.0)) out.s[i] = 4.0 * f * std::max(corrective_.gap[i], 0.0);
    q_top_[i] = f * (normal_.p[i] - corrective_.p[i]);
  }
  stick_zones_ = locate_zones(grid, corrective_.p, model_.g0);
  out.has_stick = !stick_zones_.empty();
  if (out.has_stick) out.stick_left = stick_zones_.front().left.x, out.stick_right = stick_zones_.back().right.x;
}

bool AnalogyContactResponse::implicit_pressure(std::span<const double> w, std::span<const double> d,
                                               std::vector<double>& p) {
  return solve_implicit(implicit_solver_, model_, scene_.P, w, d, p);
}

bool wear_uses_incremental(const Scene& scene) {
  return scene.control == LoadControl::displacement ||
         (scene.tangential && scene.tangential->route == TangentialRoute::incremental);
}

namespace {

IncrementalSlipOptions incremental_options(const Scene& scene) {
  IncrementalSlipOptions o;
  o.increments_per_cycle = scene.tangential->increments;
  return o;
}

CyclicLoad incremental_load(const Scene& scene, const Model& model) {
  const double strain = model.pair.bulk_strain(scene.bulk_stress);
  const bool displacement = scene.control == LoadControl::displacement;
  return {scene.P, displacement ? 0.0 : scene.Q_max(), *scene.friction, strain, displacement ? *scene.delta : 0.0};
}

}  // namespace

IncrementalContactResponse::IncrementalContactResponse(const Scene& scene, const Model& model, double reference_x,
                                                       double reference_depth)
    : scene_(scene),
      model_(model),
      solver_(*model.kernel, worn_options()),
      implicit_solver_(*model.kernel, implicit_options(model.grid.n)),
      slip_(*model.kernel, incremental_options(scene)),
      datum_(model.grid, model.pair, reference_x, reference_depth),
      load_(incremental_load(scene, model)) {
  if (!scene.history.empty())
    throw UnsupportedError("effects.wear: load.history with wear is not supported: the wear stage needs one cycle "
                           "repeated between fixed limits of Q or of the displacement");
  if (scene.control == LoadControl::force && !(scene.Q_max() < *scene.friction * scene.P))
    throw UnsupportedError(fmt::format("effects.wear: Q = {:.6g} N/m reaches f P = {:.6g} N/m: the bodies slide, and "
                                       "under force control the slip, hence the wear, is not determined; prescribe "
                                       "the displacement instead (load.control \"displacement\" with load.delta)",
                                       scene.Q_max(), *scene.friction * scene.P));
}

int IncrementalContactResponse::cells() const { return model_.grid.n; }
double IncrementalContactResponse::cell_width() const { return model_.grid.h(); }

void IncrementalContactResponse::respond(std::span<const double> w, wear::CycleResponse& out) {
  const Grid& grid = model_.grid;
  const int n = grid.n;
  gap_.resize(n);
  for (int i = 0; i < n; ++i) gap_[i] = model_.g0[i] + w[i];
  if (int(out.p.size()) == n) normal_.p = out.p;
  const SolveSummary s = solver_.solve(gap_, scene_.P, normal_);
  ++cycle_solves;
  cycle_iterations += s.iterations;
  if (!s.converged())
    throw ConvergenceError(fmt::format("wear: the normal solve on the worn profile stopped ({}) with residual {:.3g}",
                                       to_string(s.termination), s.residual));
  if (normal_.p.front() > 0.0 || normal_.p.back() > 0.0)
    throw InputError(fmt::format("grid.window: the worn contact reaches the window's {} end (x = {:.6g} m); the "
                                 "contact widens as it wears (in gross slip without limit): widen grid.window, or "
                                 "wear fewer cycles",
                                 normal_.p.front() > 0.0 ? "left" : "right",
                                 normal_.p.front() > 0.0 ? grid.x_min : grid.x_max));
  const IncrementalResult r = slip_.solve(normal_, load_, &datum_);
  cycle_solves += r.n_increments;
  cycle_iterations += r.n_iterations;
  cycle_ = r.cycles.back();
  if (cycle_.slip_travelled.empty())  // force control at Q ≥ f P: refused by the constructor
    throw UnsupportedError("effects.wear: " + cycle_.message);
  out.p = normal_.p;
  out.s = cycle_.slip_travelled;
  for (int i = 0; i < n; ++i)
    if (!(normal_.p[i] > 0.0)) out.s[i] = 0.0;
  out.has_stick = cycle_.stick_zone.has_value();
  out.stick_left = out.stick_right = 0.0;
  if (out.has_stick) out.stick_left = cycle_.stick_zone->first, out.stick_right = cycle_.stick_zone->second;
}

bool IncrementalContactResponse::implicit_pressure(std::span<const double> w, std::span<const double> d,
                                                   std::vector<double>& p) {
  return solve_implicit(implicit_solver_, model_, scene_.P, w, d, p);
}

json AnalogyContactResponse::save() const {
  return {{"normal", contact_state_json(normal_)},
          {"corrective", contact_state_json(corrective_)},
          {"implicit", contact_state_json(implicit_)},
          {"cycle_solves", cycle_solves},
          {"cycle_iterations", cycle_iterations},
          {"implicit_solves", implicit_solves},
          {"implicit_iterations", implicit_iterations}};
}

void AnalogyContactResponse::restore(const json& j) {
  contact_state_from(j.at("normal"), normal_);
  contact_state_from(j.at("corrective"), corrective_);
  contact_state_from(j.at("implicit"), implicit_);
  cycle_solves = j.at("cycle_solves").get<long>();
  cycle_iterations = j.at("cycle_iterations").get<long>();
  implicit_solves = j.at("implicit_solves").get<long>();
  implicit_iterations = j.at("implicit_iterations").get<long>();
}

json IncrementalContactResponse::save() const {
  return {{"route", "incremental"},
          {"normal", contact_state_json(normal_)},
          {"implicit", contact_state_json(implicit_)},
          {"cycle_solves", cycle_solves},
          {"cycle_iterations", cycle_iterations},
          {"implicit_solves", implicit_solves},
          {"implicit_iterations", implicit_iterations}};
}

void IncrementalContactResponse::restore(const json& j) {
  if (j.value("route", "") != "incremental") throw InputError("checkpoint: written by the analogy route's wear run");
  contact_state_from(j.at("normal"), normal_);
  contact_state_from(j.at("implicit"), implicit_);
  cycle_solves = j.at("cycle_solves").get<long>();
  cycle_iterations = j.at("cycle_iterations").get<long>();
  implicit_solves = j.at("implicit_solves").get<long>();
  implicit_iterations = j.at("implicit_iterations").get<long>();
}

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

// The contact the wear stage sees: the incremental route under displacement control or when the scene asks for it,
// the analogy otherwise.
std::unique_ptr<WearContact> make_wear_contact(const Scene& scene, const Model& model, const NormalResult& normal) {
  if (!wear_uses_incremental(scene)) return std::make_unique<AnalogyContactResponse>(scene, model);
  // The datum of the cycle stage (engine/simulation.cpp, solve_cycle): the centre of the unworn contact, 10
  // half-widths (or grid.reference_depth) below it.
  const double x_left = normal.zones.front().left.x, x_right = normal.zones.back().right.x;
  const double depth = scene.reference_depth ? *scene.reference_depth : 5.0 * (x_right - x_left);
  return std::make_unique<IncrementalContactResponse>(scene, model, 0.5 * (x_left + x_right), depth);
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
