#include "engine/wear_stage.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <boost/numeric/odeint/integrate/integrate_times.hpp>
#include <fmt/format.h>

#include "contact/contact_zones.hpp"
#include "contact/error.hpp"
#include "contact/half_plane_kernel.hpp"
#include "engine/simulation.hpp"
#include "wear/wear_law.hpp"

namespace fretwear {

AnalogyContactResponse::AnalogyContactResponse(const Scene& scene, const Model& model)
    : scene_(scene), model_(model), solver_(*model.kernel) {
  const double f = *scene.friction;
  const double bulk_strain =
      scene.bulk_stress * (model.pair.kappa_specimen() + 1.0) / (8.0 * model.pair.mu_specimen());
  tilt_ = bulk_strain / f;
  corrective_load_ = scene.P - scene.Q_max() / f;
  if (!(corrective_load_ > 0.0))
    throw UnsupportedError(fmt::format("effects.wear: Q = {:.6g} N/m reaches f P: the bodies slide, and wear in gross "
                                       "slip needs displacement control, which is not supported yet",
                                       scene.Q_max()));
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
  check(solver_.solve(gap_, scene_.P, normal_), "normal");
  for (int i = 0; i < n; ++i) gap_[i] -= tilt_ * grid.x(i);
  check(solver_.solve(gap_, corrective_load_, corrective_), "corrective");
  const double f = *scene_.friction;
  out.p = normal_.p;
  out.s.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    if (corrective_.p[i] > 0.0 && !(normal_.p[i] > 0.0))
      throw UnsupportedError(fmt::format("effects.wear: the worn contact slips backwards at its leading edge (reverse "
                                         "slip at x = {:.6g} m), which needs the incremental route, not supported yet",
                                         grid.x(i)));
    if (normal_.p[i] > 0.0 && !(corrective_.p[i] > 0.0)) out.s[i] = 4.0 * f * std::max(corrective_.gap[i], 0.0);
  }
  const auto zones = locate_zones(grid, corrective_.p, model_.g0);
  out.has_stick = !zones.empty();
  if (out.has_stick) out.stick_left = zones.front().left.x, out.stick_right = zones.back().right.x;
}

void AnalogyContactResponse::implicit_pressure(std::span<const double> w, std::span<const double> d,
                                               std::vector<double>& p) {
  const int n = model_.grid.n;
  gap_.resize(n);
  for (int i = 0; i < n; ++i) gap_[i] = model_.g0[i] + w[i];
  implicit_.p = p;
  const SolveSummary s = solver_.solve(gap_, scene_.P, implicit_, d);
  ++implicit_solves;
  implicit_iterations += s.iterations;
  if (!s.converged())
    throw ConvergenceError(fmt::format("wear: the contact-implicit solve stopped ({}) with residual {:.3g}",
                                       to_string(s.termination), s.residual));
  p = implicit_.p;
}

WearAsymptote wear_asymptote(const Scene& scene, const Model& model, const NormalResult& normal) {
  // The stick zone of the first cycle, located to sub-cell accuracy.
  AnalogyContactResponse contact(scene, model);
  wear::CycleResponse first;
  contact.respond(std::vector<double>(model.grid.n, 0.0), first);
  (void)normal;
  WearAsymptote a;
  const Grid& grid = model.grid;
  const int n = grid.n;
  a.w.assign(n, 0.0);
  a.p.assign(n, 0.0);
  if (!first.has_stick) return a;
  // The limit is a complete contact over [c_l, c_r]: on a grid whose cell boundaries fall on c_l and c_r, its
  // corners are exact, as for a sharp punch (whole cells of the contact grid would misplace them by up to h/2).
  const double cl = first.stick_left, cr = first.stick_right;
  const double h = (cr - cl) / std::max(1.0, std::round((cr - cl) / grid.h()));
  const double lo = cl - std::round((cl - grid.x_min) / h) * h;
  const Grid aligned{lo, lo + n * h, n};
  const HalfPlaneKernel kernel(aligned, model.pair.A());
  std::vector<double> g0(n), g(n);
  for (int i = 0; i < n; ++i) {
    g0[i] = model.profile.gap(aligned.x(i));
    g[i] = aligned.x(i) > cl && aligned.x(i) < cr ? g0[i] : std::numeric_limits<double>::infinity();
  }
  ContactState state;
  const NormalSolver solver(kernel);
  const SolveSummary s = solver.solve(g, scene.P, state);
  if (!s.converged())
    throw ConvergenceError(fmt::format("wear: the asymptotic complete-contact solve stopped ({}) with residual {:.3g}",
                                       to_string(s.termination), s.residual));
  std::vector<double> u(n), w(n, 0.0);
  kernel.apply(state.p, u);
  a.extent = {aligned.x_max, aligned.x_min};
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(g[i]) || !std::isfinite(g0[i])) continue;
    const double overlap = -(g0[i] + u[i] - state.approach);
    if (overlap <= 0.0) continue;
    w[i] = overlap;
    a.worn_area += overlap * h;
    if (overlap > a.max_depth) a.max_depth = overlap, a.x_max_depth = aligned.x(i);
    a.extent = {std::min(a.extent.first, aligned.left(i)), std::max(a.extent.second, aligned.left(i + 1))};
  }
  // On the contact grid (the grids differ by less than a cell): linear interpolation between aligned centres.
  auto on_aligned = [&](const std::vector<double>& v, double x) {
    const double t = (x - aligned.x_min) / h - 0.5;
    const int i = std::clamp(int(std::floor(t)), 0, n - 2);
    const double f = std::clamp(t - i, 0.0, 1.0);
    return (1.0 - f) * v[i] + f * v[i + 1];
  };
  for (int i = 0; i < n; ++i) {
    a.w[i] = on_aligned(w, grid.x(i));
    a.p[i] = grid.x(i) > cl && grid.x(i) < cr ? on_aligned(state.p, grid.x(i)) : 0.0;
  }
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

WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal) {
  const WearEffect& effect = *scene.wear;
  wear::WearLaw law{wear::law_from_string(effect.law), effect.coefficient, *scene.friction, effect.pad_fraction};
  WearStage stage;
  stage.rate_coefficient = law.rate_coefficient();
  stage.asymptote = wear_asymptote(scene, model, normal);

  AnalogyContactResponse contact(scene, model);
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
    rec.q.resize(n);  // the shear at the top of the cycle, q = f (p − p*) (analogy route)
    for (int i = 0; i < n; ++i) rec.q[i] = *scene.friction * (r.p[i] - contact.corrective_pressure()[i]);
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
  if (rate_max == 0.0) {  // nothing slips: nothing wears
    for (double t : times) record(w, t);
    return stage;
  }
  namespace odeint = boost::numeric::odeint;
  if (effect.stepper == "explicit") {
    // abs: the tolerance on the scale of the depth the run wears toward, as the implicit stepper's max-norm.
    const double depth = stage.asymptote.max_depth > 0.0 ? stage.asymptote.max_depth : rate_max * effect.cycles;
    stage.explicit_step_cap = kExplicitCapFraction * stage.stability_limit;
    wear::ExplicitWearStepper stepper(effect.tolerance * depth, effect.tolerance, stage.explicit_step_cap);
    wear::WearRateSystem rate(contact, stage.rate_coefficient);
    const double dN = std::min(stage.explicit_step_cap, std::max(1.0, effect.tolerance * depth / rate_max));
    odeint::integrate_times(std::ref(stepper), std::ref(rate), w, times.begin(), times.end(), dN, record);
    stage.steps = stepper.stats().accepted;
    stage.rejected_steps = stepper.stats().rejected;
    stage.explicit_max_step = stepper.stats().max_step;
    stage.responses = int(rate.evaluations());
  } else if (effect.stepper == "cycle_by_cycle") {
    if (!(stage.stability_limit > wear::kCycle))
      throw UnsupportedError(fmt::format(
          "effects.wear.stepper: \"cycle_by_cycle\" wears one cycle at a time, an explicit jump of one cycle, which "
          "is unstable here: the explicit stability limit 1.5 Δx/(E* c s_max) is {:.3g} cycles. Use \"implicit\", "
          "or coarser cells or a smaller wear coefficient",
          stage.stability_limit));
    wear::WearRateSystem rate(contact, stage.rate_coefficient);
    stage.steps = int(odeint::integrate_times(wear::CycleByCycleStepper(), std::ref(rate), w, times.begin(),
                                              times.end(), wear::kCycle, record));
    stage.responses = int(rate.evaluations());
  } else {
    // First jump: a small share of the asymptote's depth at the initial rate, bounded by the first record.
    double dN = std::max(1.0, effect.tolerance * stage.asymptote.max_depth / rate_max);
    wear::ImplicitWearStepper stepper(stage.rate_coefficient, effect.tolerance);
    odeint::integrate_times(std::ref(stepper), wear::ResponseRef{&contact}, w, times.begin(), times.end(), dN,
                            record);
    stage.steps = stepper.stats().accepted;
    stage.rejected_steps = stepper.stats().rejected;
    stage.implicit_solves = stepper.stats().implicit_solves;
    stage.responses = stepper.stats().responses;
  }
  stage.mean_iterations_cycle = double(contact.cycle_iterations) / double(std::max(1L, contact.cycle_solves));
  stage.mean_iterations_implicit = double(contact.implicit_iterations) / double(std::max(1L, contact.implicit_solves));
  return stage;
}

}  // namespace fretwear
